// Reanchoring after a gap in a robot's readings (ours; doc/multirobot.md §3): a part of a path
// put back on the robot's odometry where more of its readings then fit the map.
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <Eigen/Cholesky>
#include <map>

namespace mrpt_vslam::multirobot {

double TeamPathSmoother::supportedFraction(const std::vector<size_t>& frames, const TTeamPath& path,
                                           const CVisualLandmarksMap& map,
                                           const TFrameIds& ids) const
{
    std::map<uint32_t, uint32_t> inside;  // readings of each landmark from `frames`
    size_t n = 0, fit = 0;
    for (const size_t f : frames)
        for (const auto& id : ids[f]) {
            n++;
            if (id) inside[*id]++;
        }
    for (const size_t f : frames) {
        const TFusedFrame& frame = m_fusedFrames[f];
        const TPlanarTransform pose(path.at(frame.step).at(frame.robot));
        for (size_t j = 0; j < frame.z.size(); j++) {
            const auto& id = ids[f][j];
            if (!id) continue;
            const TVisualLandmark* lm = map.landmarks().find(*id);
            if (lm->times_seen <= inside[*id]) continue;
            const TMapMeasurement w = toMapFrame(frame.z[j], pose);
            const Eigen::Vector2d v = (w.z - lm->mean).head<2>();
            const Eigen::Matrix2d S = (w.R + lm->cov).topLeftCorner<2, 2>();
            if (v.dot(S.ldlt().solve(v)) < 9.21) fit++;
        }
    }
    return n ? static_cast<double>(fit) / static_cast<double>(n) : 0;
}

size_t TeamPathSmoother::reanchorAfterGaps(TTeamPath& path, const std::vector<double>& times,
                                           const std::vector<Eigen::Vector2d>& scales,
                                           CVisualLandmarksMap& map, TFrameIds& ids,
                                           const CVisualLandmarksMap* seeds) const
{
    const double gap = options.reanchor_gap, gain = options.reanchor_gain;
    size_t moved = 0;
    for (size_t k = 0; k < robotCount(); k++) {
        std::vector<size_t> frames;  // robot k's, with landmark readings
        for (size_t f = 0; f < m_fusedFrames.size(); f++)
            if (m_fusedFrames[f].robot == k && !m_fusedFrames[f].z.empty()) frames.push_back(f);
        auto stepOf = [&](size_t i) { return m_fusedFrames[frames[i]].step; };
        size_t i = 1;
        while (i < frames.size()) {
            const size_t before = stepOf(i - 1);
            size_t j = i + 1;  // the part: frames [i, j)
            while (j < frames.size() && times[stepOf(j)] - times[stepOf(j - 1)] <= gap) j++;
            const std::vector<size_t> part(frames.begin() + i, frames.begin() + j);
            const bool afterGap = times[stepOf(i)] - times[before] > gap;
            i = j;
            if (!afterGap) continue;
            const double current = supportedFraction(part, path, map, ids);
            if (current + gain >= 1) continue;  // cannot gain enough
            TTeamPath candidate = path;
            for (size_t s = before + 1; s <= m_fusedFrames[part.back()].step; s++) {
                const auto& u = m_motions[s - 1][k].mean;
                candidate[s][k] =
                    candidate[s - 1][k] +
                    (scales.empty() ? u : PlanarPoseLandmarkGraph::scaled(u, scales[k]));
            }
            TFrameIds candidateIds;
            CVisualLandmarksMap candidateMap = mapAlong(candidate, &candidateIds, seeds);
            if (supportedFraction(part, candidate, candidateMap, candidateIds) > current + gain) {
                path = std::move(candidate);
                map = std::move(candidateMap);
                ids = std::move(candidateIds);
                moved++;
            }
        }
    }
    return moved;
}

}  // namespace mrpt_vslam::multirobot
