#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/core/OdometryGaussian.h>
#include <mrpt_vslam/core/SensorPoseCorrection.h>
#include <mrpt_vslam/viewmap/COmniViewSLAM.h>

#include <Eigen/Core>
#include <deque>
#include <map>
#include <vector>

namespace mrpt_vslam::viewmap {

/** Per view, its bearing φ read last while the robot had driven at most `max_path` since the
 *  view was started, with the odometry in between (core::TEarlierPoseBearing): what the camera
 *  pose check of view-slam fits (doc/view-slam.md, "Checking the camera pose"). Through the
 *  odometry, not the filter's estimates: the filter bends its path to fit a wrong camera pose.
 *  One bearing per view: a view's bearings share its image's point errors and the odometry;
 *  taken all as independent, they gave σ 2.5 times too small. */
class ViewBearingPairing {
  public:
    /// `max_path` [m]: 1, 2 and 3.5 m gave the same σ of the turn within 10 % and normalised
    /// errors of unit spread on 12 simulated rooms.
    explicit ViewBearingPairing(double max_path = 2.0) : m_maxPath(max_path) {}

    /** One step of the filter: the odometry increment `u` into it (covariance `Q`), what the
     *  step did, and the camera's stated position on the robot. */
    void add(const mrpt::math::TPose2D& u, const Eigen::Matrix3d& Q,
             const COmniViewSLAM::TStepResult& step, const mrpt::math::TPoint2D& camera);

    /// One bearing per view read within max_path of its start, in the order of the views.
    std::vector<core::TEarlierPoseBearing> bearings() const;

  private:
    double m_maxPath;
    size_t m_steps = 0;  ///< steps added
    double m_path = 0;   ///< [m] odometry path length so far
    /// The increments since the oldest view still within max_path, the newest last.
    std::deque<core::TOdometryGaussian> m_motions;
    /// Views within max_path: the step each was started at and the path length there [m].
    struct TStart {
        size_t step;
        double path;
    };
    std::map<size_t, TStart> m_open;
    std::map<size_t, core::TEarlierPoseBearing> m_latest;  ///< per view
};

}  // namespace mrpt_vslam::viewmap
