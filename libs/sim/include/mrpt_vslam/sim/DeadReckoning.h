#pragma once

#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/TumTrajectory.h>
#include <mrpt_vslam/sim/OdometrySimulator.h>

namespace mrpt_vslam::sim {

/** One robot's dead reckoning along its true path, frame by frame: the noisy odometry increment
 *  since the previous frame (OdometrySimulator), the odometry pose it integrates to, the
 *  ground-truth and odometry tracks (TUM files of doc/data-formats.md) and the true path
 *  length. */
class DeadReckoning {
  public:
    /// Starts at the true initial pose.
    explicit DeadReckoning(const mrpt::poses::CPose2D& start) : m_odometry(start), m_previous(start)
    {
    }

    /** The frame at time t [s] with true pose `robot`: draws the increment since the previous
     *  frame from `odometry` (none at the first frame: a zero increment) and appends both tracks.
     *  \return the noisy increment. */
    mrpt::poses::CPose2D step(double t, const mrpt::poses::CPose2D& robot,
                              OdometrySimulator& odometry);

    const mrpt::poses::CPose2D& odometryPose() const { return m_odometry; }

    core::TumTrajectory ground_truth;  ///< true poses
    core::TumTrajectory odometry;      ///< integrated odometry
    double path_length = 0;            ///< [m] true distance driven

  private:
    mrpt::poses::CPose2D m_odometry, m_previous;
    bool m_first = true;
};

}  // namespace mrpt_vslam::sim
