// The results made after the filter, along the best particle's path (ours; doc/multirobot.md
// §3): the map along the path and the smoothed paths.
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <map>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;

CMultiRobotVisualSLAM::TTeamPath CMultiRobotVisualSLAM::teamPathOf(const TTeamParticle& p)
{
    TTeamPath path;
    for (const TTeamPathNode* n = p.path.get(); n; n = n->previous.get()) path.push_back(n->poses);
    std::reverse(path.begin(), path.end());
    return path;
}

CVisualLandmarksMap CMultiRobotVisualSLAM::mapAlong(const TTeamPath& path, TFrameIds* ids) const
{
    CVisualLandmarksMap map(
        std::make_shared<LandmarkDescriptorPool>(m_template.insertionOptions.grid_cell_size));
    map.insertionOptions = m_template.insertionOptions;
    map.insertionOptions.D0 = options.map_along_path_D0;
    map.renderOptions = m_template.renderOptions;
    map.genericMapParams = m_template.genericMapParams;
    std::vector<TMapMeasurement> in_map;
    std::vector<TMeasurementCandidates> candidates;
    if (ids) ids->clear();
    for (const auto& f : m_fusedFrames) {
        const TPlanarTransform pose(path.at(f.step).at(f.robot));
        in_map.resize(f.z.size());
        candidates.resize(f.z.size());
        for (size_t j = 0; j < f.z.size(); j++) {
            in_map[j] = toMapFrame(f.z[j], pose);
            candidates[j] = map.findCandidates(f.z[j], in_map[j]);
        }
        const auto fused =
            map.fuseFrame(f.z, in_map, candidates, static_cast<unsigned>(f.robot), true);
        if (ids) {
            ids->emplace_back();
            for (const auto& r : fused) ids->back().push_back(r.id);
        }
    }
    map.removeLandmarksSeenLessThan(options.map_along_path_min_times_seen);
    if (ids)
        for (auto& frame : *ids)
            for (auto& id : frame)
                if (!map.landmarks().find(*id)) id.reset();
    return map;
}

CVisualLandmarksMap CMultiRobotVisualSLAM::mapAlongPath(const TTeamParticle& p) const
{
    if (!options.map_along_path)
        throw std::logic_error("mapAlongPath() needs options.map_along_path before reset()");
    return mapAlong(teamPathOf(p), nullptr);
}

double CMultiRobotVisualSLAM::supportedFraction(const std::vector<size_t>& frames,
                                                const TTeamPath& path,
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

size_t CMultiRobotVisualSLAM::reanchorAfterGaps(TTeamPath& path, const std::vector<double>& times,
                                                const std::vector<Eigen::Vector2d>& scales,
                                                CVisualLandmarksMap& map, TFrameIds& ids) const
{
    const double gap = options.smooth_paths_reanchor_gap, gain = options.smooth_paths_reanchor_gain;
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
            CVisualLandmarksMap candidateMap = mapAlong(candidate, &candidateIds);
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

CMultiRobotVisualSLAM::TSmoothedTeam CMultiRobotVisualSLAM::smoothPaths(
    const TTeamParticle& p) const
{
    if (!options.map_along_path)
        throw std::logic_error("smoothPaths() needs options.map_along_path before reset()");
    const size_t K = robotCount();
    TTeamPath path = teamPathOf(p);
    if (path.size() != m_motions.size() + 1)
        throw std::logic_error("smoothPaths(): the particle's path is not the filter's");
    auto node = [K](size_t step, size_t robot) { return step * K + robot; };
    auto planar = [](const Eigen::Matrix3d& R) { return Eigen::Matrix2d(R.topLeftCorner<2, 2>()); };
    // the start poses: the first robot's defines the map frame (a tight prior, as reset() keeps
    // it exact), the others as reset() spreads them
    const double fixed = 1e-3;
    const double sxy = std::max(options.initial_std_xy, fixed);
    const double sphi = std::max(options.initial_std_phi, fixed);
    const double scaleStd = options.smooth_paths_odometry_scale_std;

    TSmoothedTeam result;
    result.odometry_scales.assign(scaleStd > 0 ? K : 0, Eigen::Vector2d(1, 1));
    std::vector<double> times;
    for (const auto& [t, pose] : pathOf(p, 0)) times.push_back(t);
    TFrameIds ids;
    for (unsigned round = 0; round < options.smooth_paths_rounds; round++) {
        CVisualLandmarksMap map = mapAlong(path, &ids);
        if (options.smooth_paths_reanchor_gap > 0)
            result.reanchored += reanchorAfterGaps(path, times, result.odometry_scales, map, ids);
        PlanarPoseLandmarkGraph graph;
        for (const auto& poses : path)
            for (const auto& x : poses) graph.addPose(x);
        std::map<uint32_t, size_t> pointOf;
        map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
            pointOf[id] = graph.addPoint(lm.mean.head<2>());
        });
        for (size_t k = 0; k < K; k++) {
            const double s = k == 0 ? fixed : sxy, a = k == 0 ? fixed : sphi;
            graph.addPosePrior(node(0, k), m_startPoses[k],
                               Eigen::Vector3d(s * s, s * s, a * a).asDiagonal());
        }
        for (const auto& initial : result.odometry_scales)
            graph.addOdometryScale(initial, {1, 1},
                                   Eigen::Matrix2d::Identity() * scaleStd * scaleStd);
        for (size_t step = 1; step < path.size(); step++)
            for (size_t k = 0; k < K; k++) {
                const TMotionGaussian& u = m_motions[step - 1][k];
                const Eigen::Matrix3d cov = u.cov * options.smooth_paths_motion_cov_factor;
                if (scaleStd > 0)
                    graph.addOdometry(node(step - 1, k), node(step, k), u.mean, cov, k);
                else
                    graph.addOdometry(node(step - 1, k), node(step, k), u.mean, cov);
            }
        for (size_t f = 0; f < m_fusedFrames.size(); f++) {
            const TFusedFrame& frame = m_fusedFrames[f];
            const size_t from = node(frame.step, frame.robot);
            for (size_t j = 0; j < frame.z.size(); j++)
                if (ids[f][j])
                    graph.addPointReading(from, pointOf.at(*ids[f][j]), frame.z[j].z.head<2>(),
                                          planar(frame.z[j].R));
            for (const auto& r : frame.readings)
                graph.addPoseReading(from, node(frame.step, r.robot), r.m.z.head<2>(),
                                     planar(r.m.R));
        }
        PlanarPoseLandmarkGraph::TOptions lsq;
        lsq.huber_threshold = options.smooth_paths_huber;
        const auto solved = graph.optimize(lsq);
        result.iterations += solved.iterations;
        result.outlier_readings = solved.outlier_readings;
        for (size_t step = 0; step < path.size(); step++)
            for (size_t k = 0; k < K; k++) path[step][k] = graph.pose(node(step, k));
        for (size_t k = 0; k < result.odometry_scales.size(); k++)
            result.odometry_scales[k] = graph.odometryScale(k);
    }
    result.map = mapAlong(path, nullptr);
    for (size_t k = 0; k < K; k++) {
        result.paths.push_back(pathOf(p, k));  // for the timestamps
        for (size_t step = 0; step < path.size(); step++)
            result.paths[k][step].second = path[step][k];
    }
    return result;
}

}  // namespace mrpt_vslam::multirobot
