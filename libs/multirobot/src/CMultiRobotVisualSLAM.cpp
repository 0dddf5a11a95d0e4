#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/system/string_utils.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

using mrpt::math::TPose2D;

namespace {
TPose2D compose(const TPose2D& a, const TPose2D& b)
{
    const double c = std::cos(a.phi), s = std::sin(a.phi);
    return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, mrpt::math::wrapToPi(a.phi + b.phi)};
}

void requireKey(bool ok, const std::string& section, const char* key, const char* what)
{
    if (!ok)
        throw std::invalid_argument("[" + section + "] " + key + ": " + what);
}
}  // namespace

void CMultiRobotVisualSLAM::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                         const std::string& section)
{
    const std::string names = cfg.read_string(section, "robots", "");
    if (!names.empty()) {
        robots.clear();
        mrpt::system::tokenize(names, " \t,", robots);
    }
    MRPT_LOAD_CONFIG_VAR(landmarks_suffix, string, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_observations_per_robot, uint64_t, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_motion_std_xy, double, cfg, section);
    min_motion_std_phi = mrpt::DEG2RAD(
        cfg.read_double(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(min_motion_std_phi)));
    MRPT_LOAD_CONFIG_VAR(initial_std_xy, double, cfg, section);
    initial_std_phi = mrpt::DEG2RAD(
        cfg.read_double(section, "initial_std_phi_deg", mrpt::RAD2DEG(initial_std_phi)));
    MRPT_LOAD_CONFIG_VAR(resample_per_robot, bool, cfg, section);

    requireKey(!robots.empty() && robots.size() <= 32, section, "robots",
               "must name 1 to 32 robots");
    for (size_t i = 0; i < robots.size(); i++)
        requireKey(std::count(robots.begin(), robots.end(), robots[i]) == 1, section, "robots",
                   "must not repeat a name");
    requireKey(!landmarks_suffix.empty(), section, "landmarks_suffix", "must not be empty");
    requireKey(max_observations_per_robot >= 1, section, "max_observations_per_robot",
               "must be >= 1");
    requireKey(min_motion_std_xy > 0, section, "min_motion_std_xy", "must be > 0");
    requireKey(min_motion_std_phi > 0, section, "min_motion_std_phi_deg", "must be > 0");
    requireKey(initial_std_xy >= 0, section, "initial_std_xy", "must be >= 0");
    requireKey(initial_std_phi >= 0, section, "initial_std_phi_deg", "must be >= 0");
}

void CMultiRobotVisualSLAM::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                       const std::string& section) const
{
    std::string names;
    for (const auto& r : robots) names += (names.empty() ? "" : " ") + r;
    cfg.write(section, "robots", names);
    cfg.write(section, "landmarks_suffix", landmarks_suffix);
    cfg.write(section, "max_observations_per_robot", max_observations_per_robot);
    cfg.write(section, "min_motion_std_xy", min_motion_std_xy);
    cfg.write(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(min_motion_std_phi));
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
                                    " start poses for " + std::to_string(robotCount()) +
                                    " robots");
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
        d.poses = start_poses;
        for (size_t k = 1; k < d.poses.size(); k++) {
            d.poses[k].x += options.initial_std_xy * m_rng.drawGaussian1D_normalized();
            d.poses[k].y += options.initial_std_xy * m_rng.drawGaussian1D_normalized();
            d.poses[k].phi = mrpt::math::wrapToPi(
                d.poses[k].phi + options.initial_std_phi * m_rng.drawGaussian1D_normalized());
        }
        d.path = std::make_shared<const TTeamPathNode>(timestamp, d.poses, nullptr);
        d.map = m_template;
        d.accumulated_log_w = 0;
    }
}

const TTeamParticle& CMultiRobotVisualSLAM::bestParticle() const
{
    const auto best = std::max_element(m_particles.begin(), m_particles.end(),
                                       [](const auto& a, const auto& b) {
                                           return a.d->accumulated_log_w < b.d->accumulated_log_w;
                                       });
    return *best->d;
}

std::vector<std::pair<double, TPose2D>> CMultiRobotVisualSLAM::pathOf(const TTeamParticle& p,
                                                                       size_t robot)
{
    std::vector<std::pair<double, TPose2D>> path;
    for (const TTeamPathNode* n = p.path.get(); n; n = n->previous.get())
        path.emplace_back(n->timestamp, n->poses.at(robot));
    std::reverse(path.begin(), path.end());
    return path;
}

