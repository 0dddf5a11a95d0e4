#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/core/Prefetch.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/multirobot/Cholesky3.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;

using core::requireKey;

namespace {
/** `<prefix>_std_range` [m], `<prefix>_std_bearing_deg`, `<prefix>_std_pitch_deg` (each > 0,
 *  or absent: the observation's own σ), `<prefix>_std_height` [m] (> 0). */
void loadNoise(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
               const std::string& prefix, TRangeBearingNoise& noise)
{
    const auto readStd = [&](const std::string& key, double unit, std::optional<double>& v) {
        if (!cfg.keyExists(section, key)) return;
        v = unit * cfg.read_double(section, key, 0);
        requireKey(*v > 0 && std::isfinite(*v), section, key.c_str(),
                   "must be > 0 (leave it out to use the observations' own)");
    };
    readStd(prefix + "_std_range", 1, noise.std_range);
    readStd(prefix + "_std_bearing_deg", mrpt::DEG2RAD(1.0), noise.std_bearing);
    readStd(prefix + "_std_pitch_deg", mrpt::DEG2RAD(1.0), noise.std_pitch);
    noise.std_height = cfg.read_double(section, prefix + "_std_height", noise.std_height);
    noise.config_keys = section + "." + prefix;
    requireKey(noise.std_height > 0 && std::isfinite(noise.std_height), section,
               (prefix + "_std_height").c_str(), "must be > 0");
}

/** log p(reading | both poses of a particle): the Gaussian of the point's offset from the seen
 *  robot, covariance S (the reading's, plus H Σ Hᵀ in the optimal proposal). */
double robotReadingLogLikelihood(const Eigen::Vector3d& offset, const Eigen::Matrix3d& S)
{
    const Cholesky3 L(S);
    if (!L.ok)
        throw std::runtime_error("a robot reading has a covariance that is not positive definite");
    return L.logGaussian(L.whiten(offset).squaredNorm());
}

void saveNoise(mrpt::config::CConfigFileBase& cfg, const std::string& section,
               const std::string& prefix, const TRangeBearingNoise& noise)
{
    if (noise.std_range) cfg.write(section, prefix + "_std_range", *noise.std_range);
    if (noise.std_bearing)
        cfg.write(section, prefix + "_std_bearing_deg", mrpt::RAD2DEG(*noise.std_bearing));
    if (noise.std_pitch)
        cfg.write(section, prefix + "_std_pitch_deg", mrpt::RAD2DEG(*noise.std_pitch));
    cfg.write(section, prefix + "_std_height", noise.std_height);
}
}  // namespace

