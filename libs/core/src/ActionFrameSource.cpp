#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt_vslam/core/ActionFrameSource.h>

#include <stdexcept>

namespace mrpt_vslam::core {

ActionFrameSource::ActionFrameSource(
    RawlogReader& reader, std::set<std::string> step_labels,
    const mrpt::obs::CActionRobotMovement2D::TMotionModelOptions& motion_model)
    : m_reader(reader), m_step_labels(std::move(step_labels)), m_motion_model(motion_model)
{
}

void ActionFrameSource::emitPending(mrpt::obs::CActionCollection::Ptr& actions,
                                    mrpt::obs::CSensoryFrame::Ptr& frame)
{
    mrpt::obs::CActionRobotMovement2D move;
    move.timestamp = m_pending_time;
    move.computeFromOdometry(*m_odometry - *m_odometry_at_last_step, m_motion_model);
    m_odometry_at_last_step = m_odometry;
    actions = mrpt::obs::CActionCollection::Create();
    actions->insert(move);
    frame = m_pending;
    m_pending.reset();
}

bool ActionFrameSource::next(mrpt::obs::CActionCollection::Ptr& actions,
                             mrpt::obs::CSensoryFrame::Ptr& frame)
{
    for (TRawlogEntry e; m_reader.next(e);) {
        if (e.actions || e.observations) {  // format #1
            if (!e.actions || !e.observations) continue;
            if (!e.actions->getBestMovementEstimation())
                throw std::runtime_error(m_reader.file() + ": entry " + std::to_string(e.index) +
                                         " has an action collection without odometry");
            actions = e.actions;
            frame = e.observations;
            return true;
        }
        if (!e.observation) continue;
        // format #2: a new timestamp closes the pending frame
        const bool ready = m_pending && m_pending_is_step && m_odometry_at_last_step &&
                           e.observation->timestamp != m_pending_time;
        if (m_pending && e.observation->timestamp != m_pending_time && !ready) m_pending.reset();
        if (ready) emitPending(actions, frame);
        if (const auto odo =
                std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(e.observation)) {
            m_odometry = odo->odometry;
            if (!m_odometry_at_last_step) m_odometry_at_last_step = m_odometry;
        } else {
            if (!m_pending) {
                m_pending = mrpt::obs::CSensoryFrame::Create();
                m_pending_time = e.observation->timestamp;
                m_pending_is_step = false;
            }
            m_pending->insert(e.observation);
            m_pending_is_step =
                m_pending_is_step || m_step_labels.count(e.observation->sensorLabel) > 0;
        }
        if (ready) return true;
    }
    if (m_pending && m_pending_is_step && m_odometry_at_last_step) {
        emitPending(actions, frame);
        return true;
    }
    return false;
}

}  // namespace mrpt_vslam::core
