#include <mrpt/core/format.h>
#include <mrpt/maps/CLandmarksMap.h>
#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt_vslam/core/ObservationSelector.h>
#include <mrpt_vslam/multirobot/LandmarkMeasurement.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::multirobot {

namespace {
/// [m] A measured point farther than this from its sensor is a corrupt reading.
constexpr double kMaxMeasuredDistance = 1e5;
}  // namespace

std::vector<TLandmarkMeasurement> measurementsFromObservation(
    const mrpt::obs::CObservationVisualLandmarks& obs)
{
    const Eigen::Matrix3d rot = obs.refCameraPose.getRotationMatrix().asEigen();
    const Eigen::Vector3d t(obs.refCameraPose.x(), obs.refCameraPose.y(), obs.refCameraPose.z());
    std::vector<TLandmarkMeasurement> out;
    out.reserve(obs.landmarks.landmarks.size());
    for (const auto& lm : obs.landmarks.landmarks) {
        const auto fail = [&](const std::string& what) {
            throw std::runtime_error(core::ObservationSelector::nameOf(obs) + ": landmark " +
                                     std::to_string(lm.ID) + " " + what);
        };
        if (lm.features.empty() || !lm.features[0].descriptors.SURF ||
            lm.features[0].descriptors.SURF->size() != core::USurfDescriptor::kSize)
            fail("has no 64-D SURF descriptor");
        TLandmarkMeasurement m;
        const Eigen::Vector3d p(lm.pose_mean.x, lm.pose_mean.y, lm.pose_mean.z);
        Eigen::Matrix3d C;
        C << lm.pose_cov_11, lm.pose_cov_12, lm.pose_cov_13, lm.pose_cov_12, lm.pose_cov_22,
            lm.pose_cov_23, lm.pose_cov_13, lm.pose_cov_23, lm.pose_cov_33;
        if (!p.allFinite() || !C.allFinite()) fail("has a non-finite point or covariance");
        if (C.llt().info() != Eigen::Success)
            fail("has a covariance that is not positive definite");
        if (!(p.z() > 0)) fail("is not in front of the camera");
        if (p.norm() > kMaxMeasuredDistance)
            fail(mrpt::format("is %g m from the camera: not a plausible measurement", p.norm()));
        m.z = rot * p + t;
        m.R = rot * C * rot.transpose();
        std::copy(lm.features[0].descriptors.SURF->begin(), lm.features[0].descriptors.SURF->end(),
                  m.d.begin());
        m.depth = p.z();
        m.track_id = lm.ID;
        out.push_back(m);
    }
    return out;
}

