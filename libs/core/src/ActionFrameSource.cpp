#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose2DInterpolator.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/system/datetime.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/UsageError.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace mrpt_vslam::core {
namespace {
bool isFinite(const mrpt::poses::CPose2D& p)
{
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.phi());
}

/// The odometry at `t`, between the readings `p0` at `t0` and `p1` at `t1` (t0 < t <= t1):
/// position and heading in proportion to the time (MRPT's linear interpolation, shortest turn).
mrpt::poses::CPose2D interpolate(const mrpt::poses::CPose2D& p0, mrpt::Clock::time_point t0,
                                 const mrpt::poses::CPose2D& p1, mrpt::Clock::time_point t1,
                                 mrpt::Clock::time_point t)
{
    mrpt::poses::CPose2DInterpolator path;
    path.setInterpolationMethod(mrpt::poses::imLinearSlerp);
    path.insert(t0, p0);
    path.insert(t1, p1);
    mrpt::poses::CPose2D at;
    bool valid = false;
    path.interpolate(t, at, valid);
    return valid ? at : p1;
}
}  // namespace

ActionFrameSource::ActionFrameSource(
    RawlogEntrySource& reader, std::vector<ObservationSelector> steps,
    const mrpt::obs::CActionRobotMovement2D::TMotionModelOptions& motion_model,
    std::vector<std::string> odometry_labels)
    : m_reader(reader),
      m_steps(std::move(steps)),
      m_motion_model(motion_model),
      m_odometry_labels(std::move(odometry_labels)),
      m_odometry(std::max<size_t>(1, m_odometry_labels.size())),
      m_odometry_at_last_step(m_odometry.size()),
      m_odometry_since_last_step(m_odometry.size(), false),
      m_step_sensors(m_steps.size())
{
}

std::string ActionFrameSource::entryName(size_t entry) const
{
    return m_reader.file() + ": entry " + std::to_string(entry);
}

std::runtime_error ActionFrameSource::noOdometryError(const mrpt::obs::CActionCollection& actions,
                                                      size_t entry) const
{
    const std::string where = entryName(entry);
    // MRPT's getBestMovementEstimation() takes a CActionRobotMovement2D whose covariance has a
    // determinant below 1000: none with NaN, none that wide
    if (const auto move = actions.getActionByClass<mrpt::obs::CActionRobotMovement2D>()) {
        const auto mean = move->poseChange->getMeanVal();
        const auto cov = move->poseChange->getCovariance();
        const bool finiteMean = isFinite(mean);
        if (!finiteMean || !cov.asEigen().allFinite())
            return std::runtime_error(where + " has odometry that is not finite (" +
                                      (finiteMean ? "covariance " + cov.inMatlabFormat()
                                                  : "increment " + mean.asString()) +
                                      ")");
        return std::runtime_error(
            where + mrpt::format(" has odometry too uncertain for MRPT (the determinant of its "
                                 "covariance is %g; it takes below 1000)",
                                 cov.det()));
    }
    std::string held;
    for (const auto& a : actions)
        held += std::string(held.empty() ? "" : ", ") + shortClassName(*a);
    return std::runtime_error(where +
                              " has an action collection without a "
                              "CActionRobotMovement2D (it holds " +
                              (held.empty() ? std::string("nothing") : held) +
                              "; planar odometry is needed)");
}

bool ActionFrameSource::makesStep(const mrpt::obs::CObservation& obs) const
{
    return std::any_of(m_steps.begin(), m_steps.end(),
                       [&](const auto& sel) { return sel.matches(obs); });
}

std::string ActionFrameSource::secondSensor(std::optional<std::string>& first,
                                            const mrpt::obs::CObservation& obs, size_t entry,
                                            const std::string& reads) const
{
    if (!first) first = obs.sensorLabel;
    if (obs.sensorLabel == *first) return {};
    return entryName(entry) + ": " + shortClassName(obs) + " of a second sensor, '" +
           obs.sensorLabel + "' (the first: '" + *first + "'): " + reads;
}

