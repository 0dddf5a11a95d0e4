#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt_vslam/core/HungarianAssignment.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>
#include <mrpt_vslam/omni_fastslam/RayCrossPoint.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mrpt_vslam::omni_fastslam {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

bool isUsableCovariance(const Eigen::Matrix2d& Q)
{
    return Q.allFinite() && Q(0, 0) > 0 && Q(1, 1) > 0 && Q.determinant() > 0;
}
}  // namespace

std::vector<TBearingMeasurement> CCeilingLightsMap::measurementsFromObservation(
    const mrpt::obs::CObservationBearingRange& obs) const
{
    const auto fail = [&](const std::string& what) {
        throw std::runtime_error(core::ObservationSelector::nameOf(obs) + ": " + what);
    };
    for (const auto& [name, v] :
         {std::pair<const char*, double>{"sensor_std_yaw", obs.sensor_std_yaw},
          {"sensor_std_pitch", obs.sensor_std_pitch},
          {"sensor_std_range", obs.sensor_std_range},
          {"minSensorDistance", obs.minSensorDistance},
          {"maxSensorDistance", obs.maxSensorDistance}})
        if (!(v >= 0 && std::isfinite(v)))
            fail(std::string(name) + " = " + mrpt::format("%g", v) + ": must be finite and >= 0");
    if (!(obs.fieldOfView_yaw > 0 && std::isfinite(obs.fieldOfView_yaw)))
        fail(mrpt::format("fieldOfView_yaw = %g deg: must be finite and > 0",
                          mrpt::RAD2DEG(obs.fieldOfView_yaw)));
    // the sensor's own limits, as it states them; the options override each one they set
    TSensorLimits stated;
    stated.max_abs_azimuth = std::min(0.5 * static_cast<double>(obs.fieldOfView_yaw), M_PI);
    stated.min_range = obs.minSensorDistance;
    stated.max_range = obs.maxSensorDistance;
    const TSensorLimits in_use = limitsInUse(stated);
    if (in_use.max_range > 0 && in_use.min_range >= in_use.max_range)
        fail("the reading range in use is empty (minSensorDistance = " +
             mrpt::format("%g", stated.min_range) +
             " m, maxSensorDistance = " + mrpt::format("%g", stated.max_range) +
             " m, or min_/max_cross_point_range where set): set min_cross_point_range and "
             "max_cross_point_range in the map's _insertOpts section");
    for (const auto& s : obs.sensedData) {
        const std::string which = "measurement of landmark " + std::to_string(s.landmarkID);
        // the filter does not use ranges: any value (NaN, −1, ...) says "not measured"
        if (!std::isfinite(s.yaw) || !std::isfinite(s.pitch))
            fail(which + " has a non-finite bearing or pitch");
        if (!sensorOptions.max_abs_azimuth && std::abs(s.yaw) > stated.max_abs_azimuth + 1e-6)
            fail(which + " has azimuth " + mrpt::format("%g", mrpt::RAD2DEG(s.yaw)) +
                 " deg, outside the observation's field of view (fieldOfView_yaw = " +
                 mrpt::format("%g", mrpt::RAD2DEG(obs.fieldOfView_yaw)) +
                 " deg); set max_abs_azimuth_deg in the map's _creationOpts section to half the "
                 "camera's field of view (180: all around)");
        if (sensorOptions.measurement_model == TMeasurementModelKind::Spherical && !(s.pitch < 0))
            fail(which + " has pitch " + mrpt::format("%g", mrpt::RAD2DEG(s.pitch)) +
                 " deg, at or below the camera's horizon: an upward camera sees ceiling lights "
                 "above it (pitch < 0); for azimuths alone set measurement_model = planar in the "
                 "map's _creationOpts section");
        if (obs.validCovariances &&
            (!s.covariance.asEigen().allFinite() ||
             !(s.covariance(0, 0) >= 0 && s.covariance(1, 1) >= 0 && s.covariance(2, 2) >= 0)))
            fail(which + " has a non-finite or negative covariance");
    }
    m_sensor_in_robot = sensorOptions.sensor_in_robot.value_or(obs.sensorLocationOnRobot);
    m_observed_limits = stated;
    Eigen::Matrix2d Q_sensor =
        Eigen::Vector2d(sensorOptions.sigma_phi * sensorOptions.sigma_phi,
                        sensorOptions.sigma_theta * sensorOptions.sigma_theta)
            .asDiagonal();
    if (!obs.validCovariances && obs.sensor_std_yaw > 0 && obs.sensor_std_pitch > 0) {
        const double sy = obs.sensor_std_yaw, sp = obs.sensor_std_pitch;
        Q_sensor = Eigen::Vector2d(sy * sy, sp * sp).asDiagonal();
    }
    std::vector<TBearingMeasurement> out;
    out.reserve(obs.sensedData.size());
    if (sensorOptions.measurement_model == TMeasurementModelKind::Planar) {
        // azimuth only: range and pitch are ignored; θ is the constant of the planar model and
        // its variance a placeholder (its innovation is always 0, see measurementLogLikelihood)
        double var_phi = sensorOptions.sigma_phi * sensorOptions.sigma_phi;
        if (!obs.validCovariances && obs.sensor_std_yaw > 0)
            var_phi = static_cast<double>(obs.sensor_std_yaw) * obs.sensor_std_yaw;
        for (const auto& s : obs.sensedData) {
            TBearingMeasurement m;
            m.z = BearingMeasurementModel::anglesOfYawPitch(s.yaw, 0);
            const double v = obs.validCovariances ? s.covariance(1, 1) : var_phi;
            m.Q = Eigen::Vector2d(v > 0 ? v : var_phi, 1.0).asDiagonal();
            m.hidden_id = s.landmarkID;
            out.push_back(m);
        }
        return out;
    }
    for (const auto& s : obs.sensedData) {
        TBearingMeasurement m;
        m.hidden_id = s.landmarkID;
        // θ = π/2 + pitch has unit derivative, so the (yaw, pitch) block is Q of (φ, θ)
        m.z = BearingMeasurementModel::anglesOfYawPitch(s.yaw, s.pitch);
        m.Q = Q_sensor;
        if (obs.validCovariances) {
            const Eigen::Matrix2d Q_obs = s.covariance.asEigen().block<2, 2>(1, 1);
            if (isUsableCovariance(Q_obs)) m.Q = Q_obs;
        }
        out.push_back(m);
    }
    return out;
}

