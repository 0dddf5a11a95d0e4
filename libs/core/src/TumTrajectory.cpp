#include <mrpt/math/CQuaternion.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPose3DQuat.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/TumTrajectory.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace mrpt_vslam::core {

void TumTrajectory::push_back(double t, const mrpt::math::TPose3D& pose)
{
    timestamps.push_back(t);
    poses.push_back(pose);
}

TumTrajectory TumTrajectory::loadGroundTruth(const std::string& file)
{
    auto truth = load(file);
    if (truth.empty()) throw std::runtime_error(file + ": no poses");
    return truth;
}

TumTrajectory TumTrajectory::load(const std::string& file)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open trajectory file");
    TumTrajectory traj;
    std::string line;
    for (int lineNum = 1; std::getline(in, line); lineNum++) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        const auto where = file + ":" + std::to_string(lineNum) + ": ";
        std::istringstream ss(line);
        double v[8];
        for (double& x : v) {
            if (!(ss >> x))
                throw std::runtime_error(where + "expected 8 numbers 't x y z qx qy qz qw'");
            if (!std::isfinite(x)) throw std::runtime_error(where + "non-finite value");
        }
        std::string extra;
        if (ss >> extra) throw std::runtime_error(where + "more than 8 columns");
        const double qnorm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
        if (std::abs(qnorm - 1.0) > 1e-3)
            throw std::runtime_error(where + "quaternion is not unit");
        if (!traj.timestamps.empty() && v[0] <= traj.timestamps.back())
            throw std::runtime_error(where + "timestamps must be strictly increasing");
        const mrpt::math::CQuaternionDouble q(v[7] / qnorm, v[4] / qnorm, v[5] / qnorm,
                                              v[6] / qnorm);
        traj.push_back(
            v[0], mrpt::poses::CPose3D(mrpt::poses::CPose3DQuat(v[1], v[2], v[3], q)).asTPose());
    }
    return traj;
}

void TumTrajectory::save(const std::string& file, const std::string& header_comment) const
{
    AtomicFile out(file);
    auto& os = out.stream();
    os << "# " << (header_comment.empty() ? "trajectory" : header_comment) << "\n"
       << "# timestamp x y z qx qy qz qw\n"
       << std::fixed;
    for (size_t i = 0; i < poses.size(); i++) {
        const mrpt::poses::CPose3DQuat p{mrpt::poses::CPose3D(poses[i])};
        os << std::setprecision(6) << timestamps[i] << std::setprecision(9) << ' ' << p.x() << ' '
           << p.y() << ' ' << p.z() << ' ' << p.quat().x() << ' ' << p.quat().y() << ' '
           << p.quat().z() << ' ' << p.quat().r() << '\n';
    }
    out.commit();
}

int TumTrajectory::nearestIndex(double t, double max_dt) const
{
    if (timestamps.empty()) return -1;
    const auto it = std::lower_bound(timestamps.begin(), timestamps.end(), t);
    int best = -1;
    double bestDt = max_dt;
    for (auto c : {it, it == timestamps.begin() ? it : it - 1}) {
        if (c == timestamps.end()) continue;
        const double dt = std::abs(*c - t);
        if (dt <= bestDt) {
            bestDt = dt;
            best = static_cast<int>(c - timestamps.begin());
        }
    }
    return best;
}

}  // namespace mrpt_vslam::core