std::vector<TLandmarkMeasurement> measurementsFromBearingRange(
    const mrpt::obs::CObservationBearingRange& obs, const TRangeBearingNoise& noise,
    size_t* non_positive)
{
    const auto fail = [&](const std::string& what) {
        throw std::runtime_error(core::ObservationSelector::nameOf(obs) + ": " + what);
    };
    const auto configKeys = [&](const std::string& key) {
        return noise.config_keys.empty() ? std::string()
                                         : ", or " + noise.config_keys + key + " in the config";
    };
    // Per measurement (validCovariances) or per observation (sensor_std_*), each σ the config
    // sets replacing the observation's.
    const std::optional<double> configStd[3] = {noise.std_range, noise.std_bearing,
                                                noise.std_pitch};
    Eigen::Matrix3d shared = Eigen::Matrix3d::Zero();  // of (r, b, p), without validCovariances
    if (!obs.validCovariances) {
        const double sr = noise.std_range.value_or(obs.sensor_std_range);
        const double sb = noise.std_bearing.value_or(obs.sensor_std_yaw);
        const double sp = noise.std_pitch.value_or(obs.sensor_std_pitch);
        const auto requireStd = [&](double v, const char* what, const char* field,
                                    const char* key) {
            if (!(v > 0 && std::isfinite(v)))
                fail(std::string("no usable ") + what + " (" + field + " = " +
                     mrpt::format("%g", v) + "): set it in the observations" + configKeys(key));
        };
        requireStd(sr, "range noise", "sensor_std_range", "_std_range");
        requireStd(sb, "bearing noise", "sensor_std_yaw", "_std_bearing_deg");
        if (!(sp >= 0 && std::isfinite(sp)))
            requireStd(sp, "pitch noise", "sensor_std_pitch", "_std_pitch_deg");
        shared.diagonal() << sr * sr, sb * sb, sp * sp;
    }

    const Eigen::Matrix3d rot = obs.sensorLocationOnRobot.getRotationMatrix().asEigen();
    const Eigen::Vector3d t(obs.sensorLocationOnRobot.x(), obs.sensorLocationOnRobot.y(),
                            obs.sensorLocationOnRobot.z());
    std::vector<TLandmarkMeasurement> out;
    out.reserve(obs.sensedData.size());
    for (const auto& s : obs.sensedData) {
        const auto failOn = [&](const std::string& what) {
            fail("measurement of landmark " + std::to_string(s.landmarkID) + " " + what);
        };
        if (!std::isfinite(s.range)) failOn("has a non-finite range");
        if (!std::isfinite(s.yaw)) failOn("has a non-finite bearing");
        if (!std::isfinite(s.pitch)) failOn("has a non-finite pitch");
        Eigen::Matrix3d S = shared;
        if (obs.validCovariances) {
            S = s.covariance.asEigen();
            for (int i = 0; i < 3; i++)
                if (configStd[i]) {
                    S.row(i).setZero();
                    S.col(i).setZero();
                    S(i, i) = *configStd[i] * *configStd[i];
                }
            if (!(S.allFinite() && S(0, 0) > 0 && S(1, 1) > 0 && S(2, 2) >= 0))
                failOn(mrpt::format("has a covariance without usable noise (variances of range, "
                                    "bearing, pitch: %g, %g, %g): set it in the observations",
                                    S(0, 0), S(1, 1), S(2, 2)) +
                       configKeys("_std_*"));
        }
        const bool spatial = S(2, 2) > 0;
        if (obs.validCovariances) {
            const bool positive = spatial ? S.llt().info() == Eigen::Success
                                          : S.topLeftCorner<2, 2>().llt().info() == Eigen::Success;
            if (!positive || !S.isApprox(S.transpose()))
                failOn("has a covariance that is not symmetric positive definite");
        }
        if (!spatial && s.pitch != 0)
            failOn(std::string("has a non-zero pitch, but no pitch noise (") +
                   (obs.validCovariances ? "covariance(2, 2) = 0" : "sensor_std_pitch = 0") +
                   "): planar model");
        if (s.range > kMaxMeasuredDistance)
            failOn(mrpt::format("has a range of %g m: not a plausible measurement", s.range));
        if (!(s.range > 0)) {
            if (non_positive) (*non_positive)++;
            continue;
        }
        const double r = s.range, cb = std::cos(s.yaw), sb_ = std::sin(s.yaw);
        const double cp = std::cos(s.pitch), sp_ = std::sin(s.pitch);
        Eigen::Matrix3d J;                           // ∂(x, y, z)/∂(r, b, p)
        J << cp * cb, -r * cp * sb_, -r * sp_ * cb,  //
            cp * sb_, r * cp * cb, -r * sp_ * sb_,   //
            -sp_, 0, -r * cp;
        if (!spatial) {  // planar model: the height's own σ, no pitch terms
            S.row(2).setZero();
            S.col(2).setZero();
        }
        Eigen::Matrix3d C = J * S * J.transpose();
        if (!spatial) C(2, 2) = noise.std_height * noise.std_height;
        TLandmarkMeasurement m;
        m.z = rot * Eigen::Vector3d(r * cp * cb, r * cp * sb_, -r * sp_) + t;
        m.R = rot * C * rot.transpose();
        m.depth = r;
        m.track_id = s.landmarkID;
        m.identity = s.landmarkID >= 0 ? s.landmarkID : -1;
        m.planar = !spatial;
        out.push_back(m);
    }
    return out;
}

namespace {
// ties keep the observation's order: track_id may be an identity the filter must not read
void sortByDepth(std::vector<TLandmarkMeasurement>& z)
{
    std::stable_sort(z.begin(), z.end(),
                     [](const auto& a, const auto& b) { return a.depth < b.depth; });
}
}  // namespace

std::vector<std::vector<TLandmarkMeasurement>> splitBySensor(
    const std::vector<TLandmarkMeasurement>& z)
{
    std::vector<std::vector<TLandmarkMeasurement>> bySensor;
    for (const auto& m : z) {
        if (bySensor.size() <= m.sensor) bySensor.resize(m.sensor + 1u);
        bySensor[m.sensor].push_back(m);
    }
    bySensor.erase(std::remove_if(bySensor.begin(), bySensor.end(),
                                  [](const auto& list) { return list.empty(); }),
                   bySensor.end());
    return bySensor;
}

std::vector<TLandmarkMeasurement> selectNearest(std::vector<TLandmarkMeasurement> z, size_t B)
{
    sortByDepth(z);
    if (B > 0 && z.size() > B) z.resize(B);
    return z;
}

std::vector<TLandmarkMeasurement> selectAtRandom(std::vector<TLandmarkMeasurement> z, size_t B,
                                                 mrpt::random::CRandomGenerator& rng)
{
    if (B > 0 && z.size() > B) {
        for (size_t i = 0; i < B; i++) {  // the first B steps of a Fisher-Yates shuffle
            const auto j = i + static_cast<size_t>(rng.drawUniform64bit() % (z.size() - i));
            std::swap(z[i], z[j]);
        }
        z.resize(B);
    }
    sortByDepth(z);
    return z;
}

}  // namespace mrpt_vslam::multirobot