void CMultiRobotVisualSLAM::sampleMotion(size_t k, const mrpt::obs::CActionRobotMovement2D& odometry)
{
    mrpt::math::CMatrixDouble33 cov;
    mrpt::poses::CPose2D mean;
    odometry.poseChange->getCovarianceAndMean(cov, mean);
    Eigen::Matrix3d C = cov.asEigen();
    C.diagonal() += Eigen::Vector3d(options.min_motion_std_xy * options.min_motion_std_xy,
                                    options.min_motion_std_xy * options.min_motion_std_xy,
                                    options.min_motion_std_phi * options.min_motion_std_phi);
    if (!C.allFinite() || !std::isfinite(mean.x()) || !std::isfinite(mean.y()) ||
        !std::isfinite(mean.phi()))
        throw std::runtime_error(options.robots[k] +
                                 ": odometry with a non-finite increment or covariance");
    const Eigen::LLT<Eigen::Matrix3d> llt(C);
    if (llt.info() != Eigen::Success)
        throw std::runtime_error(options.robots[k] + ": odometry covariance is not positive definite");
    const Eigen::Matrix3d L = llt.matrixL();
    for (auto& p : m_particles) {  // Alg. 1 line 18, p(x_t | x_{t-1}, u_t) per robot
        Eigen::Vector3d n;
        for (int i = 0; i < 3; i++) n[i] = m_rng.drawGaussian1D_normalized();
        const Eigen::Vector3d dx = L * n;
        p.d->poses[k] = compose(p.d->poses[k],
                                TPose2D(mean.x() + dx[0], mean.y() + dx[1], mean.phi() + dx[2]));
    }
}

void CMultiRobotVisualSLAM::fuseMeasurements(size_t k, const std::vector<TLandmarkMeasurement>& z)
{
    if (z.empty()) return;
    // the particles' spread around their mean pose of robot k: widens the candidate search
    double sx = 0, sy = 0, ss = 0, sc = 0;
    for (const auto& p : m_particles) {
        sx += p.d->poses[k].x;
        sy += p.d->poses[k].y;
        ss += std::sin(p.d->poses[k].phi);
        sc += std::cos(p.d->poses[k].phi);
    }
    const double n = static_cast<double>(m_particles.size());
    const TPose2D mean_pose(sx / n, sy / n, std::atan2(ss, sc));
    double max_xy = 0, max_phi = 0;
    for (const auto& p : m_particles) {
        max_xy = std::max(max_xy, std::hypot(p.d->poses[k].x - mean_pose.x,
                                             p.d->poses[k].y - mean_pose.y));
        max_phi = std::max(max_phi,
                           std::abs(mrpt::math::wrapToPi(p.d->poses[k].phi - mean_pose.phi)));
    }

    // Alg. 1 lines 19-26 once per measurement: the shared pool's candidates (E ≤ E0, near the
    // point). Landmarks created from this frame are not candidates for its other points.
    std::vector<TMeasurementCandidates> candidates(z.size());
    for (size_t j = 0; j < z.size(); j++) {
        const double range_xy = std::hypot(z[j].z.x(), z[j].z.y());
        candidates[j] = m_template.findCandidates(
            z[j], toMapFrame(z[j], mean_pose), max_xy + std::min(max_phi, M_PI) * range_xy);
        lastStepStats.candidates += candidates[j].candidates.size();
    }
    // Alg. 1 lines 18-46, particle by particle so that its landmarks stay in the cache
    for (auto& p : m_particles) {
        const TPlanarTransform pose(p.d->poses[k]);
        for (size_t j = 0; j < z.size(); j++) {
            const TFusionResult r = p.d->map.fuse(z[j], toMapFrame(z[j], pose), candidates[j],
                                                  static_cast<unsigned>(k));
            p.log_w += r.log_w;  // line 44 and line 11: the product over the team
            p.d->accumulated_log_w += r.log_w;
            (r.created ? lastStepStats.created : lastStepStats.associated)++;
        }
    }
    lastStepStats.measurements += z.size();
}

void CMultiRobotVisualSLAM::prediction_and_update_pfStandardProposal(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf_options)
{
    lastStepStats = TStepStats();
    const size_t K = robotCount();
    if (!action || action->size() != K)
        throw std::runtime_error("a step needs one odometry action per robot (" +
                                 std::to_string(K) + "), got " +
                                 std::to_string(action ? action->size() : 0));
    double timestamp = 0;
    for (size_t k = 0; k < K; k++) {  // Alg. 1 lines 7-9
        const auto* odo =
            dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(&action->get(k));
        if (!odo) throw std::runtime_error("action " + std::to_string(k) +
                                           " of a step is not a CActionRobotMovement2D");
        timestamp = std::max(timestamp, mrpt::Clock::toDouble(odo->timestamp));
        sampleMotion(k, *odo);
        if (!observation) continue;
        const auto obs = observation->getObservationBySensorLabelAs<
            mrpt::obs::CObservationVisualLandmarks::Ptr>(options.robots[k] +
                                                         options.landmarks_suffix);
        if (obs)
            fuseMeasurements(
                k, selectNearest(measurementsFromObservation(*obs),
                                 options.max_observations_per_robot));
        // after the last robot the framework resamples (Alg. 1 line 13)
        if (options.resample_per_robot && k + 1 < K && ESS() < pf_options.BETA)
            performResampling(pf_options);
    }
    for (auto& p : m_particles)
        p.d->path = std::make_shared<const TTeamPathNode>(timestamp, p.d->poses, p.d->path);
}

}  // namespace mrpt_vslam::multirobot