void ActionFrameSource::checkStepObservation(const mrpt::obs::CObservation& obs, size_t entry)
{
    for (size_t i = 0; i < m_steps.size(); i++) {
        const auto& sel = m_steps[i];
        if (sel.label.empty() && !sel.one_sensor_key.empty() && sel.matches(obs))
            if (const auto error =
                    secondSensor(m_step_sensors[i], obs, entry,
                                 "the run reads one sensor's; name it with " + sel.one_sensor_key);
                !error.empty())
                throw std::runtime_error(error);
    }
    mrpt::poses::CPose3D pose;
    obs.getSensorPose(pose);
    if (!(std::isfinite(pose.x()) && std::isfinite(pose.y()) && std::isfinite(pose.z()) &&
          pose.getRotationMatrix().asEigen().allFinite()))
        throw std::runtime_error(entryName(entry) + ": " + ObservationSelector::nameOf(obs) +
                                 " has a sensor pose on the robot that is not finite (" +
                                 pose.asString() + ")");
}

mrpt::obs::CActionRobotMovement2D::TMotionModelOptions ActionFrameSource::loadMotionModel(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
    auto& g = model.gaussianModel;
    g.a1 = cfg.read_double(section, "a1", g.a1);
    g.a2 = cfg.read_double(section, "a2", g.a2);
    g.a3 = cfg.read_double(section, "a3", g.a3);
    g.a4 = cfg.read_double(section, "a4", g.a4);
    g.minStdXY = cfg.read_double(section, "minStdXY", g.minStdXY);
    g.minStdPHI =
        mrpt::DEG2RAD(cfg.read_double(section, "minStdPHI_deg", mrpt::RAD2DEG(g.minStdPHI)));
    for (const auto& [key, value] :
         {std::pair<const char*, double>{"a1", g.a1}, {"a2", g.a2}, {"a3", g.a3}, {"a4", g.a4}})
        if (!(value >= 0 && std::isfinite(value)))
            throw UsageError("[" + section + "] " + key + ": must be finite and >= 0");
    if (!(g.minStdXY > 0 && std::isfinite(g.minStdXY)))
        throw UsageError("[" + section + "] minStdXY: must be finite and > 0 [m]");
    if (!(g.minStdPHI > 0 && std::isfinite(g.minStdPHI)))
        throw UsageError("[" + section + "] minStdPHI_deg: must be finite and > 0 [deg]");
    return model;
}

bool ActionFrameSource::standsStill(const mrpt::obs::CActionRobotMovement2D& odometry)
{
    const auto* g = dynamic_cast<const mrpt::poses::CPosePDFGaussian*>(odometry.poseChange.get());
    return g && g->mean == mrpt::poses::CPose2D() && g->cov.asEigen().isZero(0);
}

bool ActionFrameSource::pendingIsStep() const
{
    return m_pending && m_pending_is_step && haveOdometry();
}

bool ActionFrameSource::haveOdometry() const
{
    if (m_stand_still_without_odometry)
        return std::any_of(m_odometry_at_last_step.begin(), m_odometry_at_last_step.end(),
                           [](const auto& o) { return o.has_value(); });
    return std::all_of(m_odometry_at_last_step.begin(), m_odometry_at_last_step.end(),
                       [](const auto& o) { return o.has_value(); });
}

void ActionFrameSource::closePending()
{
    TClosedFrame closed;
    closed.frame = std::move(m_pending);
    closed.time = m_pending_time;
    closed.odometry.resize(m_odometry.size());
    closed.waiting.assign(m_odometry.size(), false);
    for (size_t k = 0; k < m_odometry.size(); k++) {
        auto& odometry = closed.odometry[k];
        if (m_stand_still_without_odometry) {  // the latest reading since the last step, or none
            if (m_odometry_since_last_step[k]) odometry = m_odometry[k];
            m_odometry_since_last_step[k] = false;
        } else {
            odometry = m_odometry[k];  // every robot has one (haveOdometry())
            // a reading more than kOdometryWait older (a gap, or clocks that disagree) stands
            closed.waiting[k] =
                closed.time != INVALID_TIMESTAMP && odometry->time != INVALID_TIMESTAMP &&
                odometry->time < closed.time &&
                mrpt::system::timeDifference(odometry->time, closed.time) <= kOdometryWait;
        }
        if (odometry && !closed.waiting[k])
            (odometry->time == closed.time ? m_odometry_timing.at_step_time
                                           : m_odometry_timing.latest_reading)++;
    }
    m_closed.push_back(std::move(closed));
}

void ActionFrameSource::dropPending()
{
    if (m_pending_is_step) m_odometry_timing.frames_before_odometry++;
    m_pending.reset();
}

