#include <mrpt/core/exceptions.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>
#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace mrpt_vslam::omni_fastslam {

namespace {
/// Far end of a planar candidate's ray when max_cross_point_range is 0 (no limit) [m]
constexpr double kUnlimitedDepth = 1e3;

/// XY distance between a robot pose and a point [m].
double horizontalDistance(const mrpt::math::TPose2D& robot, const Eigen::Vector3d& p)
{
    return std::hypot(p.x() - robot.x, p.y() - robot.y);
}
}  // namespace

double CCeilingLightsMap::updateLandmarks(const std::vector<TBearingMeasurement>& z,
                                          const mrpt::math::TPose2D& robot_in_map,
                                          const std::vector<int>& landmark_of_measurement,
                                          const Eigen::Matrix3d& robot_pose_cov)
{
    ASSERT_EQUAL_(landmark_of_measurement.size(), z.size());
    std::vector<int> measurement_of_landmark(m_landmarks.size(), -1);
    for (size_t l = 0; l < z.size(); l++) {
        const int j = landmark_of_measurement[l];
        if (j < 0) continue;
        ASSERTMSG_(j < static_cast<int>(m_landmarks.size()), "landmark index out of range");
        ASSERTMSG_(measurement_of_landmark[j] < 0, "two measurements associated to one landmark");
        measurement_of_landmark[j] = static_cast<int>(l);
    }

    const double log_miss = std::log(1 - likelihoodOptions.p_in);
    const auto model = measurementModel();
    const auto at = model.atPose(robot_in_map);
    double log_w = 0;  // Alg. 4 line 1: w = 1
    for (size_t j = 0; j < m_landmarks.size(); j++) {
        auto& lm = m_landmarks[j];
        const int l = measurement_of_landmark[j];
        if (l < 0) {
            // Alg. 4 lines 19-24: unchanged Gaussian; counter −1 inside the perceptual range
            if (isInPerceptualRange(lm.mean, at)) {
                lm.counter--;
                if (usesForWeight(lm)) log_w += log_miss;
            }
            continue;
        }
        Eigen::Vector2d nu;
        Eigen::Matrix2d S;
        BearingMeasurementModel::Matrix23 H_x;
        if (!ekfUpdate(lm, z[l], at, nu, S, H_x)) continue;
        lm.counter += static_cast<int>(insertionOptions.hit_increment);
        if (horizontalDistance(robot_in_map, lm.mean) < insertionOptions.d_min)
            lm.consecutive_close++;
        else
            lm.consecutive_close = 0;
        // lines 11-17: weight from type I landmarks only; L = H_x R H_xᵀ + Q̃
        if (usesForWeight(lm))
            log_w += measurementLogLikelihood(nu, H_x * robot_pose_cov * H_x.transpose() + S);
    }
    return log_w;
}

bool CCeilingLightsMap::ekfUpdate(TLightLandmark& lm, const TBearingMeasurement& m,
                                  const BearingMeasurementModel::AtPose& at,
                                  Eigen::Vector2d& innovation, Eigen::Matrix2d& S,
                                  BearingMeasurementModel::Matrix23& H_x) const
{
    const auto pred = at.predictWithJacobians(lm.mean);  // lines 4-5
    if (!pred.valid) return false;
    // line 6: Q̃ = Q + H_m Σ H_mᵀ
    S = m.Q + pred.H_m * lm.cov * pred.H_m.transpose();
    // line 7: K = Σ H_mᵀ Q̃⁻¹
    const Eigen::Matrix<double, 3, 2> K = lm.cov * pred.H_m.transpose() * S.inverse();
    innovation = BearingMeasurementModel::innovation(m.z, pred.z);
    // line 8: μ ← μ + K (z − z̃)
    lm.mean += K * innovation;
    // line 9, Joseph form: Σ ← (I − K H) Σ (I − K H)ᵀ + K Q Kᵀ, then symmetrized
    const Eigen::Matrix3d I_KH = Eigen::Matrix3d::Identity() - K * pred.H_m;
    const Eigen::Matrix3d cov = I_KH * lm.cov * I_KH.transpose() + K * m.Q * K.transpose();
    lm.cov = 0.5 * (cov + cov.transpose());
    H_x = pred.H_x;
    return true;
}

