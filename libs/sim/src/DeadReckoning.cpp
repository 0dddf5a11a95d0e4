#include <mrpt_vslam/sim/DeadReckoning.h>

namespace mrpt_vslam::sim {

mrpt::poses::CPose2D DeadReckoning::step(double t, const mrpt::poses::CPose2D& robot,
                                         OdometrySimulator& odometry_simulator)
{
    mrpt::poses::CPose2D increment;
    if (!m_first) {
        const mrpt::poses::CPose2D true_increment = robot - m_previous;
        increment = odometry_simulator.simulateIncrement(true_increment);
        path_length += true_increment.norm();
    }
    m_first = false;
    m_previous = robot;
    m_odometry = m_odometry + increment;
    ground_truth.push_back(t, mrpt::math::TPose3D(robot.x(), robot.y(), 0, robot.phi(), 0, 0));
    odometry.push_back(
        t, mrpt::math::TPose3D(m_odometry.x(), m_odometry.y(), 0, m_odometry.phi(), 0, 0));
    return increment;
}

}  // namespace mrpt_vslam::sim