double CCeilingLightsMap::logGaussian(const Eigen::Vector2d& innovation, const Eigen::Matrix2d& S)
{
    const double det = S.determinant();
    if (!(det > 0)) return -kInf;
    // log N(ν; 0, S) = −log 2π − ½ log|S| − ½ νᵀ S⁻¹ ν   (Alg. 2 line 11, Dim = 2)
    return -std::log(2 * M_PI) - 0.5 * std::log(det) -
           0.5 * innovation.dot(S.inverse() * innovation);
}

double CCeilingLightsMap::measurementLogLikelihood(const Eigen::Vector2d& innovation,
                                                   const Eigen::Matrix2d& S) const
{
    if (sensorOptions.measurement_model == TMeasurementModelKind::Spherical)
        return logGaussian(innovation, S);
    // planar (Eq. P4): log N(ν_φ; 0, S_φφ) = −½ log(2π S_φφ) − ½ ν_φ² / S_φφ
    const double s = S(0, 0);
    if (!(s > 0)) return -kInf;
    return -0.5 * std::log(2 * M_PI * s) - 0.5 * innovation[0] * innovation[0] / s;
}

double CCeilingLightsMap::logPNew(const TBearingMeasurement& m) const
{
    if (sensorOptions.measurement_model == TMeasurementModelKind::Planar)
        return -0.5 * std::log(2 * M_PI * m.Q(0, 0)) - 0.5 * insertionOptions.p_new_mahalanobis2;
    // P_new = (1/2π) |Q|^{-1/2} exp(−p_new_mahalanobis2 / 2)   (Sec. IV)
    return -std::log(2 * M_PI) - 0.5 * std::log(m.Q.determinant()) -
           0.5 * insertionOptions.p_new_mahalanobis2;
}

bool CCeilingLightsMap::isInPerceptualRange(const Eigen::Vector3d& point_in_map,
                                            const mrpt::math::TPose2D& robot_in_map) const
{
    const auto model = measurementModel();
    return isInPerceptualRange(point_in_map, model.atPose(robot_in_map));
}

bool CCeilingLightsMap::isInPerceptualRange(const Eigen::Vector3d& point_in_map,
                                            const BearingMeasurementModel::AtPose& at) const
{
    if (!couldBeObserved(at.predict(point_in_map))) return false;
    if (sensorOptions.max_horizontal_distance <= 0) return true;
    const Eigen::Vector3d camera = measurementModel().rayOriginInMap(at.robot());
    return (point_in_map - camera).head<2>().norm() <= sensorOptions.max_horizontal_distance;
}

bool CCeilingLightsMap::couldBeObserved(const Eigen::Vector2d& z_predicted, double margin) const
{
    if (std::abs(z_predicted[0]) > sensorLimitsInUse().max_abs_azimuth + margin) return false;
    return sensorOptions.measurement_model == TMeasurementModelKind::Planar ||
           z_predicted[1] <= sensorOptions.max_theta + margin;
}

bool CCeilingLightsMap::isWithinReadingRange(const Eigen::Vector3d& point_in_camera) const
{
    const double r = point_in_camera.norm();
    const TSensorLimits limits = sensorLimitsInUse();
    return r >= limits.min_range && (limits.max_range <= 0 || r <= limits.max_range);
}