void CMultiRobotVisualSLAM::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                         const std::string& section)
{
    if (cfg.keyExists(section, "robots")) {
        robots.clear();
        mrpt::system::tokenize(cfg.read_string(section, "robots", ""), " \t,", robots);
    }
    MRPT_LOAD_CONFIG_VAR(sensor_label, string, cfg, section);
    MRPT_LOAD_CONFIG_VAR(landmarks_suffix, string, cfg, section);
    MRPT_LOAD_CONFIG_VAR(range_bearing_suffix, string, cfg, section);
    loadNoise(cfg, section, "range_bearing", range_bearing_noise);
    MRPT_LOAD_CONFIG_VAR(robot_readings_suffix, string, cfg, section);
    loadNoise(cfg, section, "robot_reading", robot_reading_noise);
    if (cfg.keyExists(section, "robot_reading_ids")) {
        robot_reading_ids.clear();
        std::vector<std::string> ids;
        mrpt::system::tokenize(cfg.read_string(section, "robot_reading_ids", ""), " \t,", ids);
        for (const auto& id : ids) {
            size_t used = 0;
            int value = 0;
            try {
                value = std::stoi(id, &used);
            } catch (const std::exception&) {
            }
            requireKey(used == id.size() && used > 0, section, "robot_reading_ids",
                       "must be integers");
            robot_reading_ids.push_back(value);
        }
    }
    MRPT_LOAD_CONFIG_VAR(max_observations_per_robot, uint64_t, cfg, section);
    observation_selection = core::readChoice(
        cfg, section, "observation_selection",
        {{"nearest", TSelection::Nearest}, {"random", TSelection::Random}}, observation_selection);
    motion_noise_floor.loadFromConfigFile(cfg, section);
    MRPT_LOAD_CONFIG_VAR(initial_std_xy, double, cfg, section);
    initial_std_phi = mrpt::DEG2RAD(
        cfg.read_double(section, "initial_std_phi_deg", mrpt::RAD2DEG(initial_std_phi)));
    MRPT_LOAD_CONFIG_VAR(resample_per_robot, bool, cfg, section);
    requireKey(!robots.empty() && robots.size() <= 32, section, "robots",
               "must name 1 to 32 robots");
    for (size_t i = 0; i < robots.size(); i++)
        requireKey(std::count(robots.begin(), robots.end(), robots[i]) == 1, section, "robots",
                   "must not repeat a name");
    requireKey(sensor_label.empty() || robots.size() == 1, section, "sensor_label",
               "is for one robot; a team's labels are <ROBOT> + the suffixes");
    requireKey(!landmarks_suffix.empty(), section, "landmarks_suffix", "must not be empty");
    requireKey(!range_bearing_suffix.empty() && range_bearing_suffix != landmarks_suffix, section,
               "range_bearing_suffix", "must not be empty nor equal landmarks_suffix");
    requireKey(!robot_readings_suffix.empty() && robot_readings_suffix != landmarks_suffix &&
                   robot_readings_suffix != range_bearing_suffix,
               section, "robot_readings_suffix",
               "must not be empty nor equal landmarks_suffix or range_bearing_suffix");
    requireKey(robot_reading_ids.empty() || robot_reading_ids.size() == robots.size(), section,
               "robot_reading_ids", "must give one id per robot of `robots`, or none");
    for (size_t i = 0; i < robot_reading_ids.size(); i++)
        requireKey(std::count(robot_reading_ids.begin(), robot_reading_ids.end(),
                              robot_reading_ids[i]) == 1,
                   section, "robot_reading_ids", "must not repeat an id");
    requireKey(max_observations_per_robot >= 1 && max_observations_per_robot <= 1000, section,
               "max_observations_per_robot", "must be 1 to 1000");
    requireKey(initial_std_xy >= 0, section, "initial_std_xy", "must be >= 0");
    requireKey(initial_std_phi >= 0, section, "initial_std_phi_deg", "must be >= 0");
}

void CMultiRobotVisualSLAM::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                       const std::string& section) const
{
    std::string names;
    for (const auto& r : robots) names += (names.empty() ? "" : " ") + r;
    cfg.write(section, "robots", names);
    cfg.write(section, "sensor_label", sensor_label);
    cfg.write(section, "landmarks_suffix", landmarks_suffix);
    cfg.write(section, "range_bearing_suffix", range_bearing_suffix);
    saveNoise(cfg, section, "range_bearing", range_bearing_noise);
    cfg.write(section, "robot_readings_suffix", robot_readings_suffix);
    std::string ids;
    for (const int id : robot_reading_ids) ids += (ids.empty() ? "" : " ") + std::to_string(id);
    cfg.write(section, "robot_reading_ids", ids);
    saveNoise(cfg, section, "robot_reading", robot_reading_noise);
    cfg.write(section, "max_observations_per_robot", max_observations_per_robot);
    cfg.write(section, "observation_selection",
              observation_selection == TSelection::Random ? "random" : "nearest");
    motion_noise_floor.saveToConfigFile(cfg, section);
    cfg.write(section, "initial_std_xy", initial_std_xy);
    cfg.write(section, "initial_std_phi_deg", mrpt::RAD2DEG(initial_std_phi));
    cfg.write(section, "resample_per_robot", resample_per_robot);
}