void ActionFrameSource::resolveWaiting(size_t k, const TOdometryReading& reading)
{
    if (reading.time == INVALID_TIMESTAMP) return;
    for (auto& closed : m_closed) {
        if (!closed.waiting[k]) continue;
        auto& before = *closed.odometry[k];
        if (reading.time < closed.time) {  // a later reading before the frame (written late)
            if (reading.time > before.time) before = reading;
            continue;
        }
        (reading.time == closed.time ? m_odometry_timing.at_step_time
                                     : m_odometry_timing.interpolated)++;
        before = {interpolate(before.pose, before.time, reading.pose, reading.time, closed.time),
                  closed.time, reading.entry};
        closed.waiting[k] = false;
    }
}

void ActionFrameSource::stopWaiting(std::optional<mrpt::Clock::time_point> now)
{
    for (auto& closed : m_closed)
        for (size_t k = 0; k < closed.waiting.size(); k++)
            if (closed.waiting[k] &&
                (!now || mrpt::system::timeDifference(closed.time, *now) > kOdometryWait)) {
                closed.waiting[k] = false;
                m_odometry_timing.latest_reading++;
            }
}

bool ActionFrameSource::frontReady() const
{
    return !m_closed.empty() &&
           std::none_of(m_closed.front().waiting.begin(), m_closed.front().waiting.end(),
                        [](bool waiting) { return waiting; });
}

void ActionFrameSource::emitFront(mrpt::obs::CActionCollection::Ptr& actions,
                                  mrpt::obs::CSensoryFrame::Ptr& frame)
{
    if (!m_second_odometry.empty()) throw std::runtime_error(m_second_odometry);
    const TClosedFrame closed = std::move(m_closed.front());
    m_closed.pop_front();
    actions = mrpt::obs::CActionCollection::Create();
    for (size_t k = 0; k < closed.odometry.size(); k++) {
        mrpt::obs::CActionRobotMovement2D move;
        if (const auto& odometry = closed.odometry[k]; !odometry) {
            move = standingMove();
        } else {
            move.computeFromOdometry(odometry->pose - *m_odometry_at_last_step[k], m_motion_model);
            m_odometry_at_last_step[k] = odometry->pose;
            mrpt::obs::CActionCollection alone;
            alone.insert(move);
            if (!alone.getBestMovementEstimation()) throw noOdometryError(alone, odometry->entry);
        }
        move.timestamp = closed.time;
        actions->insert(move);
    }
    frame = closed.frame;
}

mrpt::obs::CActionRobotMovement2D ActionFrameSource::standingMove()
{
    mrpt::obs::CActionRobotMovement2D move;
    move.poseChange = mrpt::poses::CPosePDFGaussian::Create();  // zero mean and covariance
    return move;
}

mrpt::obs::CActionCollection::Ptr ActionFrameSource::standingStill() const
{
    auto actions = mrpt::obs::CActionCollection::Create();
    for (size_t k = 0; k < m_odometry.size(); k++) actions->insert(standingMove());
    return actions;
}

void ActionFrameSource::stampAtFrameTime(mrpt::obs::CActionCollection& actions,
                                         const mrpt::obs::CSensoryFrame& frame) const
{
    mrpt::Clock::time_point time = INVALID_TIMESTAMP;
    for (const bool stepsOnly : {true, false})  // an observation of the steps first
        for (const auto& obs : frame)
            if (time == INVALID_TIMESTAMP && obs && (!stepsOnly || makesStep(*obs)))
                time = obs->timestamp;
    for (auto& action : actions)
        if (action && action->timestamp == INVALID_TIMESTAMP) action->timestamp = time;
}

mrpt::obs::CActionCollection::Ptr ActionFrameSource::afterCarried(
    const mrpt::obs::CActionCollection& later) const
{
    auto out = mrpt::obs::CActionCollection::Create();
    for (size_t k = 0; k < later.size(); k++) {
        const auto* move = dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(&later.get(k));
        const auto* before = k < m_carried->size()
                                 ? dynamic_cast<const mrpt::obs::CActionRobotMovement2D*>(
                                       &std::as_const(*m_carried).get(k))
                                 : nullptr;
        if (!move || !before) {
            out->insert(later.get(k));
            continue;
        }
        mrpt::poses::CPosePDFGaussian sum(*before->poseChange);
        sum += mrpt::poses::CPosePDFGaussian(*move->poseChange);
        mrpt::obs::CActionRobotMovement2D composed = *move;
        composed.poseChange = mrpt::poses::CPosePDFGaussian::Create(sum);
        composed.rawOdometryIncrementReading =
            before->rawOdometryIncrementReading + move->rawOdometryIncrementReading;
        out->insert(composed);
    }
    return out;
}

