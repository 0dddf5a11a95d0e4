#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <map>
#include <tuple>

namespace mrpt_vslam::multirobot {

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
    std::map<std::pair<size_t, uint16_t>, std::vector<core::TReadingPair>> pairs;
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
            mrpt::poses::CPosePDFGaussian u;  // the odometry between the two, composed
            for (size_t s = before.step + 1; s <= now.step; s++) {
                const core::TOdometryGaussian& step = m_motions.at(s - 1).at(frame.robot);
                u += mrpt::poses::CPosePDFGaussian(mrpt::poses::CPose2D(step.mean),
                                                   mrpt::math::CMatrixDouble33(step.cov));
            }
            pairs[{frame.robot, m.sensor}].push_back(
                {before.z, now.z, before.R, now.R, u.mean.asTPose(), u.cov.asEigen()});
        }
    }
    std::vector<TSensorPoseCheck> checks;
    for (const auto& [key, of_sensor] : pairs)
        checks.push_back({key.first, key.second, core::TSensorPoseCorrection::estimate(of_sensor)});
    return checks;
}

}  // namespace mrpt_vslam::multirobot