CMultiRobotVisualSLAM::CMultiRobotVisualSLAM(const CVisualLandmarksMap& map_template,
                                             size_t particle_count, uint32_t seed)
{
    if (particle_count == 0) throw std::invalid_argument("particle count must be > 0");
    if (!map_template.isEmpty())
        throw std::invalid_argument("the map template of the filter must be empty");
    m_template.insertionOptions = map_template.insertionOptions;
    m_template.renderOptions = map_template.renderOptions;
    m_template.genericMapParams = map_template.genericMapParams;
    m_rng.randomize(seed);
    m_particles.resize(particle_count);
    for (auto& p : m_particles) p.d.reset(new TTeamParticle);
}

void CMultiRobotVisualSLAM::reset(const std::vector<TPose2D>& start_poses, double timestamp)
{
    if (start_poses.size() != robotCount())
        throw std::invalid_argument("reset(): " + std::to_string(start_poses.size()) +
                                    " start poses for " + std::to_string(robotCount()) + " robots");
    // a fresh pool shared by the template and every particle's map
    CVisualLandmarksMap empty(
        std::make_shared<LandmarkDescriptorPool>(m_template.insertionOptions.grid_cell_size));
    empty.insertionOptions = m_template.insertionOptions;
    empty.renderOptions = m_template.renderOptions;
    empty.genericMapParams = m_template.genericMapParams;
    m_template = empty;
    for (auto& p : m_particles) {
        p.log_w = 0;
        auto& d = *p.d;
        d.poses = teamPoses(start_poses);
        for (size_t k = 1; k < d.poses.size(); k++) {
            d.poses[k].x += options.initial_std_xy * m_rng.drawGaussian1D_normalized();
            d.poses[k].y += options.initial_std_xy * m_rng.drawGaussian1D_normalized();
            d.poses[k].phi = mrpt::math::wrapToPi(
                d.poses[k].phi + options.initial_std_phi * m_rng.drawGaussian1D_normalized());
        }
        d.path = TTeamParticlePath();
        d.path.append(timestamp, d.poses);
        d.map = m_template;
        d.accumulated_log_w = 0;
        d.correspondences.resize(0);
    }
    m_steps = 0;
    m_noise_ahead_drawn = false;
    m_poolSizeAtPrune = m_poolKeptAtPrune = 0;
    if (m_observer)
        m_observer->onReset(start_poses, options.initial_std_xy, options.initial_std_phi);
}

void CMultiRobotVisualSLAM::performSubstitution(const std::vector<size_t>& indx)
{
    ParticleFilterDataImpl::performSubstitution(indx);
    const size_t pool_size = m_template.descriptorPool().size();
    if (pool_size - m_poolSizeAtPrune < std::max<size_t>(m_poolKeptAtPrune, 32)) return;
    std::vector<uint32_t> held;
    for (const auto& p : m_particles) p.d->map.landmarks().addIdsTo(held);
    m_poolKeptAtPrune = m_template.sharedDescriptorPool()->forgetAllBut(held);
    m_poolSizeAtPrune = pool_size;
}

std::vector<std::pair<double, TPose2D>> CMultiRobotVisualSLAM::pathOf(const TTeamParticle& p,
                                                                      size_t robot)
{
    std::vector<std::pair<double, TPose2D>> path;
    for (const auto* s : p.path.stepsOldestFirst())
        path.emplace_back(s->timestamp, s->state.poses.at(robot));
    return path;
}

core::TOdometryGaussian CMultiRobotVisualSLAM::motionOf(
    size_t k, const mrpt::obs::CActionRobotMovement2D& odometry) const
{
    try {
        return core::TOdometryGaussian::from(&odometry, options.motion_noise_floor);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(options.robots[k] + ": " + e.what());
    }
}

