#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/KLDSampling.h>
#include <mrpt_vslam/core/ParallelFor.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace mrpt_vslam::omni_fastslam {

using mrpt::math::TPose2D;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
/// The factor on P_new's squared Mahalanobis distance beyond which Alg. 2 skips a pair.
constexpr double kSkipFactor2 = 4;

TPose2D plus(const TPose2D& x, const Eigen::Vector3d& dx)
{
    return {x.x + dx[0], x.y + dx[1], mrpt::math::wrapToPi(x.phi + dx[2])};
}
}  // namespace

void COmniFastSLAM::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                 const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(bearings_label, string, cfg, section);
    motion_noise_floor.loadFromConfigFile(cfg, section);
    prediction_margin = mrpt::DEG2RAD(
        cfg.read_double(section, "prediction_margin_deg", mrpt::RAD2DEG(prediction_margin)));
    if (!(prediction_margin >= 0))
        throw std::invalid_argument("[" + section + "] prediction_margin_deg must be >= 0");
    const int maxBearings =
        cfg.read_int(section, "max_bearings_per_frame", static_cast<int>(max_bearings_per_frame));
    if (maxBearings < 1)
        throw std::invalid_argument("[" + section + "] max_bearings_per_frame must be >= 1");
    max_bearings_per_frame = static_cast<unsigned int>(maxBearings);
}

void COmniFastSLAM::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                               const std::string& section) const
{
    cfg.write(section, "bearings_label", bearings_label);
    motion_noise_floor.saveToConfigFile(cfg, section);
    cfg.write(section, "prediction_margin_deg", mrpt::RAD2DEG(prediction_margin));
    cfg.write(section, "max_bearings_per_frame", max_bearings_per_frame);
}

size_t TAssociationTally::labelled() const
{
    size_t n = 0;
    for (const auto& [landmark, ids] : counts)
        for (const auto& [id, count] : ids) n += count;
    return n;
}

size_t TAssociationTally::wrong() const
{
    size_t n = 0;
    for (const auto& [landmark, ids] : counts) {
        uint32_t total = 0, most = 0;
        for (const auto& [id, count] : ids) {
            total += count;
            most = std::max(most, count);
        }
        n += total - most;
    }
    return n;
}

COmniFastSLAM::COmniFastSLAM(const CCeilingLightsMap& map_template, size_t particle_count,
                             uint32_t seed)
{
    if (particle_count == 0) throw std::invalid_argument("particle count must be > 0");
    m_rng.randomize(seed);
    m_particles.resize(particle_count);
    for (auto& p : m_particles) {
        p.d.reset(new TOmniFastSLAMParticle);
        p.d->map = map_template;
    }
}

void COmniFastSLAM::reset(const TPose2D& robot_in_map, double timestamp)
{
    TOmniFastSLAMPath start;
    start.append(timestamp, robot_in_map);
    for (auto& p : m_particles) {
        p.log_w = 0;
        p.d->robot_in_map = robot_in_map;
        p.d->path = start;
        p.d->accumulated_log_w = 0;
    }
    if (m_observer) m_observer->onReset(robot_in_map, timestamp);
}

std::vector<std::pair<double, TPose2D>> COmniFastSLAM::pathOf(const TOmniFastSLAMParticle& p)
{
    std::vector<std::pair<double, TPose2D>> path;
    for (const auto* s : p.path.stepsOldestFirst())
        path.emplace_back(s->timestamp, s->state.robot_in_map);
    return path;
}

TAssociationTally COmniFastSLAM::associationsOf(const TOmniFastSLAMParticle& p)
{
    TAssociationTally tally;
    p.path.forEachNewestFirst([&](const TOmniFastSLAMPath::TStep& s) {
        for (const auto& c : s.state.correspondences)
            if (c.hidden_id >= 0) tally.counts[c.landmark_id][c.hidden_id]++;
    });
    return tally;
}

std::vector<TBearingMeasurement> COmniFastSLAM::measurementsFromFrame(
    const mrpt::obs::CSensoryFrame* sf, const CCeilingLightsMap& map, double& timestamp) const
{
    if (!sf) return {};
    for (const auto& obs : *sf) {
        const auto* b = dynamic_cast<const mrpt::obs::CObservationBearingRange*>(obs.get());
        if (!b || (!options.bearings_label.empty() && b->sensorLabel != options.bearings_label))
            continue;
        if (b->sensedData.size() > options.max_bearings_per_frame)
            throw std::runtime_error(mrpt::format(
                "%s: %zu bearings in one frame, more than max_bearings_per_frame = %u",
                b->sensorLabel.empty() ? "CObservationBearingRange" : b->sensorLabel.c_str(),
                b->sensedData.size(), options.max_bearings_per_frame));
        timestamp = mrpt::Clock::toDouble(b->timestamp);
        return map.measurementsFromObservation(*b);
    }
    return {};
}

