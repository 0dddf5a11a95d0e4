#include <mrpt/config/CConfigFileBase.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/multirobot/PlanarPoseLandmarkGraph.h>
#include <mrpt_vslam/multirobot/TeamPathSmoother.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;

namespace {
/// σ [m, rad] of the first start pose's prior, which defines the map frame (the filter's
/// reset() keeps it exact), and of the tie of a robot that stood
constexpr double kFixedStd = 1e-3;
Eigen::Matrix3d fixedCovariance()
{
    return Eigen::Vector3d::Constant(kFixedStd * kFixedStd).asDiagonal();
}

/// Adds to `to` each landmark of `from` as `as(id, landmark)` gives it, with its descriptor and
/// identity (known correspondences).
template <class F>
void addLandmarksOf(const CVisualLandmarksMap& from, CVisualLandmarksMap& to, F as)
{
    std::map<uint32_t, int64_t> identityOf;
    for (const auto& [identity, id] : from.descriptorPool().identities())
        identityOf.emplace(id, identity);
    from.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const uint32_t added = to.addLandmark(as(id, lm), from.descriptorPool().descriptor(id));
        if (const auto it = identityOf.find(id); it != identityOf.end())
            to.sharedDescriptorPool()->setLandmarkOfIdentity(it->second, added);
    });
}
}  // namespace

using core::requireKey;