std::vector<TLandmarkMeasurement> CMultiRobotVisualSLAM::measurementsOf(
    size_t k, const mrpt::obs::CSensoryFrame& frame)
{
    using core::ObservationSelector;
    std::vector<TLandmarkMeasurement> z;
    uint16_t sensor = 0;
    const auto append = [&](std::vector<TLandmarkMeasurement> of_sensor) {
        for (auto& m : of_sensor) m.sensor = sensor;
        z.insert(z.end(), of_sensor.begin(), of_sensor.end());
        sensor++;
    };
    for (const auto& obs : ObservationSelector::allIn<mrpt::obs::CObservationVisualLandmarks>(
             frame, options.inputLabel(k, options.landmarks_suffix)))
        append(measurementsFromObservation(*obs));
    for (const auto& obs : ObservationSelector::allIn<mrpt::obs::CObservationBearingRange>(
             frame, options.inputLabel(k, options.range_bearing_suffix)))
        append(measurementsFromBearingRange(*obs, options.range_bearing_noise,
                                            &lastStepStats.non_positive_ranges));
    const size_t B = options.max_observations_per_robot;
    return options.observation_selection == TOptions::TSelection::Random
               ? selectAtRandom(std::move(z), B, m_rng)
               : selectNearest(std::move(z), B);
}

std::vector<CMultiRobotVisualSLAM::TRobotReading> CMultiRobotVisualSLAM::robotReadingsOf(
    size_t k, const mrpt::obs::CSensoryFrame& frame)
{
    std::vector<TRobotReading> readings;
    if (options.robot_reading_ids.empty()) return readings;
    const auto obs = frame.getObservationBySensorLabelAs<mrpt::obs::CObservationBearingRange::Ptr>(
        options.robots[k] + options.robot_readings_suffix);
    if (!obs) return readings;
    const auto& ids = options.robot_reading_ids;
    for (const auto& m : measurementsFromBearingRange(*obs, options.robot_reading_noise,
                                                      &lastStepStats.non_positive_ranges)) {
        const auto seen = std::find(ids.begin(), ids.end(), m.track_id);
        const auto j = static_cast<size_t>(seen - ids.begin());
        if (seen != ids.end() && j != k) readings.push_back({j, m});
    }
    return readings;
}

void CMultiRobotVisualSLAM::weighRobotReadings(size_t k, const std::vector<TRobotReading>& readings)
{
    if (readings.empty()) return;
    forEachParticle([&](size_t i) {
        auto& p = m_particles[i];
        const TPlanarTransform pose(p.d->poses[k]);
        for (const auto& r : readings) {
            const TMapMeasurement w = toMapFrame(r.m, pose);
            const TPose2D& other = p.d->poses[r.robot];
            const double log_w =
                robotReadingLogLikelihood(w.z - Eigen::Vector3d(other.x, other.y, 0), w.R);
            addLogWeight(p, log_w);
        }
    });
}

const std::vector<Eigen::Vector3d>& CMultiRobotVisualSLAM::particleNoise()
{
    const bool ahead = m_noise_ahead_drawn && m_noise_ahead.size() == m_particles.size();
    m_noise_ahead_drawn = false;
    if (ahead) {
        std::swap(m_noise, m_noise_ahead);
        return m_noise;
    }
    return core::drawStandardNormals(m_rng, m_particles.size(), m_noise, m_threads);
}

void CMultiRobotVisualSLAM::drawNoiseAhead()
{
    if (options.observation_selection == TOptions::TSelection::Random) return;
    core::drawStandardNormals(m_rng, m_particles.size(), m_noise_ahead, 1);
    m_noise_ahead_drawn = true;
}

void CMultiRobotVisualSLAM::sampleMotion(size_t k, const core::TOdometryGaussian& motion)
{
    const auto& noise = particleNoise();
    forEachParticle(
        [&](size_t i) {
            auto& pose = m_particles[i].d->poses[k];  // Alg. 1 line 18, p(x_t | x_{t-1}, u_t)
            const Eigen::Vector3d dx = motion.L * noise[i];
            pose = pose +
                   TPose2D(motion.mean.x + dx[0], motion.mean.y + dx[1], motion.mean.phi + dx[2]);
        },
        [this] { drawNoiseAhead(); });
}