TPose2D COmniFastSLAM::sampleMotion(const TPose2D& from, const core::TOdometryGaussian& motion,
                                    const Eigen::Vector3d& noise)
{
    return from + plus(motion.mean, motion.L * noise);
}

TPose2D COmniFastSLAM::sampleFastSLAM2Proposal(const TOmniFastSLAMParticle& p,
                                               const std::vector<TBearingMeasurement>& z,
                                               const core::TOdometryGaussian& motion,
                                               const Eigen::Matrix3d& R,
                                               const Eigen::Vector3d& noise,
                                               std::vector<int>& landmark_of_measurement) const
{
    const auto& map = p.map;
    const auto& lms = map.landmarks();
    const auto model = map.measurementModel();

    // x̂_t (R_t comes from the caller)
    const TPose2D x_hat = p.robot_in_map + motion.mean;
    const auto at_x_hat = model.atPose(x_hat);
    const Eigen::Matrix3d R_inv = R.inverse();
    const double p_new_mahalanobis2 = map.insertionOptions.p_new_mahalanobis2;

    // Alg. 2: φ_{l,j} for every measurement and landmark
    Eigen::MatrixXd log_phi = Eigen::MatrixXd::Constant(z.size(), lms.size(), -kInf);
    for (size_t j = 0; j < lms.size(); j++) {
        const auto pred = at_x_hat.predictWithJacobians(lms[j].mean);  // lines 2-4
        if (!pred.valid || !map.couldBeObserved(pred.z, options.prediction_margin) ||
            !map.isWithinReadingRange(pred.point_in_camera))
            continue;
        const Eigen::Matrix2d HmSHm = pred.H_m * lms[j].cov * pred.H_m.transpose();
        const Eigen::Matrix2d HxRHx = pred.H_x * R * pred.H_x.transpose();
        for (size_t l = 0; l < z.size(); l++) {
            const Eigen::Matrix2d Q_jl = z[l].Q + HmSHm;  // line 6
            // A pair that cannot beat a new landmark is never assigned: skipped when the
            // innovation left after the shift of line 8, Q S⁻¹ ν to first order (S = Q + H_x R
            // H_xᵀ), is more than twice P_new's Mahalanobis distance away.
            const Eigen::Vector2d S_inv_nu =
                (Q_jl + HxRHx).inverse() * BearingMeasurementModel::innovation(z[l].z, pred.z);
            if (S_inv_nu.dot(Q_jl * S_inv_nu) > kSkipFactor2 * p_new_mahalanobis2) continue;
            const Eigen::Matrix2d Q_inv = Q_jl.inverse();
            const Eigen::Matrix3d Sigma_x =
                (pred.H_x.transpose() * Q_inv * pred.H_x + R_inv).inverse();  // line 7
            const Eigen::Vector3d dx = Sigma_x * pred.H_x.transpose() * Q_inv *
                                       BearingMeasurementModel::innovation(z[l].z, pred.z);
            const Eigen::Vector2d z_hat = model.predict(lms[j].mean, plus(x_hat, dx));  // 9-10
            log_phi(l, j) = map.measurementLogLikelihood(
                BearingMeasurementModel::innovation(z[l].z, z_hat), Q_jl);  // line 11
        }
    }

    // Sec. III-C, level 1
    Eigen::VectorXd log_p_new(z.size());
    for (size_t l = 0; l < z.size(); l++) log_p_new(l) = map.logPNew(z[l]);
    landmark_of_measurement = CCeilingLightsMap::solveAssociation(
        log_phi, log_p_new, map.insertionOptions.association_method);

    // Alg. 3: fuse associated type-I landmarks, lowest covariance first (ties: lower φ)
    std::vector<size_t> order;
    for (size_t l = 0; l < z.size(); l++) {
        const int j = landmark_of_measurement[l];
        if (j >= 0 && lms[j].type == TLandmarkType::TypeI) order.push_back(l);
    }
    if (order.empty()) return sampleMotion(p.robot_in_map, motion, noise);  // line 2
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        const double ta = lms[landmark_of_measurement[a]].cov.trace();
        const double tb = lms[landmark_of_measurement[b]].cov.trace();
        return ta != tb ? ta < tb : z[a].z[0] < z[b].z[0];
    });
    TPose2D mu = x_hat;         // line 5
    Eigen::Matrix3d Sigma = R;  // line 4
    for (const size_t l : order) {
        const auto& lm = lms[landmark_of_measurement[l]];
        // relinearised at the current mean: the sequential form of lines 8-9
        const auto pred = model.predictWithJacobians(lm.mean, mu);
        if (!pred.valid) continue;
        const Eigen::Matrix2d Q = z[l].Q + pred.H_m * lm.cov * pred.H_m.transpose();
        const Eigen::Matrix2d Q_inv = Q.inverse();
        Sigma = (pred.H_x.transpose() * Q_inv * pred.H_x + Sigma.inverse()).inverse();  // line 8
        Sigma = 0.5 * (Sigma + Sigma.transpose());
        mu = plus(mu, Sigma * pred.H_x.transpose() * Q_inv *
                          BearingMeasurementModel::innovation(z[l].z, pred.z));  // line 9
    }
    // line 14: x_t ~ N(μ_xt, Σ_xt)
    const Eigen::Matrix3d L = Sigma.llt().matrixL();
    return plus(mu, L * noise);
}

