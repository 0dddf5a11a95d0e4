#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt_vslam/sim/CeilingLights.h>
#include <mrpt_vslam/sim/PajdlaBaksteinInverse.h>

#include <Eigen/Core>
#include <vector>

namespace mrpt_vslam::sim {

/** A ceiling light that the camera sees in one frame. */
struct TVisibleLight {
    int id = 0;                        ///< light id
    Eigen::Vector3d center_in_camera;  ///< [m] disk centre, camera frame
    Eigen::Vector3d normal_in_camera;  ///< [-] unit normal of the disk, camera frame
    Eigen::Vector2d angles;            ///< [rad] ideal (φ, θ) of the centre
    Eigen::Vector2d uv;                ///< [px] ideal projection of the centre (Eq. 1)
};

/** A spurious reflection: a small bright spot at a random place of the image. */
struct TSpuriousBlob {
    Eigen::Vector2d uv;    ///< [px] centre
    double radius_px = 0;  ///< [px]
    double peak = 0;       ///< [0-255] brightness
};

/** One bearing measurement, as a detector would report it from a blob centroid. */
struct TBearing {
    int source_id = -1;  ///< id of the light it comes from; -1 for a spurious reflection
    double phi = 0;      ///< [rad] azimuth around the optical axis
    double theta = 0;    ///< [rad] angle from the optical axis
};

/** Everything the camera observes in one frame; the image and the bearings both come from it. */
struct TFrameDetections {
    std::vector<TVisibleLight> lights;  ///< ordered by id
    std::vector<TSpuriousBlob> spurious;
    std::vector<TBearing> bearings;  ///< lights first (same order), then spurious blobs
};

/** Decides which lights the upward fisheye camera sees and simulates the bearings a blob
 *  detector would extract (Gamallo et al. 2013, Sec. III-A: centroid
 *  (u, v) → (φ, θ) through Eq. 1).
 *
 *  1. A light is visible when its centre is within `max_light_theta` of the optical axis, its
 *     projection is inside the image and it is not washed out by the windows.
 *  2. Spurious reflections: a Poisson number (mean `spurious_rate`) of spots uniformly spread
 *     over the image disk θ ≤ max_light_theta.
 *  3. Bearings: the centre pixel plus N(0, pixel_std²) noise per axis, mapped back to (φ, θ)
 *     with the inverse model. */
class DetectionSimulator : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Detections])
    /// @{
    double pixel_std = 0.7;  ///< [px] std of the detected centroid, per axis
    double max_light_theta =
        1.2217;  ///< [rad] lights further from the axis are not detected (ini: _deg)
    double spurious_rate = 0.3;  ///< [1/frame] mean number of spurious reflections
    double spurious_radius_min = 1.0, spurious_radius_max = 2.5;  ///< [px]
    double spurious_peak_min = 150, spurious_peak_max = 255;      ///< [0-255]
    /// @}

    void reset(uint32_t seed) { m_rng.randomize(seed); }

    /** Observations of one frame.
     *  \param camera_in_world pose of the camera in the world
     *  \param t time since the start of the run [s] (for the washout intervals) */
    TFrameDetections simulate(const mrpt::poses::CPose3D& camera_in_world,
                              const CeilingLights& layout, double t,
                              const PajdlaBaksteinInverse& model);

    /// Angular std [rad] of (φ, θ) at angle θ from the axis, for pixel_std: σ/r(θ), σ/r'(θ).
    Eigen::Vector2d angularStd(const core::PajdlaBaksteinCamera& camera, double theta) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;

  private:
    TBearing measure(int source_id, const Eigen::Vector2d& uv, const PajdlaBaksteinInverse& model);
    int drawPoisson(double mean);

    mrpt::random::CRandomGenerator m_rng;
};

}  // namespace mrpt_vslam::sim