std::vector<TMeasurementCandidates> CMultiRobotVisualSLAM::searchCandidates(
    const std::vector<TPose2D>& poses, double extra_xy, double extra_phi,
    const std::vector<TLandmarkMeasurement>& z)
{
    // the particles' spread around their mean pose widens the search; the sines and distances
    // on the threads, the sums in particle order (the same whatever the thread count)
    const size_t M = poses.size();
    std::vector<double> sin_phi(M), cos_phi(M);
    core::parallelFor(M, m_threads, [&](size_t i) {
        sin_phi[i] = std::sin(poses[i].phi);
        cos_phi[i] = std::cos(poses[i].phi);
    });
    double sx = 0, sy = 0, ss = 0, sc = 0;
    for (size_t i = 0; i < M; i++) {
        sx += poses[i].x;
        sy += poses[i].y;
        ss += sin_phi[i];
        sc += cos_phi[i];
    }
    const double n = static_cast<double>(M);
    const TPose2D mean_pose(sx / n, sy / n, std::atan2(ss, sc));
    std::vector<double> d_xy(M), d_phi(M);
    core::parallelFor(M, m_threads, [&](size_t i) {
        d_xy[i] = std::hypot(poses[i].x - mean_pose.x, poses[i].y - mean_pose.y);
        d_phi[i] = std::abs(mrpt::math::wrapToPi(poses[i].phi - mean_pose.phi));
    });
    double max_xy = *std::max_element(d_xy.begin(), d_xy.end());
    double max_phi = *std::max_element(d_phi.begin(), d_phi.end());
    max_xy += extra_xy;
    max_phi = std::min(max_phi + extra_phi, M_PI);

    // Alg. 1 lines 19-26 once per measurement: the shared pool's candidates (E ≤ E0, near the
    // point). Landmarks created from this frame are not candidates for its other points.
    std::vector<TMeasurementCandidates> candidates(z.size());
    for (size_t j = 0; j < z.size(); j++) {
        const double range_xy = std::hypot(z[j].z.x(), z[j].z.y());
        candidates[j] = m_template.findCandidates(z[j], toMapFrame(z[j], mean_pose),
                                                  max_xy + max_phi * range_xy);
        lastStepStats.candidates += candidates[j].candidates.size();
    }
    lastStepStats.measurements += z.size();
    return candidates;
}

std::vector<TPose2D> CMultiRobotVisualSLAM::posesOf(size_t k) const
{
    std::vector<TPose2D> poses(m_particles.size());
    forEachParticle([&](size_t i) { poses[i] = m_particles[i].d->poses[k]; });
    return poses;
}

void CMultiRobotVisualSLAM::forEachParticle(const std::function<void(size_t)>& body,
                                            const std::function<void()>& first) const
{
    core::parallelForAhead(
        m_particles.size(), m_threads,
        [&](size_t i, size_t end) {
            if (i + kParticlesAhead < end)
                core::prefetchObject(&m_particles[i + kParticlesAhead].d->poses);
            body(i);
        },
        first);
}

void CMultiRobotVisualSLAM::fuseMeasurements(size_t k, const std::vector<TLandmarkMeasurement>& z,
                                             CVisualLandmarksMap::TFrameAssociation rule)
{
    auto candidates = searchCandidates(posesOf(k), 0, 0, z);
    const size_t n = z.size();
    // Known correspondences look ids up in the pool as they go, so they run serially. Else a
    // new landmark waits: the particles fuse the rest in parallel, the pool hands out the ids
    // of the new ones in particle order, as a serial loop would, then they are created.
    const bool serial = m_template.insertionOptions.associate_by_identity;
    std::vector<TFusionResult> fused(m_particles.size() * n);
    // Alg. 1 lines 18-46, particle by particle so that its landmarks stay in the cache
    core::parallelFor(m_particles.size(), serial ? 1 : m_threads, [&](size_t i) {
        auto& p = m_particles[i];
        const TPlanarTransform pose(p.d->poses[k]);
        std::vector<TMapMeasurement> in_map(n);
        for (size_t j = 0; j < n; j++) in_map[j] = toMapFrame(z[j], pose);
        const auto r =
            p.d->map.fuseFrame(z, in_map, candidates, static_cast<unsigned>(k), rule, serial);
        std::copy(r.begin(), r.end(), fused.begin() + static_cast<std::ptrdiff_t>(i * n));
        for (size_t j = 0; j < n; j++) {
            addLogWeight(p, r[j].log_w);  // line 44 and line 11: the product over the team
            p.d->correspondences.push_back({static_cast<uint32_t>(k), r[j].id, z[j].track_id});
        }
    });
    std::vector<bool> created(fused.size());
    for (size_t i = 0; i < fused.size(); i++) created[i] = fused[i].created;
    if (!serial) createLandmarks(k, z, candidates, created);
    for (const bool c : created) (c ? lastStepStats.created : lastStepStats.associated)++;
}

