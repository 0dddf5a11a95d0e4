#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace mrpt::obs;
using mrpt_vslam::core::ActionFrameSource;
using mrpt_vslam::core::ObservationSelector;
using mrpt_vslam::core::RawlogReader;

namespace {
CActionCollection forward(double meters)
{
    CActionRobotMovement2D move;
    CActionRobotMovement2D::TMotionModelOptions model;
    model.gaussianModel.minStdXY = 0.01;
    move.computeFromOdometry(mrpt::poses::CPose2D(meters, 0, M_PI / 2), model);
    CActionCollection acts;
    acts.insert(move);
    return acts;
}

CSensoryFrame frame()
{
    CSensoryFrame sf;
    sf.insert(CObservationBearingRange::Create());
    return sf;
}

/// A rawlog `name` in the scratch folder of these tests, holding what `write` puts in it.
std::string writeRawlog(const std::string& name,
                        const std::function<void(mrpt::serialization::CArchive&)>& write)
{
    static const mrpt_vslam::test::ScratchFolder scratch("ActionFrameSource_unittest");
    const std::string file = scratch.file(name);
    mrpt::io::CFileGZOutputStream f(file);
    auto ar = mrpt::serialization::archiveFrom(f);
    write(ar);
    return file;
}

/// One step of a rawlog: its odometry, whether it stands still, and the sizes of its action
/// collection and of its frame.
struct TStep {
    mrpt::poses::CPosePDFGaussian move;
    bool still = false;
    size_t actions = 0, observations = 0;
};

/// The steps ActionFrameSource makes of the rawlog `file`, stepping on bearing frames.
std::vector<TStep> stepsOf(const std::string& file)
{
    RawlogReader reader(file);
    ActionFrameSource source(reader, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    std::vector<TStep> steps;
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    while (source.next(acts, sf)) {
        const auto& move = *acts->getBestMovementEstimation();
        steps.push_back({mrpt::poses::CPosePDFGaussian(*move.poseChange),
                         ActionFrameSource::standsStill(move), acts->size(), sf->size()});
    }
    return steps;
}

/// Observations handed out from memory, as team::TeamListener hands them out.
class ObservationList : public mrpt_vslam::core::RawlogEntrySource {
  public:
    std::vector<CObservation::Ptr> observations;  ///< nullptr: a time barrier after the previous
    bool next(mrpt_vslam::core::TRawlogEntry& e) override
    {
        if (m_next == observations.size()) return false;
        e = {};
        e.index = m_next;
        if (!observations[m_next]) {
            e.time_barrier = true;
            e.timestamp = observations.at(m_next - 1)->timestamp;
        } else {
            e.observation = observations[m_next];
            e.timestamp = e.observation->timestamp;
        }
        m_next++;
        return true;
    }
    size_t read() const { return m_next; }
    const mrpt_vslam::core::TRawlogSummary& summary() const override { return m_summary; }
    const std::string& file() const override { return m_name; }

  private:
    size_t m_next = 0;
    mrpt_vslam::core::TRawlogSummary m_summary;
    std::string m_name = "list";
};

/// "N steps" that `list` makes, stepping on `steps`, or the error that stops it.
std::string messageOf(ObservationList list, const ObservationSelector& steps,
                      std::vector<std::string> odometry_labels = {})
{
    ActionFrameSource source(list, {steps}, CActionRobotMovement2D::TMotionModelOptions(),
                             std::move(odometry_labels));
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    size_t n = 0;
    try {
        while (source.next(acts, sf)) n++;
    } catch (const std::runtime_error& e) {
        return std::string(e.what());
    }
    return std::to_string(n) + " steps";
}

CObservation::Ptr odometry(const std::string& label, double t, double x)
{
    auto o = CObservationOdometry::Create();
    o->sensorLabel = label;
    o->timestamp = mrpt::Clock::fromDouble(t);
    o->odometry = mrpt::poses::CPose2D(x, 0, 0);
    return o;
}

CObservation::Ptr bearings(const std::string& label, double t)
{
    auto o = CObservationBearingRange::Create();
    o->sensorLabel = label;
    o->timestamp = mrpt::Clock::fromDouble(t);
    return o;
}

/// A robot's motion in one step: the mean x of its increment, and whether it stands still.
struct TMotion {
    double x;
    bool still;
};

/// The steps of a team whose R2 sends its first odometry at t = 3 and none at t = 5: per step,
/// (R1, R2).
std::vector<std::pair<TMotion, TMotion>> teamSteps(bool stand_still)
{
    ObservationList list;
    for (int t = 1; t <= 6; t++) {
        list.observations.push_back(odometry("R1_ODOM", t, 0.5 * t));
        if (t >= 3 && t != 5) list.observations.push_back(odometry("R2_ODOM", t, 10.0 + t));
        list.observations.push_back(bearings("R1_RB", t));
    }
    ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions(), {"R1_ODOM", "R2_ODOM"});
    if (stand_still) source.standStillWithoutOdometry();
    std::vector<std::pair<TMotion, TMotion>> steps;
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    while (source.next(acts, sf)) {
        const auto motion = [&](size_t k) {
            const auto& move = dynamic_cast<const CActionRobotMovement2D&>(*acts->get(k));
            return TMotion{move.poseChange->getMeanVal().x(), ActionFrameSource::standsStill(move)};
        };
        steps.emplace_back(motion(0), motion(1));
    }
    return steps;
}
}  // namespace

