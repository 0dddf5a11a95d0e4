#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/DetectionSimulator.h>

#include <cmath>

namespace mrpt_vslam::sim {

TFrameDetections DetectionSimulator::simulate(const mrpt::poses::CPose3D& camera_in_world,
                                              const CeilingLights& layout, double t,
                                              const PajdlaBaksteinInverse& model)
{
    const core::PajdlaBaksteinCamera& cam = model.camera();
    TFrameDetections out;
    const mrpt::math::CMatrixDouble33 R = camera_in_world.getRotationMatrix();
    for (const TCeilingLight& light : layout.lights()) {
        if (layout.isWashedOut(light, t)) continue;
        const mrpt::math::TPoint3D p = camera_in_world.inverseComposePoint(light.position);
        TVisibleLight v;
        v.id = light.id;
        v.center_in_camera = {p.x, p.y, p.z};
        // The disks face down: normal −z of the world, expressed in the camera frame (Rᵀ·n).
        v.normal_in_camera = -R.asEigen().transpose().col(2);
        v.angles = core::PajdlaBaksteinCamera::anglesOfPoint(p);
        if (p.z <= 0 || v.angles.y() > max_light_theta) continue;
        v.uv = cam.project(v.angles.x(), v.angles.y());
        if (!cam.isInsideImage(v.uv)) continue;
        out.lights.push_back(v);
    }

    const int n_spurious = drawPoisson(spurious_rate);
    const double r_max = cam.radius(max_light_theta);
    for (int i = 0; i < n_spurious; i++) {
        TSpuriousBlob s;
        do {
            s.uv = {m_rng.drawUniform(0.0, cam.width - 1.0),
                    m_rng.drawUniform(0.0, cam.height - 1.0)};
        } while (std::hypot(s.uv.x() - cam.u0, s.uv.y() / cam.beta - cam.v0) > r_max);
        s.radius_px = m_rng.drawUniform(spurious_radius_min, spurious_radius_max);
        s.peak = m_rng.drawUniform(spurious_peak_min, spurious_peak_max);
        out.spurious.push_back(s);
    }

    for (const TVisibleLight& v : out.lights) out.bearings.push_back(measure(v.id, v.uv, model));
    for (const TSpuriousBlob& s : out.spurious) out.bearings.push_back(measure(-1, s.uv, model));
    return out;
}

TBearing DetectionSimulator::measure(int source_id, const Eigen::Vector2d& uv,
                                     const PajdlaBaksteinInverse& model)
{
    const Eigen::Vector2d noisy =
        uv + pixel_std * Eigen::Vector2d(m_rng.drawGaussian1D_normalized(),
                                         m_rng.drawGaussian1D_normalized());
    const Eigen::Vector2d a = model.unproject(noisy);
    TBearing b;
    b.source_id = source_id;
    b.phi = a.x();
    b.theta = a.y();
    return b;
}

int DetectionSimulator::drawPoisson(double mean)
{
    // Knuth's multiplication method; mean is small (< 10).
    const double limit = std::exp(-mean);
    int k = 0;
    for (double p = m_rng.drawUniform(0.0, 1.0); p > limit; p *= m_rng.drawUniform(0.0, 1.0)) k++;
    return k;
}

Eigen::Vector2d DetectionSimulator::angularStd(const core::PajdlaBaksteinCamera& camera,
                                               double theta) const
{
    return {pixel_std / camera.radius(theta), pixel_std / camera.radiusDerivative(theta)};
}

void DetectionSimulator::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                            const std::string& s)
{
    MRPT_LOAD_CONFIG_VAR(pixel_std, double, cfg, s);
    max_light_theta = readDegrees(cfg, s, "max_light_theta_deg", max_light_theta);
    MRPT_LOAD_CONFIG_VAR(spurious_rate, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(spurious_radius_min, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(spurious_radius_max, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(spurious_peak_min, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(spurious_peak_max, double, cfg, s);
    checkConfig(pixel_std >= 0, s, "pixel_std", ">= 0");
    checkConfig(max_light_theta > 0 && max_light_theta < M_PI / 2, s, "max_light_theta_deg",
                "in (0, 90)");
    checkConfig(spurious_rate >= 0 && spurious_rate < 10, s, "spurious_rate", "in [0, 10)");
    checkConfig(spurious_radius_min > 0 && spurious_radius_min <= spurious_radius_max, s,
                "spurious_radius_min/max", "0 < min <= max");
    checkConfig(spurious_peak_min >= 0 && spurious_peak_min <= spurious_peak_max &&
                    spurious_peak_max <= 255,
                s, "spurious_peak_min/max", "0 <= min <= max <= 255");
}

}  // namespace mrpt_vslam::sim