void CMultiRobotVisualSLAM::proposeAndFuse(size_t k, const core::TOdometryGaussian& motion,
                                           const std::vector<TLandmarkMeasurement>& z,
                                           const std::vector<TRobotReading>& readings)
{
    // x̂ = x_{t-1} ⊕ u for every particle; the search also covers 3σ of the motion noise
    std::vector<TPose2D> predicted(m_particles.size());
    forEachParticle([&](size_t i) { predicted[i] = m_particles[i].d->poses[k] + motion.mean; });
    auto candidates =
        searchCandidates(predicted, 3 * std::sqrt(motion.cov(0, 0) + motion.cov(1, 1)),
                         3 * std::sqrt(motion.cov(2, 2)), z);

    // Per particle (in parallel): the proposal, its associations and weight, the sampled pose
    const size_t n = z.size();
    std::vector<std::optional<CVisualLandmarksMap::TAssociation>> assoc(m_particles.size() * n);
    std::vector<double> log_w(m_particles.size(), 0);
    const auto& noise = particleNoise();
    const bool joint = m_template.insertionOptions.joint_association;
    core::parallelForAhead(
        m_particles.size(), m_threads,
        [&](size_t i, size_t end) {
            // the first look-ups of the associations of this thread's next particles, ahead
            for (const auto stage :
                 {CVisualLandmarksMap::kPrefetchTable, CVisualLandmarksMap::kPrefetchEntries,
                  CVisualLandmarksMap::kPrefetchLandmarks}) {
                const size_t ahead = i + 3 - static_cast<size_t>(stage);
                if (ahead < end) m_particles[ahead].d->map.prefetchAssociation(candidates, stage);
            }
            auto& p = *m_particles[i].d;
            const auto assoc_i = assoc.begin() + static_cast<std::ptrdiff_t>(i * n);
            // prior N(x̂, J C Jᵀ), J the rotation of the increment into the map frame
            Eigen::Matrix3d Sigma = core::incrementCovInMapFrame(motion.cov, p.poses[k].phi);
            Eigen::Vector3d mu(predicted[i].x, predicted[i].y, predicted[i].phi);

            // Gaussian proposal p(x_t | x_{t-1}, u_t, z_t) by sequential EKF updates of the pose,
            // each measurement associated with the pose uncertainty so far in its gate; the
            // product of the marginals N(v; 0, Σ_l + R_w + H Σ Hᵀ) is the weight
            // p(z_t | x_{t-1}, u_t, map) (FastSLAM 2.0, ours for Gil et al. 2010)
            Eigen::Matrix3d HS;
            // the point measured from the current mean, with H Σ Hᵀ added to its covariance
            const auto linearize = [&](const TLandmarkMeasurement& m) {
                const TPose2D x(mu[0], mu[1], mu[2]);
                const TMapMeasurement w = toMapFrame(m, x);
                const Eigen::Matrix3d H = poseJacobian(w.z, x);
                HS = H * Sigma;
                return TMapMeasurement{w.z, w.R + HS * H.transpose()};
            };
            // the EKF update of the proposal with innovation v and its covariance S
            const auto correct = [&](const Eigen::Vector3d& v, const Eigen::Matrix3d& S) {
                const Eigen::Matrix3d K = HS.transpose() * Cholesky3(S).inverse();
                mu -= K * v;
                mu[2] = mrpt::math::wrapToPi(mu[2]);
                const Eigen::Matrix3d updated = Sigma - K * HS;
                Sigma = 0.5 * (updated + updated.transpose());
            };
            std::vector<TMapMeasurement> gated(n);
            std::vector<uint32_t> taken;
            if (joint) {  // every point against the prior, then the updates one by one
                for (size_t j = 0; j < n; j++) gated[j] = linearize(z[j]);
                std::copy_n(p.map.associateJointly(gated, candidates).begin(), n, assoc_i);
            }
            for (size_t j = 0; j < n; j++) {
                auto& a = assoc_i[static_cast<std::ptrdiff_t>(j)];
                gated[j] = linearize(z[j]);
                if (!joint) {
                    a = p.map.associate(gated[j], candidates[j], &taken, z[j].identity);
                    if (a) taken.push_back(a->id);
                } else if (a) {  // p(z_j | z_1..z_{j-1}) for the weight
                    a = p.map.evaluate(gated[j], a->id);
                }
                if (!a) {
                    log_w[i] += std::log(p.map.insertionOptions.p0);  // line 36
                    continue;
                }
                log_w[i] += a->log_likelihood;
                const TVisualLandmark& lm = *p.map.landmark(a->id);
                correct(gated[j].z - lm.mean, lm.cov + gated[j].R);
            }
            for (const auto& r : readings) {  // the seen robot's pose is exact in this particle
                const TMapMeasurement w = linearize(r.m);
                const Eigen::Vector3d v =
                    w.z - Eigen::Vector3d(p.poses[r.robot].x, p.poses[r.robot].y, 0);
                log_w[i] += robotReadingLogLikelihood(v, w.R);
                correct(v, w.R);
            }
            const Cholesky3 L(Sigma);
            if (!L.ok)
                throw std::runtime_error(options.robots[k] +
                                         ": proposal covariance is not positive definite");
            const Eigen::Vector3d x = mu + L.factor() * noise[i];
            p.poses[k] = TPose2D(x[0], x[1], mrpt::math::wrapToPi(x[2]));

            // The associated landmarks updated from the sampled pose while they are in the cache;
            // a new landmark waits for its id, and its correspondence with it
            const TPlanarTransform pose(p.poses[k]);
            for (size_t j = 0; j < n; j++) {
                const auto& a = assoc_i[static_cast<std::ptrdiff_t>(j)];
                if (a)
                    p.map.fuseAs(z[j], toMapFrame(z[j], pose), candidates[j],
                                 static_cast<unsigned>(k), a);
                p.correspondences.push_back(
                    {static_cast<uint32_t>(k), a ? a->id : 0, z[j].track_id});
            }
            addLogWeight(m_particles[i], log_w[i]);  // line 11: the product over the team
        },
        [this] { drawNoiseAhead(); });

    std::vector<bool> created(assoc.size());
    for (size_t i = 0; i < assoc.size(); i++) created[i] = !assoc[i];
    createLandmarks(k, z, candidates, created);
    for (const bool c : created) (c ? lastStepStats.created : lastStepStats.associated)++;
}