void CCeilingLightsMap::addCandidateObservation(TCandidateLight& cand,
                                                const TCandidateObservation& obs) const
{
    const auto model = measurementModel();
    using AtPose = BearingMeasurementModel::AtPose;
    // log p(z_i | point, x_i) and the squared Mahalanobis distance of one measurement, `at` the
    // model at x_i
    auto term = [this](const Eigen::Vector3d& point, const TCandidateObservation& o,
                       const AtPose& at, double& mahalanobis2) {
        const Eigen::Vector2d nu =
            BearingMeasurementModel::innovation(o.measurement.z, at.predict(point));
        mahalanobis2 = nu.dot(o.measurement.Q.inverse() * nu);
        return measurementLogLikelihood(nu, o.measurement.Q);
    };

    if (cand.observations.size() >= insertionOptions.max_candidate_measurements) {
        const auto& oldest = cand.observations.front();
        auto& xs = cand.cross_points;
        xs.erase(std::remove_if(xs.begin(), xs.end(),
                                [&](const auto& x) { return x.step_first == oldest.step; }),
                 xs.end());
        const AtPose at_oldest = model.atPose(oldest.robot_in_map);
        for (auto& x : xs) {
            double m2;
            x.sum_log_prob -= term(x.point, oldest, at_oldest, m2);
            x.sum_mahalanobis2 -= m2;
        }
        cand.observations.erase(cand.observations.begin());
    }

    cand.observations.push_back(obs);
    std::vector<AtPose> at_each;  // the model at each observation's pose, obs's last
    at_each.reserve(cand.observations.size());
    for (const auto& o : cand.observations) at_each.push_back(model.atPose(o.robot_in_map));
    for (auto& x : cand.cross_points) {
        double m2;
        x.sum_log_prob += term(x.point, obs, at_each.back(), m2);
        x.sum_mahalanobis2 += m2;
    }

    // Cross-points of the new measurement with each earlier one (Sec. III-F(1), Fig. 3)
    const Eigen::Vector3d origin = model.rayOriginInMap(obs.robot_in_map);
    const Eigen::Vector3d dir = model.rayDirectionInMap(obs.measurement.z, obs.robot_in_map);
    for (size_t i = 0; i + 1 < cand.observations.size(); i++) {
        const auto& earlier = cand.observations[i];
        const Eigen::Vector3d o1 = model.rayOriginInMap(earlier.robot_in_map);
        const auto rx = computeRayCrossPoint(
            o1, model.rayDirectionInMap(earlier.measurement.z, earlier.robot_in_map), origin, dir);
        if (rx.parallel) continue;
        TCandidateCrossPoint x;
        x.point = rx.point;
        x.step_first = earlier.step;
        x.step_second = obs.step;
        x.angle = rx.angle;
        x.gap = rx.gap;
        // test (b): in front of both cameras and above them (spherical) or in front of both
        // bearing lines (planar), within max_cross_point_range
        x.in_front = crossPointInFront(rx, o1, origin, crossPointLimits());
        for (size_t k = 0; k < cand.observations.size(); k++) {
            double m2;
            x.sum_log_prob += term(x.point, cand.observations[k], at_each[k], m2);
            x.sum_mahalanobis2 += m2;
        }
        cand.cross_points.push_back(x);
    }
    refreshCrossPointValidity(cand);
    if (model.isPlanar()) updateDepthInterval(cand);
}