double COmniFastSLAM::updateParticle(TOmniFastSLAMParticle& p, const TPose2D& x_t, double timestamp,
                                     const std::vector<TBearingMeasurement>& z,
                                     const std::vector<int>& landmark_of_measurement,
                                     const Eigen::Matrix3d& R_t)
{
    TOmniFastSLAMStep step{x_t, {}};
    for (size_t l = 0; l < z.size(); l++)
        if (const int j = landmark_of_measurement[l]; j >= 0)
            step.correspondences.push_back(
                {p.map.landmarks()[j].id, z[l].hidden_id, static_cast<uint32_t>(l)});
    // Alg. 4 lines 1-27
    const double log_w_inc = p.map.updateLandmarks(z, x_t, landmark_of_measurement, R_t);
    // Sec. III-C level 2, Alg. 4 lines 28-29
    TLightAssociation assoc;
    assoc.landmark_of_measurement = landmark_of_measurement;
    assoc.candidate_of_measurement = p.map.associateCandidates(z, x_t, landmark_of_measurement);
    p.map.updateCandidates(z, x_t, assoc);
    p.map.updateLandmarksType();

    p.robot_in_map = x_t;
    p.path.append(timestamp, std::move(step));
    return log_w_inc;
}

void COmniFastSLAM::runStep(const mrpt::obs::CActionCollection* action,
                            const mrpt::obs::CSensoryFrame* sf, bool fastslam2,
                            const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf)
{
    // CParticleFilter leaves the resampling to us when adaptiveSampleSize is set; the weights
    // are those it normalised after the previous step
    if (pf.adaptiveSampleSize && m_particles.size() > 0 && ESS() < pf.BETA) {
        std::vector<double> log_w;
        std::vector<TPose2D> poses;
        for (const auto& part : m_particles) {
            log_w.push_back(part.log_w);
            poses.push_back(part.d->robot_in_map);
        }
        performSubstitution(core::kldResample(log_w, poses, kld, m_rng));
    }
    const core::TOdometryGaussian motion = core::TOdometryGaussian::from(
        action ? action->getBestMovementEstimation().get() : nullptr, options.motion_noise_floor);
    lastStepStats = {};
    if (m_observer && !m_particles.empty()) {
        double timestamp = 0;
        m_observer->onStep(motion, measurementsFromFrame(sf, m_particles[0].d->map, timestamp));
    }
    const auto& noise = core::drawStandardNormals(m_rng, m_particles.size(), m_noise, m_threads);
    std::vector<size_t> measured(m_particles.size()), associated(m_particles.size());
    core::parallelFor(m_particles.size(), m_threads, [&](size_t i) {
        auto& part = m_particles[i];
        auto& p = *part.d;
        double timestamp = p.path.empty() ? 0 : p.path.newest().timestamp;
        const auto z = measurementsFromFrame(sf, p.map, timestamp);
        measured[i] = z.size();

        std::vector<int> assoc;
        TPose2D x_t;
        Eigen::Matrix3d R_t = Eigen::Matrix3d::Zero();
        if (fastslam2) {
            // R_t: the odometry covariance in the map frame
            R_t = core::incrementCovInMapFrame(motion.cov, p.robot_in_map.phi);
            x_t = sampleFastSLAM2Proposal(p, z, motion, R_t, noise[i], assoc);
        } else {
            x_t = sampleMotion(p.robot_in_map, motion, noise[i]);
            Eigen::VectorXd log_p_new(z.size());
            for (size_t l = 0; l < z.size(); l++) log_p_new(l) = p.map.logPNew(z[l]);
            assoc =
                CCeilingLightsMap::solveAssociation(p.map.landmarkLogLikelihoods(z, x_t), log_p_new,
                                                    p.map.insertionOptions.association_method);
        }
        associated[i] = static_cast<size_t>(
            std::count_if(assoc.begin(), assoc.end(), [](int j) { return j >= 0; }));
        addLogWeight(part, updateParticle(p, x_t, timestamp, z, assoc, R_t));
    });
    lastStepStats.measurements = measured.back();
    for (const size_t n : associated) {
        lastStepStats.associated_to_landmarks += n;
        if (n == 0) lastStepStats.motion_only_samples++;
    }
}

void COmniFastSLAM::prediction_and_update_pfStandardProposal(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf)
{
    runStep(action, observation, false, pf);
}

void COmniFastSLAM::prediction_and_update_pfOptimalProposal(
    const mrpt::obs::CActionCollection* action, const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& pf)
{
    runStep(action, observation, true, pf);
}

}  // namespace mrpt_vslam::omni_fastslam