void CMultiRobotVisualSLAM::createLandmarks(size_t k, const std::vector<TLandmarkMeasurement>& z,
                                            std::vector<TMeasurementCandidates>& candidates,
                                            const std::vector<bool>& created)
{
    const size_t n = z.size();
    std::vector<size_t> creating;  // the particles that create any
    for (size_t i = 0; i < m_particles.size(); i++)
        for (size_t j = 0; j < n; j++) {
            if (!created[i * n + j]) continue;
            if (creating.empty() || creating.back() != i) creating.push_back(i);
            if (candidates[j].new_id) continue;  // the id an earlier particle was given
            const TPlanarTransform pose(m_particles[i].d->poses[k]);
            m_particles[i].d->map.reserveNewId(z[j], toMapFrame(z[j], pose), candidates[j]);
        }
    core::parallelFor(creating.size(), m_threads, [&](size_t c) {
        auto& d = *m_particles[creating[c]].d;
        const TPlanarTransform pose(d.poses[k]);
        const size_t first = d.correspondences.size() - n;  // robot k's, in the order of z
        for (size_t j = 0; j < n; j++)
            if (created[creating[c] * n + j])
                d.correspondences[first + j].landmark =
                    d.map
                        .fuseAs(z[j], toMapFrame(z[j], pose), candidates[j],
                                static_cast<unsigned>(k), std::nullopt)
                        .id;
    });
}

