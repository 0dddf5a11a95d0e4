#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <map>
#include <tuple>

namespace mrpt_vslam::multirobot {

std::vector<TeamPathSmoother::TSensorPoseCheck> TeamPathSmoother::sensorPoseChecks(
    const TTeamParticle& p) const
{
    TFrameIds ids;
    mapAlong(recordedPathOf(p), &ids);
    using TKey = std::tuple<size_t, uint16_t, uint32_t>;  // robot, sensor, landmark
    core::ReadingPairing<TKey> pairing(
        [&](const TKey& key, size_t step) -> const core::TOdometryGaussian& {
            return m_motions.at(step - 1).at(std::get<0>(key));
        });
    std::map<std::pair<size_t, uint16_t>, std::vector<core::TReadingPair>> pairs;
    for (size_t f = 0; f < m_fusedFrames.size(); f++) {
        const TFusedFrame& frame = m_fusedFrames[f];
        for (size_t j = 0; j < frame.z.size(); j++) {
            if (!ids[f][j]) continue;
            const TLandmarkMeasurement& m = frame.z[j];
            if (auto pair = pairing.add({frame.robot, m.sensor, *ids[f][j]}, frame.step,
                                        m.z.head<2>(), m.R.topLeftCorner<2, 2>()))
                pairs[{frame.robot, m.sensor}].push_back(*pair);
        }
    }
    std::vector<TSensorPoseCheck> checks;
    for (const auto& [key, of_sensor] : pairs)
        checks.push_back({key.first, key.second, core::TSensorPoseCorrection::estimate(of_sensor)});
    return checks;
}

}  // namespace mrpt_vslam::multirobot
