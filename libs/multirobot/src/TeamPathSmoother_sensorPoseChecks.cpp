#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <map>
#include <tuple>
#include <utility>

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
    using TSensorKey = std::pair<size_t, uint16_t>;
    std::map<TSensorKey, std::vector<core::TReadingPair>> pairs;
    std::map<TSensorKey, std::map<uint32_t, std::vector<core::TPointReading>>> readings;
    for (size_t f = 0; f < m_fusedFrames.size(); f++) {
        const TFusedFrame& frame = m_fusedFrames[f];
        for (size_t j = 0; j < frame.z.size(); j++) {
            if (!ids[f][j]) continue;
            const TLandmarkMeasurement& m = frame.z[j];
            const TSensorKey sensor{frame.robot, m.sensor};
            if (auto pair = pairing.add({frame.robot, m.sensor, *ids[f][j]}, frame.step,
                                        m.z.head<2>(), m.R.topLeftCorner<2, 2>()))
                pairs[sensor].push_back(*pair);
            if (!m.planar) readings[sensor][*ids[f][j]].push_back({m.z, m.R});
        }
    }
    std::vector<TSensorPoseCheck> checks;
    for (const auto& [key, of_sensor] : pairs) {
        TSensorPoseCheck check{key.first, key.second,
                               core::TSensorPoseCorrection::estimate(of_sensor), std::nullopt};
        if (const auto r = readings.find(key); r != readings.end()) {
            std::vector<std::vector<core::TPointReading>> points;
            for (auto& [landmark, of_landmark] : r->second)
                points.push_back(std::move(of_landmark));
            if (auto tilt = core::TSensorTiltCorrection::estimate(points); tilt.points > 0)
                check.tilt = tilt;
        }
        checks.push_back(check);
    }
    return checks;
}

}  // namespace mrpt_vslam::multirobot
