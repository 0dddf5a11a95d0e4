#pragma once

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/omni_fastslam/BearingMeasurementModel.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <cmath>
#include <limits>
#include <vector>

namespace mrpt_vslam::omni_fastslam::test {

/** The map options of `sports-hall.ini` for the shipped halls' rawlogs: 70° perceptual range,
 *  Σ0 = 0.1 m², a new light refined from its candidate's measurements. */
inline CCeilingLightsMap hallMapTemplate()
{
    CCeilingLightsMap map;
    map.sensorOptions.max_theta = 70 * M_PI / 180;
    map.insertionOptions.sigma0_xx = map.insertionOptions.sigma0_yy =
        map.insertionOptions.sigma0_zz = 0.1;
    map.insertionOptions.refine_initialization = true;
    return map;
}

/// The map after a round trip through MRPT's serialization (the way particles are copied).
inline CCeilingLightsMap serializedCopy(const CCeilingLightsMap& map)
{
    mrpt::io::CMemoryStream buf;
    auto arch = mrpt::serialization::archiveFrom(buf);
    arch << map;
    buf.Seek(0);
    CCeilingLightsMap back;
    arch >> back;
    return back;
}

/** An OMNICAM_BEARINGS observation of `lights` from `robot`: yaw = φ, pitch = θ − π/2, range NaN,
 *  Gaussian angle noise of σ `sigma` [rad] when `rng` is given, lights with θ > max_theta left
 *  out; the camera sees all around (fieldOfView_yaw = 2π). */
inline mrpt::obs::CObservationBearingRange makeBearingObservation(
    const BearingMeasurementModel& model, const mrpt::math::TPose2D& robot,
    const std::vector<Eigen::Vector3d>& lights, double sigma,
    mrpt::random::CRandomGenerator* rng = nullptr, double max_theta = 1.4)
{
    mrpt::obs::CObservationBearingRange obs;
    obs.sensorLabel = "OMNICAM_BEARINGS";
    obs.sensorLocationOnRobot = model.sensorInRobot();
    obs.validCovariances = false;
    obs.sensor_std_range = 0;
    obs.sensor_std_yaw = static_cast<float>(sigma);
    obs.sensor_std_pitch = static_cast<float>(sigma);
    obs.fieldOfView_yaw = static_cast<float>(2 * M_PI);
    for (const auto& light : lights) {
        const Eigen::Vector2d z = model.predict(light, robot);
        if (z[1] > max_theta) continue;
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = std::numeric_limits<float>::quiet_NaN();
        const double n_phi = rng ? rng->drawGaussian1D(0, sigma) : 0.0;
        const double n_theta = rng ? rng->drawGaussian1D(0, sigma) : 0.0;
        m.yaw = static_cast<float>(z[0] + n_phi);
        m.pitch = static_cast<float>(z[1] - M_PI / 2 + n_theta);
        m.landmarkID = -1;
        obs.sensedData.push_back(m);
    }
    return obs;
}

}  // namespace mrpt_vslam::omni_fastslam::test
