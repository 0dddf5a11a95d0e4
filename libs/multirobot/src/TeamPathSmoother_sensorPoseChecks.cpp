#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <iterator>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

namespace mrpt_vslam::multirobot {

namespace {

/// A landmark as one sensor read it: the mean of its 3D readings in the map frame (their sum
/// and count while they are added), and the descriptor of the first.
struct TPlacedLandmark {
    Eigen::Vector3d at = Eigen::Vector3d::Zero();
    size_t readings = 0;
    const LandmarkDescriptorPool::TDescriptor* descriptor = nullptr;
};

/** For each landmark of `a`, the landmark of `b` within `radius` across (the heights play no
 *  part) of the least descriptor distance, at most E0 (ties: the nearest across). */
std::vector<std::optional<size_t>> bestAcross(const std::vector<TPlacedLandmark>& a,
                                              const std::vector<TPlacedLandmark>& b, double radius,
                                              double E0)
{
    std::vector<std::optional<size_t>> best(a.size());
    for (size_t i = 0; i < a.size(); i++) {
        const Eigen::Vector2d p = a[i].at.head<2>();
        std::pair<double, double> least{E0, std::numeric_limits<double>::infinity()};
        for (size_t j = 0; j < b.size(); j++) {
            const double across = (b[j].at.head<2>() - p).norm();
            if (across > radius) continue;
            const std::pair<double, double> key{
                LandmarkDescriptorPool::squaredDistance(*a[i].descriptor, *b[j].descriptor),
                across};
            if (key.first <= E0 && (!best[i] || key < least)) {
                best[i] = j;
                least = key;
            }
        }
    }
    return best;
}

/// The heights of `a`'s landmarks less those of `b`'s, each pair the best across of each other.
std::vector<double> heightDifferences(const std::vector<TPlacedLandmark>& a,
                                      const std::vector<TPlacedLandmark>& b, double radius,
                                      double E0)
{
    const auto ab = bestAcross(a, b, radius, E0), ba = bestAcross(b, a, radius, E0);
    std::vector<double> dz;
    for (size_t i = 0; i < a.size(); i++)
        if (ab[i] && ba[*ab[i]] == i) dz.push_back(a[i].at.z() - b[*ab[i]].at.z());
    return dz;
}

}  // namespace

std::vector<TeamPathSmoother::TSensorPoseCheck> TeamPathSmoother::sensorPoseChecks(
    const TTeamParticle& p) const
{
    const TTeamPath path = recordedPathOf(p);
    TFrameIds ids;
    mapAlong(path, &ids);
    using TKey = std::tuple<size_t, uint16_t, uint32_t>;  // robot, sensor, landmark
    core::ReadingPairing<TKey> pairing(
        [&](const TKey& key, size_t step) -> const core::TOdometryGaussian& {
            return m_motions.at(step - 1).at(std::get<0>(key));
        });
    using TSensorKey = std::pair<size_t, uint16_t>;
    std::map<TSensorKey, std::vector<core::TReadingPair>> pairs;
    std::map<TSensorKey, std::map<uint32_t, std::vector<core::TPointReading>>> readings;
    std::map<TSensorKey, std::map<uint32_t, TPlacedLandmark>> placed;
    for (size_t f = 0; f < m_fusedFrames.size(); f++) {
        const TFusedFrame& frame = m_fusedFrames[f];
        const TPlanarTransform pose(path.at(frame.step).at(frame.robot));
        for (size_t j = 0; j < frame.z.size(); j++) {
            if (!ids[f][j]) continue;
            const TLandmarkMeasurement& m = frame.z[j];
            const TSensorKey sensor{frame.robot, m.sensor};
            if (auto pair = pairing.add({frame.robot, m.sensor, *ids[f][j]}, frame.step,
                                        m.z.head<2>(), m.R.topLeftCorner<2, 2>()))
                pairs[sensor].push_back(*pair);
            if (m.planar) continue;
            readings[sensor][*ids[f][j]].push_back({m.z, m.R});
            TPlacedLandmark& l = placed[sensor][*ids[f][j]];
            l.at += toMapFrame(m, pose).z;
            if (l.readings++ == 0) l.descriptor = &m.d;
        }
    }
    std::map<TSensorKey, std::vector<TPlacedLandmark>> landmarksOf;
    for (auto& [sensor, of_sensor] : placed)
        for (auto& [id, l] : of_sensor) {
            l.at /= static_cast<double>(l.readings);
            landmarksOf[sensor].push_back(l);
        }
    // per two sensors, once: the readings' own search for landmarks, within search_radius and
    // of descriptors within E0; the other way round the differences change sign
    const CVisualLandmarksMap empty = emptyMap();
    const double radius = empty.insertionOptions.search_radius, E0 = empty.insertionOptions.E0;
    std::map<std::pair<TSensorKey, TSensorKey>, core::TSensorHeightOffset> offsets;
    for (auto a = landmarksOf.begin(); a != landmarksOf.end(); ++a)
        for (auto b = std::next(a); b != landmarksOf.end(); ++b) {
            const auto o = core::TSensorHeightOffset::estimate(
                heightDifferences(a->second, b->second, radius, E0));
            if (o.points < 2) continue;
            offsets[{a->first, b->first}] = o;
            offsets[{b->first, a->first}] = {-o.dz, o.std_dz, o.points};
        }

    std::vector<TSensorPoseCheck> checks;
    for (const auto& [key, of_sensor] : pairs) {
        TSensorPoseCheck check{key.first,
                               key.second,
                               core::TSensorPoseCorrection::estimate(of_sensor),
                               std::nullopt,
                               {}};
        if (const auto r = readings.find(key); r != readings.end()) {
            std::vector<std::vector<core::TPointReading>> points;
            for (auto& [landmark, of_landmark] : r->second)
                points.push_back(std::move(of_landmark));
            if (auto tilt = core::TSensorTiltCorrection::estimate(points); tilt.points > 0)
                check.tilt = tilt;
        }
        for (const auto& [sensors, offset] : offsets)
            if (sensors.first == key)
                check.heights.push_back({sensors.second.first, sensors.second.second, offset});
        checks.push_back(check);
    }
    return checks;
}

}  // namespace mrpt_vslam::multirobot