bool ActionFrameSource::next(mrpt::obs::CActionCollection::Ptr& actions,
                             mrpt::obs::CSensoryFrame::Ptr& frame)
{
    if (frontReady()) {
        emitFront(actions, frame);
        return true;
    }
    for (TRawlogEntry e; m_reader.next(e);) {
        if (e.actions || e.observations) {  // format #1
            // an empty frame holds nothing to step on
            const bool noFrame = !e.observations || e.observations->size() == 0;
            if (!noFrame)
                for (const auto& obs : *e.observations)
                    if (obs && makesStep(*obs)) checkStepObservation(*obs, e.index);
            if (!e.actions) {
                if (noFrame) continue;
                // no action since the previous frame (or the start): the robot has not moved,
                // unless by odometry carried from an action without a frame
                actions = m_carried ? m_carried : standingStill();
                m_carried.reset();
                frame = e.observations;
                stampAtFrameTime(*actions, *frame);
                return true;
            }
            if (!e.actions->getBestMovementEstimation()) throw noOdometryError(*e.actions, e.index);
            actions = m_carried ? afterCarried(*e.actions) : e.actions;
            m_carried.reset();
            if (noFrame) {  // no frame to go with: into the next step
                m_carried = actions;
                continue;
            }
            frame = e.observations;
            stampAtFrameTime(*actions, *frame);
            return true;
        }
        if (e.time_barrier) {  // nothing more at the pending frame's time
            if (pendingIsStep() && m_pending_time <= e.timestamp) closePending();
        } else if (e.observation) {
            const auto time = e.observation->timestamp;
            if (time != INVALID_TIMESTAMP) stopWaiting(time);
            // format #2: a new timestamp closes the pending frame
            if (m_pending && time != m_pending_time) {
                if (pendingIsStep())
                    closePending();
                else
                    dropPending();
            }
            if (const auto odo =
                    std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(e.observation))
                readOdometry(*odo, e.index);
            else
                addToPending(e.observation, e.index);
        }
        if (frontReady()) {
            emitFront(actions, frame);
            return true;
        }
    }
    if (pendingIsStep())
        closePending();
    else if (m_pending)
        dropPending();
    stopWaiting(std::nullopt);
    if (!frontReady()) return false;
    emitFront(actions, frame);
    return true;
}

void ActionFrameSource::readOdometry(const mrpt::obs::CObservationOdometry& odo, size_t entry)
{
    const auto it = std::find(m_odometry_labels.begin(), m_odometry_labels.end(), odo.sensorLabel);
    const size_t k = static_cast<size_t>(it - m_odometry_labels.begin());  // 0 if none
    if (m_odometry_labels.empty() && m_second_odometry.empty())
        m_second_odometry =
            secondSensor(m_odometry_sensor, odo, entry,
                         "the run reads one robot's odometry (doc/your-own-data.md)");
    if (!m_odometry_labels.empty() && it == m_odometry_labels.end()) return;
    const auto& pose = odo.odometry;
    if (!isFinite(pose))
        throw std::runtime_error(entryName(entry) + ": " + ObservationSelector::nameOf(odo) +
                                 " has an odometry pose that is not finite (" + pose.asString() +
                                 ")");
    const TOdometryReading reading{pose, odo.timestamp, entry};
    resolveWaiting(k, reading);
    m_odometry[k] = reading;
    m_odometry_since_last_step[k] = true;
    if (!m_odometry_at_last_step[k]) m_odometry_at_last_step[k] = pose;
}

void ActionFrameSource::addToPending(const mrpt::obs::CObservation::Ptr& obs, size_t entry)
{
    if (!m_pending) {
        m_pending = mrpt::obs::CSensoryFrame::Create();
        m_pending_time = obs->timestamp;
        m_pending_is_step = false;
    }
    if (makesStep(*obs)) {
        for (const auto& held : *m_pending)
            if (held->sensorLabel == obs->sensorLabel &&
                held->GetRuntimeClass() == obs->GetRuntimeClass())
                throw std::runtime_error(
                    entryName(entry) + ": " + ObservationSelector::nameOf(*obs) +
                    mrpt::format(" at %.6f s, the time of an earlier reading of the same "
                                 "sensor: two readings of one sensor at one time",
                                 mrpt::Clock::toDouble(obs->timestamp)));
        checkStepObservation(*obs, entry);
        m_pending_is_step = true;
    }
    m_pending->insert(obs);
}

}  // namespace mrpt_vslam::core