// An action collection with no frame after it: its odometry goes into the next step.
TEST(ActionFrameSource, OdometryWithoutAFrameIsComposedIntoTheNextStep)
{
    const auto steps = stepsOf(writeRawlog("carried.rawlog", [](auto& ar) {
        ar << forward(1.0) << forward(2.0);  // the first has no frame
        ar << frame() << forward(0.5) << frame();
    }));
    ASSERT_EQ(steps.size(), 2u);
    // (1, 0, 90°) ⊕ (2, 0, 90°) = (1, 2, 180°)
    EXPECT_NEAR(steps[0].move.mean.x(), 1.0, 1e-12);
    EXPECT_NEAR(steps[0].move.mean.y(), 2.0, 1e-12);
    EXPECT_NEAR(std::abs(steps[0].move.mean.phi()), M_PI, 1e-12);
    // the covariance of the composition exceeds that of the single increment
    const mrpt::poses::CPosePDFGaussian second(
        *forward(2.0).getBestMovementEstimation()->poseChange);
    EXPECT_GT(steps[0].move.cov.trace(), second.cov.trace());
    EXPECT_NEAR(steps[1].move.mean.x(), 0.5, 1e-12);
}

// An empty sensory frame (as rawlog-edit --cut writes after a last action) holds nothing to
// step on: it is passed over, and the odometry before it goes into the next step.
TEST(ActionFrameSource, AnEmptyFrameIsNotAStep)
{
    const auto steps = stepsOf(writeRawlog("empty.rawlog", [](auto& ar) {
        ar << CSensoryFrame() << forward(1.0) << CSensoryFrame() << forward(2.0) << frame();
        ar << forward(0.5) << CSensoryFrame();
    }));
    ASSERT_EQ(steps.size(), 1u);
    EXPECT_EQ(steps[0].observations, 1u);
    EXPECT_NEAR(steps[0].move.mean.x(), 1.0, 1e-12);  // (1, 0, 90°) ⊕ (2, 0, 90°) = (1, 2, 180°)
    EXPECT_NEAR(steps[0].move.mean.y(), 2.0, 1e-12);
}

// A frame with no action before it: at the start, or right after another frame, the robot has
// not moved (a step that stands still); after an action with no frame of its own, it moves by
// that action's odometry.
TEST(ActionFrameSource, AFrameWithoutAnActionBeforeItStandsStill)
{
    const auto steps = stepsOf(writeRawlog("frames.rawlog", [](auto& ar) {
        ar << frame() << forward(1.0) << frame() << frame();
        ar << forward(0.5) << mrpt::poses::CPose2D() << frame();  // no frame right after 0.5 m
    }));
    const std::vector<double> x = {0, 1.0, 0, 0.5};
    const std::vector<bool> still = {true, false, true, false};
    ASSERT_EQ(steps.size(), x.size());
    for (size_t i = 0; i < x.size(); i++) {
        EXPECT_EQ(steps[i].actions, 1u) << "step " << i;
        EXPECT_NEAR(steps[i].move.mean.x(), x[i], 1e-12) << "step " << i;
        EXPECT_EQ(steps[i].still, still[i]) << "step " << i;
    }
}