void TeamPathSmoother::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                    const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(map_along_path, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(D0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_seen_fraction, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(nearest_pair_first, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(smooth_paths, bool, cfg, section);
    const int roundCount = cfg.read_int(section, "rounds", static_cast<int>(rounds));
    // each round maps and solves the whole run again; a few converge
    requireKey(roundCount >= 1 && roundCount <= 100, section, "rounds", "must be 1 to 100");
    rounds = static_cast<unsigned int>(roundCount);
    MRPT_LOAD_CONFIG_VAR(huber, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(odometry_scale_std, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(motion_cov_factor, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(zero_odometry_stands_still, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(reanchor_gap, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(reanchor_gain, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(reassociate, bool, cfg, section);

    requireKey(!cfg.keyExists(section, "min_times_seen"), section, "min_times_seen",
               "replaced by min_seen_fraction, a fraction of the frames with landmark readings");
    requireKey(D0 > 0, section, "D0", "must be > 0");
    requireKey(min_seen_fraction >= 0 && min_seen_fraction <= 1, section, "min_seen_fraction",
               "must be in [0, 1]");
    requireKey(!smooth_paths || map_along_path, section, "smooth_paths",
               "needs map_along_path = true");
    requireKey(!reassociate || smooth_paths, section, "reassociate", "needs smooth_paths = true");
    requireKey(huber >= 0, section, "huber", "must be >= 0");
    requireKey(odometry_scale_std >= 0, section, "odometry_scale_std", "must be >= 0");
    requireKey(motion_cov_factor > 0, section, "motion_cov_factor", "must be > 0");
    requireKey(reanchor_gap >= 0, section, "reanchor_gap", "must be >= 0");
    requireKey(reanchor_gain > 0 && reanchor_gain < 1, section, "reanchor_gain",
               "must be in (0, 1)");
}

void TeamPathSmoother::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                  const std::string& section) const
{
    cfg.write(section, "map_along_path", map_along_path);
    cfg.write(section, "D0", D0);
    cfg.write(section, "min_seen_fraction", min_seen_fraction);
    cfg.write(section, "nearest_pair_first", nearest_pair_first);
    cfg.write(section, "smooth_paths", smooth_paths);
    cfg.write(section, "rounds", rounds);
    cfg.write(section, "huber", huber);
    cfg.write(section, "odometry_scale_std", odometry_scale_std);
    cfg.write(section, "motion_cov_factor", motion_cov_factor);
    cfg.write(section, "zero_odometry_stands_still", zero_odometry_stands_still);
    cfg.write(section, "reanchor_gap", reanchor_gap);
    cfg.write(section, "reanchor_gain", reanchor_gain);
    cfg.write(section, "reassociate", reassociate);
}

TeamPathSmoother::TeamPathSmoother(const CVisualLandmarksMap& map_template)
{
    m_template.insertionOptions = map_template.insertionOptions;
    m_template.renderOptions = map_template.renderOptions;
    m_template.genericMapParams = map_template.genericMapParams;
}

void TeamPathSmoother::onReset(const std::vector<TPose2D>& start_poses, double initial_std_xy,
                               double initial_std_phi)
{
    m_fusedFrames.clear();
    m_motions.clear();
    m_startPoses = start_poses;
    m_initialStdXY = initial_std_xy;
    m_initialStdPhi = initial_std_phi;
}

void TeamPathSmoother::onRobotStep(
    size_t step, size_t robot, const core::TOdometryGaussian& motion,
    const std::vector<TLandmarkMeasurement>& z,
    const std::vector<CMultiRobotVisualSLAM::TRobotReading>& readings)
{
    if (robot == 0) m_motions.emplace_back();
    m_motions.back().push_back(motion);
    // a frame per sensor, fused in turn as the filter fuses them; the readings with the first
    const auto bySensor = splitBySensor(z);
    if (bySensor.empty() && !readings.empty()) m_fusedFrames.push_back({step, robot, {}, readings});
    for (size_t s = 0; s < bySensor.size(); s++)
        m_fusedFrames.push_back(
            {step, robot, bySensor[s],
             s == 0 ? readings : std::vector<CMultiRobotVisualSLAM::TRobotReading>()});
}

TeamPathSmoother::TTeamPath TeamPathSmoother::recordedPathOf(const TTeamParticle& p) const
{
    TTeamPath path;
    for (const auto* s : p.path.stepsOldestFirst())
        path.emplace_back(s->state.poses.begin(), s->state.poses.end());
    if (path.size() != m_motions.size() + 1)
        throw std::logic_error(
            "TeamPathSmoother: the particle's path is not that of the steps recorded since the "
            "filter's reset() (setStepObserver() before reset())");
    return path;
}

CVisualLandmarksMap TeamPathSmoother::emptyMap() const
{
    CVisualLandmarksMap map(
        std::make_shared<LandmarkDescriptorPool>(m_template.insertionOptions.grid_cell_size));
    map.insertionOptions = m_template.insertionOptions;
    map.insertionOptions.D0 = options.D0;
    map.renderOptions = m_template.renderOptions;
    map.genericMapParams = m_template.genericMapParams;
    return map;
}

Eigen::Matrix3d TeamPathSmoother::stepCovariance(size_t step, size_t robot) const
{
    const core::TOdometryGaussian& u = m_motions.at(step - 1).at(robot);
    const bool stood = u.mean.x == 0 && u.mean.y == 0 && u.mean.phi == 0;
    if (options.zero_odometry_stands_still && stood) return fixedCovariance();
    return u.cov * options.motion_cov_factor;
}

CVisualLandmarksMap TeamPathSmoother::mapAlong(const TTeamPath& path, TFrameIds* ids,
                                               const CVisualLandmarksMap* seeds) const
{
    CVisualLandmarksMap map = emptyMap();
    if (seeds) addLandmarksOf(*seeds, map, [](uint32_t, const TVisualLandmark& lm) { return lm; });
    std::vector<TMapMeasurement> in_map;
    std::vector<TMeasurementCandidates> candidates;
    if (ids) ids->clear();
    for (const auto& f : m_fusedFrames) {
        const TPose2D& x = path.at(f.step).at(f.robot);
        const TPlanarTransform pose(x);
        // reassociate: the pose is as uncertain as the step into it, H Σ Hᵀ on each point
        const bool widen = options.reassociate && f.step > 0;
        const Eigen::Matrix3d Sigma =
            widen ? core::incrementCovInMapFrame(stepCovariance(f.step, f.robot),
                                                 path[f.step - 1][f.robot].phi)
                  : Eigen::Matrix3d::Zero();
        in_map.resize(f.z.size());
        candidates.resize(f.z.size());
        for (size_t j = 0; j < f.z.size(); j++) {
            in_map[j] = toMapFrame(f.z[j], pose);
            if (widen) {
                const Eigen::Matrix3d H = poseJacobian(in_map[j].z, x);
                in_map[j].R += H * Sigma * H.transpose();
            }
            candidates[j] = map.findCandidates(f.z[j], in_map[j]);
        }
        const auto fused =
            map.fuseFrame(f.z, in_map, candidates, static_cast<unsigned>(f.robot),
                          options.nearest_pair_first
                              ? CVisualLandmarksMap::TFrameAssociation::DistinctNearestFirst
                              : CVisualLandmarksMap::TFrameAssociation::DistinctInOrder);
        if (ids) {
            ids->emplace_back();
            for (const auto& r : fused) ids->back().push_back(r.id);
        }
    }
    // seeds no reading went to are dropped whatever the threshold
    map.removeLandmarksSeenLessThan(std::max(1u, minTimesSeen()));
    if (ids)
        for (auto& frame : *ids)
            for (auto& id : frame)
                if (!map.landmarks().find(*id)) id.reset();
    return map;
}

unsigned int TeamPathSmoother::minTimesSeen() const
{
    size_t frames = 0;  // robot steps with landmark measurements, of one sensor or more
    const TFusedFrame* counted = nullptr;
    for (const auto& f : m_fusedFrames)
        if (!f.z.empty()) {
            if (!counted || counted->step != f.step || counted->robot != f.robot) frames++;
            counted = &f;
        }
    // a product within 1e-9 of a whole count is that count (0.07 × 100 is 7, not 8)
    return static_cast<unsigned int>(
        std::ceil(options.min_seen_fraction * static_cast<double>(frames) - 1e-9));
}

std::vector<TCorrespondence> TeamPathSmoother::correspondencesOf(const TFrameIds& ids) const
{
    std::vector<TCorrespondence> c;
    for (size_t f = 0; f < m_fusedFrames.size(); f++)
        for (size_t j = 0; j < ids[f].size(); j++)
            if (ids[f][j])
                c.push_back({static_cast<uint32_t>(m_fusedFrames[f].robot), *ids[f][j],
                             m_fusedFrames[f].z[j].track_id});
    return c;
}

CVisualLandmarksMap TeamPathSmoother::mapAlongPath(
    const TTeamParticle& p, std::vector<TCorrespondence>* correspondences) const
{
    TFrameIds ids;
    CVisualLandmarksMap map = mapAlong(recordedPathOf(p), correspondences ? &ids : nullptr);
    if (correspondences) *correspondences = correspondencesOf(ids);
    return map;
}

CVisualLandmarksMap TeamPathSmoother::seedsFrom(const CVisualLandmarksMap& map,
                                                const PlanarPoseLandmarkGraph& graph,
                                                const std::map<uint32_t, size_t>& pointOf) const
{
    CVisualLandmarksMap seeds = emptyMap();
    addLandmarksOf(map, seeds, [&](uint32_t id, const TVisualLandmark& lm) {
        TVisualLandmark seed;  // times_seen and seen_by 0
        seed.mean = lm.mean;
        seed.mean.head<2>() = graph.point(pointOf.at(id));
        seed.cov = lm.cov;
        return seed;
    });
    return seeds;
}

PlanarPoseLandmarkGraph TeamPathSmoother::graphOf(const TTeamPath& path,
                                                  const CVisualLandmarksMap& map,
                                                  const TFrameIds& ids,
                                                  const std::vector<Eigen::Vector2d>& scales,
                                                  std::map<uint32_t, size_t>& pointOf) const
{
    const size_t K = robotCount();
    auto planar = [](const Eigen::Matrix3d& R) { return Eigen::Matrix2d(R.topLeftCorner<2, 2>()); };
    PlanarPoseLandmarkGraph graph;
    for (const auto& poses : path)
        for (const auto& x : poses) graph.addPose(x);
    pointOf.clear();
    map.landmarks().forEach([&](uint32_t id, const TVisualLandmark& lm) {
        pointOf[id] = graph.addPoint(lm.mean.head<2>());
    });
    // the start poses: the first robot's defines the map frame (a tight prior, as the filter's
    // reset() keeps it exact), the others as reset() spreads them
    const double sxy = std::max(m_initialStdXY, kFixedStd);
    const double sphi = std::max(m_initialStdPhi, kFixedStd);
    const Eigen::Matrix3d spread = Eigen::Vector3d(sxy * sxy, sxy * sxy, sphi * sphi).asDiagonal();
    for (size_t k = 0; k < K; k++)
        graph.addPosePrior(nodeOf(0, k), m_startPoses[k], k == 0 ? fixedCovariance() : spread);
    const double scaleStd = options.odometry_scale_std;
    for (const auto& initial : scales)
        graph.addOdometryScale(initial, {1, 1}, Eigen::Matrix2d::Identity() * scaleStd * scaleStd);
    for (size_t step = 1; step < path.size(); step++)
        for (size_t k = 0; k < K; k++) {
            const core::TOdometryGaussian& u = m_motions[step - 1][k];
            const Eigen::Matrix3d cov = stepCovariance(step, k);
            if (scaleStd > 0)
                graph.addOdometry(nodeOf(step - 1, k), nodeOf(step, k), u.mean, cov, k);
            else
                graph.addOdometry(nodeOf(step - 1, k), nodeOf(step, k), u.mean, cov);
        }
    for (size_t f = 0; f < m_fusedFrames.size(); f++) {
        const TFusedFrame& frame = m_fusedFrames[f];
        const size_t from = nodeOf(frame.step, frame.robot);
        for (size_t j = 0; j < frame.z.size(); j++)
            if (ids[f][j])
                graph.addPointReading(from, pointOf.at(*ids[f][j]), frame.z[j].z.head<2>(),
                                      planar(frame.z[j].R));
        for (const auto& r : frame.readings)
            graph.addPoseReading(from, nodeOf(frame.step, r.robot), r.m.z.head<2>(), planar(r.m.R));
    }
    return graph;
}

TeamPathSmoother::TSmoothedTeam TeamPathSmoother::smoothPaths(const TTeamParticle& p) const
{
    const size_t K = robotCount();
    TTeamPath path = recordedPathOf(p);
    TSmoothedTeam result;
    result.odometry_scales.assign(options.odometry_scale_std > 0 ? K : 0, Eigen::Vector2d(1, 1));
    std::vector<double> times;
    for (const auto& [t, pose] : CMultiRobotVisualSLAM::pathOf(p, 0)) times.push_back(t);
    TFrameIds ids;
    std::map<uint32_t, size_t> pointOf;
    std::optional<CVisualLandmarksMap> seeds;  // options.reassociate
    for (unsigned round = 0; round < options.rounds; round++) {
        const CVisualLandmarksMap* seed = seeds ? &*seeds : nullptr;
        CVisualLandmarksMap map = mapAlong(path, &ids, seed);
        if (options.reanchor_gap > 0)
            result.reanchored +=
                reanchorAfterGaps(path, times, result.odometry_scales, map, ids, seed);
        PlanarPoseLandmarkGraph graph = graphOf(path, map, ids, result.odometry_scales, pointOf);
        PlanarPoseLandmarkGraph::TOptions lsq;
        lsq.huber_threshold = options.huber;
        const auto solved = graph.optimize(lsq);
        result.iterations += solved.iterations;
        result.readings = solved.readings;
        result.outlier_readings = solved.outlier_readings;
        for (size_t step = 0; step < path.size(); step++)
            for (size_t k = 0; k < K; k++) path[step][k] = graph.pose(nodeOf(step, k));
        for (size_t k = 0; k < result.odometry_scales.size(); k++)
            result.odometry_scales[k] = graph.odometryScale(k);
        if (options.reassociate) seeds = seedsFrom(map, graph, pointOf);
    }
    result.map = mapAlong(path, &ids);
    result.correspondences = correspondencesOf(ids);
    // the output's own cost: its paths and map, through the associations it was mapped with
    result.cost =
        graphOf(path, result.map, ids, result.odometry_scales, pointOf).cost(options.huber);
    for (size_t k = 0; k < K; k++) {
        result.paths.push_back(CMultiRobotVisualSLAM::pathOf(p, k));  // for the timestamps
        for (size_t step = 0; step < path.size(); step++)
            result.paths[k][step].second = path[step][k];
    }
    return result;
}

}  // namespace mrpt_vslam::multirobot