void CMultiRobotVisualSLAM::runStep(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options, bool optimal)
{
    lastStepStats = TStepStats();
    const size_t K = robotCount();
    if (!action || action->size() != K)
        throw std::runtime_error("a step needs one odometry action per robot (" +
                                 std::to_string(K) + "), got " +
                                 std::to_string(action ? action->size() : 0));
    double timestamp = 0;
    for (size_t k = 0; k < K; k++) {  // Alg. 1 lines 7-9
        const auto* odo = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(&action->get(k));
        if (!odo)
            throw std::runtime_error("action " + std::to_string(k) +
                                     " of a step is not a CActionRobotMovement2D");
        timestamp = std::max(timestamp, mrpt::Clock::toDouble(odo->timestamp));
        const core::TOdometryGaussian motion = motionOf(k, *odo);
        const auto z =
            observation ? measurementsOf(k, *observation) : std::vector<TLandmarkMeasurement>();
        const auto readings =
            observation ? robotReadingsOf(k, *observation) : std::vector<TRobotReading>();
        lastStepStats.robot_readings += readings.size();
        if (m_observer) m_observer->onRobotStep(m_steps + 1, k, motion, z, readings);
        if (z.empty() && readings.empty() && core::ActionFrameSource::standsStill(*odo))
            continue;  // no reading of this robot since the last step (a live team)
        const auto bySensor = splitBySensor(z);
        using TRule = CVisualLandmarksMap::TFrameAssociation;
        if (optimal && !(z.empty() && readings.empty())) {
            proposeAndFuse(k, motion, bySensor.empty() ? z : bySensor.front(), readings);
            for (size_t s = 1; s < bySensor.size(); s++)
                fuseMeasurements(k, bySensor[s], TRule::DistinctInOrder);  // as in the proposal
        } else {
            sampleMotion(k, motion);
            for (const auto& of_sensor : bySensor) fuseMeasurements(k, of_sensor, TRule::OneByOne);
            weighRobotReadings(k, readings);
        }
        // after the last robot the framework resamples (Alg. 1 line 13)
        if (options.resample_per_robot && k + 1 < K && ESS() < pf_options.BETA)
            performResampling(pf_options);
    }
    // a memory-bound loop: what particle i + 2·kAhead appends loaded, and then its path's slot
    constexpr size_t kAhead = kParticlesAhead;
    core::parallelForAhead(m_particles.size(), m_threads, [&](size_t i, size_t end) {
        if (i + 2 * kAhead < end) {
            const TTeamParticle& ahead = *m_particles[i + 2 * kAhead].d;
            core::prefetchObject(&ahead.poses);
            core::prefetchObject(&ahead.path);
            core::prefetchObject(&ahead.correspondences);
        }
        if (i + kAhead < end) m_particles[i + kAhead].d->path.prefetchAppend();
        auto& d = *m_particles[i].d;
        d.path.append(timestamp, d.poses, d.correspondences);
        d.correspondences.resize(0);  // keeps its storage for the next step
    });
    m_steps++;
}

void CMultiRobotVisualSLAM::prediction_and_update_pfStandardProposal(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options)
{
    runStep(action, observation, pf_options, false);
}

void CMultiRobotVisualSLAM::prediction_and_update_pfOptimalProposal(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options)
{
    runStep(action, observation, pf_options, true);
}

}  // namespace mrpt_vslam::multirobot
