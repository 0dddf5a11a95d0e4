#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <cmath>
#include <map>
#include <tuple>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;

namespace {

/// The odometry a ⊕ b and its covariance, a and b independent.
std::pair<TPose2D, Eigen::Matrix3d> compose(const TPose2D& a, const Eigen::Matrix3d& Qa,
                                            const TPose2D& b, const Eigen::Matrix3d& Qb)
{
    const double c = std::cos(a.phi), s = std::sin(a.phi);
    Eigen::Matrix3d Ja = Eigen::Matrix3d::Identity(), Jb = Eigen::Matrix3d::Identity();
    Ja(0, 2) = -s * b.x - c * b.y;
    Ja(1, 2) = c * b.x - s * b.y;
    Jb.topLeftCorner<2, 2>() << c, -s, s, c;
    return {a + b, Ja * Qa * Ja.transpose() + Jb * Qb * Jb.transpose()};
}

}  // namespace

std::vector<TeamPathSmoother::TSensorPoseCheck> TeamPathSmoother::sensorPoseChecks(
    const TTeamParticle& p) const
{
    constexpr size_t kMaxGap = 3;  // steps between two readings of a pair
    TFrameIds ids;
    mapAlong(recordedPathOf(p), &ids);
    struct TLast {
        size_t step;
        Eigen::Vector2d z;
        Eigen::Matrix2d R;
    };
    std::map<std::tuple<size_t, uint16_t, uint32_t>, TLast> last;  // (robot, sensor, landmark)
    std::map<std::pair<size_t, uint16_t>, std::vector<TReadingPair>> pairs;
    for (size_t f = 0; f < m_fusedFrames.size(); f++) {
        const TFusedFrame& frame = m_fusedFrames[f];
        for (size_t j = 0; j < frame.z.size(); j++) {
            if (!ids[f][j]) continue;
            const TLandmarkMeasurement& m = frame.z[j];
            const TLast now{frame.step, m.z.head<2>(), m.R.topLeftCorner<2, 2>()};
            auto [it, first] = last.try_emplace({frame.robot, m.sensor, *ids[f][j]}, now);
            if (first) continue;
            const TLast before = it->second;
            it->second = now;
            if (now.step <= before.step || now.step - before.step > kMaxGap) continue;
            TPose2D u(0, 0, 0);
            Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
            for (size_t s = before.step + 1; s <= now.step; s++) {
                const core::TOdometryGaussian& step = m_motions.at(s - 1).at(frame.robot);
                std::tie(u, Q) = compose(u, Q, step.mean, step.cov);
            }
            pairs[{frame.robot, m.sensor}].push_back({before.z, now.z, before.R, now.R, u, Q});
        }
    }
    std::vector<TSensorPoseCheck> checks;
    for (const auto& [key, of_sensor] : pairs)
        checks.push_back({key.first, key.second, TSensorPoseCorrection::estimate(of_sensor)});
    return checks;
}

}  // namespace mrpt_vslam::multirobot