// Such a step is at the time of its frame, and so is one whose action has no timestamp.
TEST(ActionFrameSource, AStepWithoutATimeIsAtItsFramesTime)
{
    const auto stamped = [](double t) {
        CSensoryFrame sf;
        sf.insert(CObservationImage::Create());  // no step on images, no time
        sf.insert(bearings("", t));
        return sf;
    };
    RawlogReader reader(writeRawlog(
        "stamped.rawlog", [&](auto& ar) { ar << stamped(1.5) << forward(1.0) << stamped(2.5); }));
    ActionFrameSource source(reader, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    ASSERT_TRUE(source.next(acts, sf));
    EXPECT_TRUE(ActionFrameSource::standsStill(*acts->getBestMovementEstimation()));
    EXPECT_EQ(acts->begin()->get()->timestamp, mrpt::Clock::fromDouble(1.5));
    ASSERT_TRUE(source.next(acts, sf));  // an action without a timestamp, the same
    EXPECT_EQ(acts->begin()->get()->timestamp, mrpt::Clock::fromDouble(2.5));
}

// An action collection with no planar odometry (3D odometry, as simul-landmarks writes for a
// 6D path) stops the run with the entry and what it holds.
TEST(ActionFrameSource, AnActionWithoutPlanarOdometryIsNamed)
{
    const std::string file = writeRawlog("odometry3d.rawlog", [](auto& ar) {
        CActionCollection acts;
        acts.insert(CActionRobotMovement3D());
        ar << frame() << acts << frame();
    });
    RawlogReader reader(file);
    ActionFrameSource source(reader, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    CActionCollection::Ptr a;
    CSensoryFrame::Ptr sf;
    ASSERT_TRUE(source.next(a, sf));  // the first frame, standing
    try {
        source.next(a, sf);
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  file +
                      ": entry 1 has an action collection without a CActionRobotMovement2D (it "
                      "holds CActionRobotMovement3D; planar odometry is needed)");
    }
}

// MRPT's CActionCollection::getBestMovementEstimation() passes over a CActionRobotMovement2D
// whose covariance has a NaN or a determinant of 1000 or more: the message says which.
TEST(ActionFrameSource, OdometryMRPTPassesOverIsNamed)
{
    const auto action = [](double x, double min_std) {
        CActionRobotMovement2D move;
        CActionRobotMovement2D::TMotionModelOptions model;
        model.gaussianModel.minStdXY = min_std;
        model.gaussianModel.minStdPHI = min_std;
        move.computeFromOdometry(mrpt::poses::CPose2D(x, 0, 0), model);
        CActionCollection acts;
        acts.insert(move);
        return acts;
    };
    const auto messageOf = [](const std::string& file) {
        try {
            stepsOf(file);
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string nan = writeRawlog("nan-odometry.rawlog", [&](auto& ar) {
        ar << action(1, 0.01) << frame() << action(std::nan(""), 0.01) << frame();
    });
    const std::string message = messageOf(nan);
    EXPECT_EQ(message.rfind(nan + ": entry 1 has odometry that is not finite (increment [nan ", 0),
              0u)
        << message;
    const std::string wide =
        writeRawlog("wide-odometry.rawlog", [&](auto& ar) { ar << action(1, 20) << frame(); });
    EXPECT_EQ(messageOf(wide), wide +
                                   ": entry 0 has odometry too uncertain for MRPT (the "
                                   "determinant of its covariance is 6.42401e+07; it takes below "
                                   "1000)");

    // format #2: the increment the motion model makes of two readings, the same
    ObservationList list;
    list.observations = {odometry("", 1, 0), bearings("", 1), odometry("", 2, 1), bearings("", 2)};
    CActionRobotMovement2D::TMotionModelOptions wideModel;
    wideModel.gaussianModel.minStdXY = 100;
    ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                             wideModel);
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    try {
        while (source.next(acts, sf)) {
        }
        ADD_FAILURE() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(
            std::string(e.what()).rfind("list: entry 0 has odometry too uncertain for MRPT", 0), 0u)
            << e.what();
    }
}

// Format #2 with a robot whose odometry comes late and misses a step: by default the steps wait
// for every robot's first odometry, and a robot without a reading at a step's time has its
// odometry interpolated between the readings around it; with standStillWithoutOdometry() the
// others go on and a robot without a reading since the last step stands exactly still, its
// increment counted from its last reading.
TEST(ActionFrameSource, ARobotWithoutOdometryStandsStillWhenAsked)
{
    const auto waiting = teamSteps(false);
    ASSERT_EQ(waiting.size(), 4u);                // t = 3 to 6
    EXPECT_NEAR(waiting[0].first.x, 1.0, 1e-12);  // R1 from t = 1
    EXPECT_NEAR(waiting[0].second.x, 0.0, 1e-12);
    EXPECT_NEAR(waiting[1].second.x, 1.0, 1e-12);
    EXPECT_NEAR(waiting[2].second.x, 1.0, 1e-12);  // t = 5: halfway from t = 4 to t = 6
    EXPECT_NEAR(waiting[3].second.x, 1.0, 1e-12);
    for (const auto& [r1, r2] : waiting) EXPECT_FALSE(r1.still || r2.still);

    const auto standing = teamSteps(true);
    ASSERT_EQ(standing.size(), 6u);  // t = 1 to 6
    EXPECT_NEAR(standing[0].first.x, 0.0, 1e-12);
    for (size_t i = 1; i < 6; i++) EXPECT_NEAR(standing[i].first.x, 0.5, 1e-12);
    for (const auto& [r1, r2] : standing) EXPECT_FALSE(r1.still);
    const std::vector<double> r2_x = {0, 0, 0, 1, 0, 2};  // t = 3: its first reading
    const std::vector<bool> r2_still = {true, true, false, false, true, false};
    for (size_t i = 0; i < 6; i++) {
        EXPECT_NEAR(standing[i].second.x, r2_x[i], 1e-12) << "step " << i;
        EXPECT_EQ(standing[i].second.still, r2_still[i]) << "step " << i;
    }
}

// Format #2 with odometry readings at other times than the frames' (sensors of their own
// clocks): a frame takes the odometry interpolated at its time, several frames may wait for the
// same reading, and past the last reading or a gap longer than kOdometryWait a frame takes the
// latest reading before it; odometryTiming() counts each kind.
TEST(ActionFrameSource, AFramesOdometryIsThatOfItsTime)
{
    ActionFrameSource::TOdometryTiming timing;
    // the steps' odometry poses, the readings and frames in time order; the frames stamped by a
    // clock `frame_clock` s ahead of the odometry's
    const auto stepPoses = [&](const std::vector<std::pair<double, mrpt::poses::CPose2D>>& readings,
                               const std::vector<double>& frames, double frame_clock = 0) {
        std::vector<std::pair<double, CObservation::Ptr>> timed;
        for (const auto& [t, pose] : readings) {
            auto o = std::dynamic_pointer_cast<CObservationOdometry>(odometry("", t, 0));
            o->odometry = pose;
            timed.emplace_back(t, o);
        }
        for (double t : frames) timed.emplace_back(t, bearings("", t + frame_clock));
        std::stable_sort(timed.begin(), timed.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        ObservationList list;
        for (const auto& [t, o] : timed) list.observations.push_back(o);
        ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                                 CActionRobotMovement2D::TMotionModelOptions());
        std::vector<mrpt::poses::CPose2D> poses;
        mrpt::poses::CPose2D pose = readings.front().second;
        CActionCollection::Ptr acts;
        CSensoryFrame::Ptr sf;
        while (source.next(acts, sf)) {
            pose = pose + acts->getBestMovementEstimation()->poseChange->getMeanVal();
            poses.push_back(pose);
        }
        timing = source.odometryTiming();
        return poses;
    };
    // MRPT interpolates at times in seconds since 1601 (doubles): to a few microseconds
    const auto expectPoses = [](const std::vector<mrpt::poses::CPose2D>& poses,
                                const std::vector<mrpt::poses::CPose2D>& expected) {
        ASSERT_EQ(poses.size(), expected.size());
        for (size_t i = 0; i < poses.size(); i++)
            EXPECT_NEAR((poses[i] - expected[i]).norm() + std::abs((poses[i] - expected[i]).phi()),
                        0, 1e-5)
                << "step " << i << ": " << poses[i] << ", expected " << expected[i];
    };
    using P = mrpt::poses::CPose2D;
    // 1 m/s along x, turning by 0.2 rad in the first second; frames at 0.25 and 0.5 wait for the
    // reading at 1; the one at 2 has its own; the one at 3.5 is after the last reading
    expectPoses(
        stepPoses({{0, P(0, 0, 0)}, {1, P(1, 0, 0.2)}, {2, P(2, 0, 0.2)}, {3, P(3, 0, 0.2)}},
                  {0, 0.25, 0.5, 1.5, 2, 3.5}),
        {P(0, 0, 0), P(0.25, 0, 0.05), P(0.5, 0, 0.1), P(1.5, 0, 0.2), P(2, 0, 0.2), P(3, 0, 0.2)});
    EXPECT_EQ(timing.at_step_time, 2u);
    EXPECT_EQ(timing.interpolated, 3u);
    EXPECT_EQ(timing.latest_reading, 1u);
    EXPECT_EQ(timing.frames_before_odometry, 0u);
    // a frame before the first reading, passed over; a gap of 5 s in the odometry: the frame at
    // 0.5 stops waiting at the frame at 2 (more than kOdometryWait after it); the later frames,
    // more than kOdometryWait after the latest reading, take it at once
    ASSERT_EQ(ActionFrameSource::kOdometryWait, 1.0);
    expectPoses(stepPoses({{0, P(0, 0, 0)}, {5, P(5, 0, 0)}}, {-0.5, 0.5, 2, 4.5}),
                {P(0, 0, 0), P(0, 0, 0), P(0, 0, 0)});
    EXPECT_EQ(timing.at_step_time, 0u);
    EXPECT_EQ(timing.interpolated, 0u);
    EXPECT_EQ(timing.latest_reading, 3u);
    EXPECT_EQ(timing.frames_before_odometry, 1u);
    // the frames' clock 1000 s ahead of the odometry's: each frame takes the latest reading
    // before it in the rawlog, none from after it
    expectPoses(
        stepPoses({{0, P(0, 0, 0)}, {0.5, P(0.5, 0, 0)}, {1, P(1, 0, 0)}}, {0.4, 0.9, 1.4}, 1000),
        {P(0, 0, 0), P(0.5, 0, 0), P(1, 0, 0)});
    EXPECT_EQ(timing.latest_reading, 3u);
    // readings written out of time order: the latest in time before the frame counts (0.3 s,
    // not 0.2 s), so the frame at 0.5 s is halfway
    ObservationList late;
    late.observations = {odometry("", 0, 0), bearings("", 0.5), odometry("", 0.3, 0.3),
                         odometry("", 0.2, 0.5), odometry("", 1, 1)};
    ActionFrameSource source(late, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    ASSERT_TRUE(source.next(acts, sf));
    EXPECT_NEAR(acts->getBestMovementEstimation()->poseChange->getMeanVal().x(), 0.5, 1e-5);
    EXPECT_FALSE(source.next(acts, sf));
}

// A live source's time barrier closes the frame at once; without it the frame waits for the
// next timestamp. The steps are the same.
TEST(ActionFrameSource, ATimeBarrierClosesTheFrame)
{
    ObservationList list;
    for (int t = 1; t <= 3; t++) {
        list.observations.push_back(odometry("", t, 0.5 * t));
        list.observations.push_back(bearings("", t));
        list.observations.push_back(nullptr);
    }
    ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    for (size_t step = 1; step <= 3; step++) {
        ASSERT_TRUE(source.next(acts, sf));
        EXPECT_EQ(list.read(), 3 * step);  // up to the barrier, not beyond
        EXPECT_EQ(sf->size(), 1u);
        EXPECT_NEAR(acts->getBestMovementEstimation()->poseChange->getMeanVal().x(),
                    step == 1 ? 0.0 : 0.5, 1e-12);
    }
    EXPECT_FALSE(source.next(acts, sf));
}

// A sensor pose with NaN (e.g. a calibration file gone wrong) would put every reading of the
// sensor at NaN: the observations that make steps are refused where they are read, in either
// format, as is an odometry pose with NaN; observations of other classes are not the app's to
// judge.
TEST(ActionFrameSource, ANonFiniteSensorOrOdometryPoseIsNamed)
{
    const auto broken = [](const std::string& label, double t) {
        auto o = bearings(label, t);
        dynamic_cast<CObservationBearingRange&>(*o).sensorLocationOnRobot =
            mrpt::poses::CPose3D(0, 0, std::nan(""), 0, 0, 0);
        return o;
    };
    const auto expectNamed = [](const std::function<void()>& read, const std::string& message) {
        try {
            read();
            ADD_FAILURE() << "no error";
        } catch (const std::runtime_error& e) {
            EXPECT_EQ(std::string(e.what()), message);
        }
    };
    const std::string file = writeRawlog("nan-pose.rawlog", [&](auto& ar) {
        CSensoryFrame sf;
        sf.insert(broken("CAM", 1));
        ar << forward(1) << frame() << forward(1) << sf;
    });
    expectNamed([&] { stepsOf(file); },
                file +
                    ": entry 1: CAM has a sensor pose on the robot that is not finite ([0.000000 "
                    "0.000000 nan 0.000000 0.000000 0.000000])");

    ObservationList list;
    list.observations = {odometry("", 1, 0), bearings("", 1), odometry("", 2, 1), broken("", 2)};
    ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    expectNamed(
        [&] {
            while (source.next(acts, sf)) {
            }
        },
        "list: entry 3: CObservationBearingRange has a sensor pose on the robot that is not "
        "finite ([0.000000 0.000000 nan 0.000000 0.000000 0.000000])");

    // an odometry reading of the robot, in format #2, the same
    ObservationList odometryList;
    auto nanOdometry = odometry("ODO", 2, 1);
    dynamic_cast<CObservationOdometry&>(*nanOdometry).odometry.x(std::nan(""));
    odometryList.observations = {odometry("ODO", 1, 0), bearings("", 1), nanOdometry};
    ActionFrameSource odometrySource(odometryList,
                                     {ObservationSelector::of<CObservationBearingRange>("")},
                                     CActionRobotMovement2D::TMotionModelOptions());
    expectNamed(
        [&] {
            while (odometrySource.next(acts, sf)) {
            }
        },
        "list: entry 2: ODO has an odometry pose that is not finite ([nan 0.000000 0.000000deg])");

    // an observation that makes no step is left as it is
    ObservationList other;
    other.observations = {odometry("", 1, 0), bearings("", 1), odometry("", 2, 1),
                          broken("OTHER", 2), bearings("", 3)};
    ActionFrameSource skipping(other, {ObservationSelector::of<CObservationBearingRange>("RB")},
                               CActionRobotMovement2D::TMotionModelOptions());
    EXPECT_FALSE(skipping.next(acts, sf));  // no "RB" at all, and no error
}

// With an empty label every observation of the class is read, but a run that reads one sensor's
// (a camera model; one robot's odometry) refuses a second sensor instead of mixing the two.
TEST(ActionFrameSource, ASecondSensorWhereTheRunReadsOneIsNamed)
{
    const auto oneSensor = ObservationSelector::ofOneSensor<CObservationBearingRange>("", "KEY");
    ObservationList cameras;
    cameras.observations = {odometry("ODO", 1, 0), bearings("A", 1), odometry("ODO", 2, 1),
                            bearings("B", 2)};
    EXPECT_EQ(messageOf(cameras, oneSensor),
              "list: entry 3: CObservationBearingRange of a second sensor, 'B' (the first: 'A'): "
              "the run reads one sensor's; name it with KEY");
    // several sensors are fine where the run reads them all, or where the label names one
    EXPECT_EQ(messageOf(cameras, ObservationSelector::of<CObservationBearingRange>("")), "2 steps");
    EXPECT_EQ(
        messageOf(cameras, ObservationSelector::ofOneSensor<CObservationBearingRange>("A", "KEY")),
        "1 steps");

    ObservationList team;
    team.observations = {odometry("R1_ODOM", 1, 0), odometry("R2_ODOM", 1, 5), bearings("", 1)};
    EXPECT_EQ(messageOf(team, ObservationSelector::of<CObservationBearingRange>("")),
              "list: entry 1: CObservationOdometry of a second sensor, 'R2_ODOM' (the first: "
              "'R1_ODOM'): the run reads one robot's odometry (doc/your-own-data.md)");
    EXPECT_EQ(messageOf(team, ObservationSelector::of<CObservationBearingRange>(""), {"R1_ODOM"}),
              "1 steps");
}

// In format #2 the observations of one time make one frame; two of one sensor there are a fault
// of the data, named, rather than one of them passed over.
TEST(ActionFrameSource, TwoReadingsOfOneSensorAtOneTimeAreNamed)
{
    const auto read = [](std::vector<CObservation::Ptr> observations) {
        ObservationList list;
        list.observations = std::move(observations);
        return messageOf(list, ObservationSelector::of<CObservationBearingRange>(""));
    };
    EXPECT_EQ(read({odometry("", 1, 0), bearings("", 1), odometry("", 2, 1), bearings("", 2),
                    bearings("", 2)}),
              "list: entry 4: CObservationBearingRange at 2.000000 s, the time of an earlier "
              "reading of the same sensor: two readings of one sensor at one time");
    // two sensors at one time make one frame
    EXPECT_EQ(read({odometry("", 1, 0), bearings("A", 1), bearings("B", 1), odometry("", 2, 1),
                    bearings("A", 2)}),
              "2 steps");
}