void CCeilingLightsMap::updateDepthInterval(TCandidateLight& cand) const
{
    // Samples of the last ray between the range limits; a depth agrees when every earlier
    // measurement is within the P_new gate of its projection.
    constexpr int kSamples = 64;
    const auto model = measurementModel();
    const auto& last = cand.observations.back();
    const Eigen::Vector3d origin = model.rayOriginInMap(last.robot_in_map);
    const Eigen::Vector3d dir = model.rayDirectionInMap(last.measurement.z, last.robot_in_map);
    const TSensorLimits limits = sensorLimitsInUse();
    const double s_lo = std::max(limits.min_range, 0.05);
    const double s_hi = limits.max_range > 0 ? limits.max_range : kUnlimitedDepth;
    cand.depth_min = s_hi;
    cand.depth_max = s_lo;
    std::vector<BearingMeasurementModel::AtPose> at_each;  // the model at each earlier pose
    for (size_t k = 0; k + 1 < cand.observations.size(); k++)
        at_each.push_back(model.atPose(cand.observations[k].robot_in_map));
    bool any = false;
    for (int i = 0; i < kSamples; i++) {
        // geometric spacing: the azimuths change fastest near the robot
        const double s = s_lo * std::pow(s_hi / s_lo, i / (kSamples - 1.0));
        const Eigen::Vector3d point = origin + s * dir;
        bool agrees = true;
        for (size_t k = 0; agrees && k + 1 < cand.observations.size(); k++) {
            const auto& o = cand.observations[k];
            const Eigen::Vector2d nu =
                BearingMeasurementModel::innovation(o.measurement.z, at_each[k].predict(point));
            agrees = nu.dot(o.measurement.Q.inverse() * nu) < insertionOptions.p_new_mahalanobis2;
        }
        if (!agrees) continue;
        any = true;
        cand.depth_min = std::min(cand.depth_min, s);
        cand.depth_max = std::max(cand.depth_max, s);
    }
    if (any || cand.observations.size() < 2) return;
    // No single point explains the measurements (two landmarks were mixed, as happens when
    // they are seen in nearly the same direction): the candidate starts over from its newest
    // measurement.
    cand.observations.erase(cand.observations.begin(), cand.observations.end() - 1);
    cand.cross_points.clear();
    cand.nz = 0;  // the caller counts the newest measurement
    cand.depth_min = s_lo;
    cand.depth_max = s_hi;
}

TCrossPointLimits CCeilingLightsMap::crossPointLimits() const
{
    TCrossPointLimits limits;
    limits.min_angle = insertionOptions.ang_min;
    const TSensorLimits in_use = sensorLimitsInUse();
    limits.max_range = in_use.max_range;
    limits.min_range = in_use.min_range;
    limits.planar = sensorOptions.measurement_model == TMeasurementModelKind::Planar;
    return limits;
}

void CCeilingLightsMap::refreshCrossPointValidity(TCandidateLight& cand) const
{
    // test (c): Π_i p(z_i | x) > Π_i P_new,i  ⇔  Σ_i d²_i < n · p_new_mahalanobis2
    const double max_sum_m2 =
        insertionOptions.p_new_mahalanobis2 * static_cast<double>(cand.observations.size());
    const TCrossPointLimits limits = crossPointLimits();
    for (auto& x : cand.cross_points)
        x.valid = x.in_front && crossPointHasParallax(x.angle, limits) &&  // tests (a), (b)
                  x.sum_mahalanobis2 < max_sum_m2;
}

bool CCeilingLightsMap::tryPromote(const TCandidateLight& cand)
{
    if (cand.nz < insertionOptions.nz_min) return false;
    const uint64_t newest = cand.observations.back().step;
    const TCandidateCrossPoint* best = nullptr;
    unsigned int n_valid = 0;
    bool from_current = false;
    for (const auto& x : cand.cross_points) {
        if (!x.valid) continue;
        n_valid++;
        from_current = from_current || x.step_second == newest;
        if (!best || x.sum_log_prob > best->sum_log_prob) best = &x;
    }
    if (n_valid < insertionOptions.ncross_valid || !from_current) return false;

    // Mean: the valid cross-point with the highest probability; covariance Σ0.
    // Type I when every measurement was taken within D_min (XY) of it (Sec. III-F(2)).
    bool all_close = true;
    int trailing_close = 0;
    for (const auto& o : cand.observations) {
        const bool close = horizontalDistance(o.robot_in_map, best->point) < insertionOptions.d_min;
        all_close = all_close && close;
        trailing_close = close ? trailing_close + 1 : 0;
    }
    const Eigen::Matrix3d sigma0 =
        Eigen::Vector3d(insertionOptions.sigma0_xx, insertionOptions.sigma0_yy,
                        insertionOptions.sigma0_zz)
            .asDiagonal();
    addLandmark(best->point, sigma0, all_close ? TLandmarkType::TypeI : TLandmarkType::TypeII,
                cand.counter);
    auto& lm = m_landmarks.back();
    lm.consecutive_close = trailing_close;
    if (insertionOptions.refine_initialization) {
        Eigen::Vector2d nu;
        Eigen::Matrix2d S;
        BearingMeasurementModel::Matrix23 H_x;
        const auto model = measurementModel();
        for (const auto& o : cand.observations)
            ekfUpdate(lm, o.measurement, model.atPose(o.robot_in_map), nu, S, H_x);
    }
    return true;
}