Eigen::MatrixXd CCeilingLightsMap::landmarkLogLikelihoods(
    const std::vector<TBearingMeasurement>& z, const mrpt::math::TPose2D& robot_in_map) const
{
    const auto model = measurementModel();
    const auto at = model.atPose(robot_in_map);
    Eigen::MatrixXd out(z.size(), m_landmarks.size());
    for (size_t j = 0; j < m_landmarks.size(); j++) {
        const auto& lm = m_landmarks[j];
        const auto pred = at.predictWithJacobians(lm.mean);  // Alg. 2 lines 2-4
        if (!pred.valid || !isWithinReadingRange(pred.point_in_camera)) {
            out.col(static_cast<Eigen::Index>(j)).setConstant(-kInf);
            continue;
        }
        const Eigen::Matrix2d HSH = pred.H_m * lm.cov * pred.H_m.transpose();
        for (size_t l = 0; l < z.size(); l++) {
            // Alg. 2 line 6: Q_{j,l} = Q_l + H_m Σ_j H_mᵀ
            const Eigen::Matrix2d S = z[l].Q + HSH;
            out(l, j) =
                measurementLogLikelihood(BearingMeasurementModel::innovation(z[l].z, pred.z), S);
        }
    }
    return out;
}

Eigen::Vector2d CCeilingLightsMap::segmentInnovation(const BearingMeasurementModel& model,
                                                     const Eigen::Vector3d& origin,
                                                     const Eigen::Vector3d& dir, double s_lo,
                                                     double s_hi, const TRayCrossPoint& x,
                                                     const Eigen::Vector2d& z,
                                                     const mrpt::math::TPose2D& robot_in_map)
{
    // The azimuth along the segment is monotonic: the closest one to z is at an end, or z
    // itself where the new ray crosses the segment in front of the robot.
    std::vector<double> depths{s_lo, s_hi};
    if (!x.parallel && x.s2 > 0) depths.push_back(std::clamp(x.s1, s_lo, s_hi));
    Eigen::Vector2d best = Eigen::Vector2d::Constant(kInf);
    for (const double s : depths) {
        const Eigen::Vector2d nu =
            BearingMeasurementModel::innovation(z, model.predict(origin + s * dir, robot_in_map));
        if (std::abs(nu[0]) < std::abs(best[0])) best = nu;
    }
    return best;
}

Eigen::MatrixXd CCeilingLightsMap::candidateLogLikelihoods(
    const std::vector<TBearingMeasurement>& z, const mrpt::math::TPose2D& robot_in_map) const
{
    const auto model = measurementModel();
    const Eigen::Vector3d origin = model.rayOriginInMap(robot_in_map);
    const Eigen::Matrix3d R_camera_T =
        model.cameraInMap(robot_in_map).getRotationMatrix().asEigen().transpose();
    const Eigen::Matrix3d sigma0 =
        Eigen::Vector3d(insertionOptions.sigma0_xx, insertionOptions.sigma0_yy,
                        insertionOptions.sigma0_zz)
            .asDiagonal();

    Eigen::MatrixXd out(z.size(), m_candidates.size());
    for (size_t c = 0; c < m_candidates.size(); c++) {
        const auto& cand = m_candidates[c];
        const TCandidateCrossPoint* best = nullptr;
        for (const auto& x : cand.cross_points)
            if (x.valid && (!best || x.sum_log_prob > best->sum_log_prob)) best = &x;

        if (best) {
            // A candidate with a valid cross-point predicts like a landmark with covariance Σ0
            const auto pred = model.predictWithJacobians(best->point, robot_in_map);
            for (size_t l = 0; l < z.size(); l++)
                out(l, c) = pred.valid ? measurementLogLikelihood(
                                             BearingMeasurementModel::innovation(z[l].z, pred.z),
                                             z[l].Q + pred.H_m * sigma0 * pred.H_m.transpose())
                                       : -kInf;
            continue;
        }
        // Otherwise the light lies somewhere along the last measurement's ray: predict the point
        // of that ray closest to the new ray (its direction at infinity if none in front).
        const auto& last = cand.observations.back();
        const Eigen::Vector3d last_origin = model.rayOriginInMap(last.robot_in_map);
        const Eigen::Vector3d last_dir =
            model.rayDirectionInMap(last.measurement.z, last.robot_in_map);
        for (size_t l = 0; l < z.size(); l++) {
            const Eigen::Vector3d dir = model.rayDirectionInMap(z[l].z, robot_in_map);
            const auto x = computeRayCrossPoint(last_origin, last_dir, origin, dir);
            if (model.isPlanar()) {
                // Any two bearing lines cross: the light is on the segment of the last ray that
                // agrees with all the candidate's measurements, and the azimuth of that segment
                // closest to z_l is predicted (z_l itself when its ray crosses it).
                out(l, c) = measurementLogLikelihood(
                    segmentInnovation(model, last_origin, last_dir, cand.depth_min, cand.depth_max,
                                      x, z[l].z, robot_in_map),
                    z[l].Q + last.measurement.Q);
                continue;
            }
            const Eigen::Vector2d z_pred =
                (!x.parallel && x.s1 > 0)
                    ? model.predict(last_origin + x.s1 * last_dir, robot_in_map)
                    : BearingMeasurementModel::anglesOfDirection(R_camera_T * last_dir);
            out(l, c) = measurementLogLikelihood(
                BearingMeasurementModel::innovation(z[l].z, z_pred), z[l].Q + last.measurement.Q);
        }
    }
    return out;
}