void CCeilingLightsMap::updateCandidates(const std::vector<TBearingMeasurement>& z,
                                         const mrpt::math::TPose2D& robot_in_map,
                                         const TLightAssociation& assoc)
{
    ASSERT_EQUAL_(assoc.landmark_of_measurement.size(), z.size());
    ASSERT_EQUAL_(assoc.candidate_of_measurement.size(), z.size());
    std::vector<bool> seen(m_candidates.size(), false);
    std::vector<TCandidateLight> created;
    for (size_t l = 0; l < z.size(); l++) {
        if (assoc.landmark_of_measurement[l] >= 0) continue;
        const TCandidateObservation obs{z[l], robot_in_map, m_step};
        const int c = assoc.candidate_of_measurement[l];
        if (c < 0) {
            // a new candidate: its counter starts at one hit (paper: 1)
            TCandidateLight cand;
            cand.id = m_next_candidate_id++;
            addCandidateObservation(cand, obs);
            cand.counter = static_cast<int>(insertionOptions.hit_increment);
            cand.nz = 1;
            created.push_back(std::move(cand));
            continue;
        }
        ASSERTMSG_(c < static_cast<int>(m_candidates.size()), "candidate index out of range");
        ASSERTMSG_(!seen[c], "two measurements associated to one candidate");
        seen[c] = true;
        auto& cand = m_candidates[c];
        addCandidateObservation(cand, obs);
        cand.counter += static_cast<int>(insertionOptions.hit_increment);
        cand.nz++;
        cand.consecutive_misses = 0;
    }

    std::vector<TCandidateLight> kept;
    kept.reserve(m_candidates.size() + created.size());
    for (size_t c = 0; c < m_candidates.size(); c++) {
        auto& cand = m_candidates[c];
        if (seen[c]) {
            if (tryPromote(cand)) continue;
        } else {
            // i_j ← i_j − I_not, I_not = iterations in a row without a measurement
            cand.consecutive_misses++;
            cand.counter -= insertionOptions.candidate_miss_decrement > 0
                                ? static_cast<int>(insertionOptions.candidate_miss_decrement)
                                : cand.consecutive_misses;
        }
        if (cand.counter > 0) kept.push_back(std::move(cand));
    }
    for (auto& cand : created) kept.push_back(std::move(cand));
    m_candidates = std::move(kept);
    m_step++;
}

void CCeilingLightsMap::updateLandmarksType()
{
    for (auto& lm : m_landmarks)
        if (lm.type == TLandmarkType::TypeII &&
            lm.consecutive_close >= static_cast<int>(insertionOptions.nz_min))
            lm.type = TLandmarkType::TypeI;
    m_landmarks.erase(std::remove_if(m_landmarks.begin(), m_landmarks.end(),
                                     [](const auto& lm) { return lm.counter < 0; }),
                      m_landmarks.end());
}

double CCeilingLightsMap::insertMeasurements(const std::vector<TBearingMeasurement>& z,
                                             const mrpt::math::TPose2D& robot_in_map)
{
    const TLightAssociation assoc = associate(z, robot_in_map);
    const double log_w = updateLandmarks(z, robot_in_map, assoc.landmark_of_measurement);
    updateCandidates(z, robot_in_map, assoc);
    updateLandmarksType();
    return log_w;
}

}  // namespace mrpt_vslam::omni_fastslam