std::vector<int> CCeilingLightsMap::solveAssociation(const Eigen::MatrixXd& log_lik,
                                                     const Eigen::VectorXd& log_p_new,
                                                     TAssociationMethod method)
{
    const int n_z = static_cast<int>(log_lik.rows());
    const int n = static_cast<int>(log_lik.cols());
    ASSERT_EQUAL_(log_p_new.size(), n_z);
    std::vector<int> out(n_z, -1);
    if (n_z == 0) return out;

    if (method == TAssociationMethod::ML) {
        // Greedy ML: each measurement, in order, to its most likely landmark not yet taken
        std::vector<bool> taken(n, false);
        for (int l = 0; l < n_z; l++) {
            double best = log_p_new(l);
            for (int j = 0; j < n; j++)
                if (!taken[j] && log_lik(l, j) > best) {
                    best = log_lik(l, j);
                    out[l] = j;
                }
            if (out[l] >= 0) taken[out[l]] = true;
        }
        return out;
    }

    // Sec. III-C: cost matrix Φ of size N_z × (N + N_z), −log φ_{l,j} then −log P_new; the
    // landmarks no measurement can take (all φ zero: out of view, or skipped) left out
    std::vector<int> landmark_of_column;
    for (int j = 0; j < n; j++)
        if (log_lik.col(j).array().isFinite().any()) landmark_of_column.push_back(j);
    const int n_cols = static_cast<int>(landmark_of_column.size());
    Eigen::MatrixXd cost(n_z, n_cols + n_z);
    for (int l = 0; l < n_z; l++) {
        for (int c = 0; c < n_cols; c++) {
            const double v = log_lik(l, landmark_of_column[size_t(c)]);
            cost(l, c) = std::isfinite(v) ? -v : kInf;
        }
        cost.row(l).tail(n_z).setConstant(-log_p_new(l));
    }
    const auto assignment = core::solveHungarianAssignment(cost);
    for (int l = 0; l < n_z; l++) {
        const int col = assignment.row_to_col[l];
        out[l] = (col >= 0 && col < n_cols) ? landmark_of_column[size_t(col)] : -1;
    }
    return out;
}

std::vector<int> CCeilingLightsMap::associateCandidates(
    const std::vector<TBearingMeasurement>& z, const mrpt::math::TPose2D& robot_in_map,
    const std::vector<int>& landmark_of_measurement) const
{
    ASSERT_EQUAL_(landmark_of_measurement.size(), z.size());
    std::vector<int> out(z.size(), -1);
    std::vector<TBearingMeasurement> rest;
    std::vector<size_t> rest_index;
    for (size_t l = 0; l < z.size(); l++)
        if (landmark_of_measurement[l] < 0) {
            rest.push_back(z[l]);
            rest_index.push_back(l);
        }
    if (rest.empty() || m_candidates.empty()) return out;
    Eigen::VectorXd rest_p_new(rest.size());
    for (size_t r = 0; r < rest.size(); r++) rest_p_new(r) = logPNew(rest[r]);
    const auto cand = solveAssociation(candidateLogLikelihoods(rest, robot_in_map), rest_p_new,
                                       insertionOptions.association_method);
    for (size_t r = 0; r < rest.size(); r++) out[rest_index[r]] = cand[r];
    return out;
}

TLightAssociation CCeilingLightsMap::associate(const std::vector<TBearingMeasurement>& z,
                                               const mrpt::math::TPose2D& robot_in_map) const
{
    TLightAssociation out;
    Eigen::VectorXd log_p_new(z.size());
    for (size_t l = 0; l < z.size(); l++) log_p_new(l) = logPNew(z[l]);
    // Level 1: landmarks; level 2: candidates, for the measurements left over
    out.landmark_of_measurement = solveAssociation(landmarkLogLikelihoods(z, robot_in_map),
                                                   log_p_new, insertionOptions.association_method);
    out.candidate_of_measurement =
        associateCandidates(z, robot_in_map, out.landmark_of_measurement);
    return out;
}

}  // namespace mrpt_vslam::omni_fastslam
