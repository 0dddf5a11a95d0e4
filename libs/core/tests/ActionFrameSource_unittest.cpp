#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/RawlogReader.h>
#include <mrpt_vslam/test/ScratchFolder.h>

#include <cmath>
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

/// The steps of a team whose R2 sends its first odometry at t = 3: per step, (R1 x, R2 x).
std::vector<std::pair<double, double>> teamSteps(bool stand_still)
{
    ObservationList list;
    for (int t = 1; t <= 4; t++) {
        list.observations.push_back(odometry("R1_ODOM", t, 0.5 * t));
        if (t >= 3) list.observations.push_back(odometry("R2_ODOM", t, 10.0 + t));
        list.observations.push_back(bearings("R1_RB", t));
    }
    ActionFrameSource source(list, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions(), {"R1_ODOM", "R2_ODOM"});
    if (stand_still) source.standStillUntilOdometry();
    std::vector<std::pair<double, double>> steps;
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    while (source.next(acts, sf)) {
        const auto x = [&](size_t k) {
            return dynamic_cast<const CActionRobotMovement2D&>(*acts->get(k))
                .poseChange->getMeanVal()
                .x();
        };
        steps.emplace_back(x(0), x(1));
    }
    return steps;
}
}  // namespace

// An action collection with no frame after it: its odometry goes into the next step.
TEST(ActionFrameSource, OdometryWithoutAFrameIsComposedIntoTheNextStep)
{
    mrpt_vslam::test::ScratchFolder scratch("ActionFrameSource_unittest");
    const std::string file = scratch.file("carried.rawlog");
    {
        mrpt::io::CFileGZOutputStream f(file);
        auto ar = mrpt::serialization::archiveFrom(f);
        ar << frame();                       // no motion before it: passed over
        ar << forward(1.0) << forward(2.0);  // the first has no frame
        ar << frame() << forward(0.5) << frame();
    }
    RawlogReader reader(file);
    ActionFrameSource source(reader, {ObservationSelector::of<CObservationBearingRange>("")},
                             CActionRobotMovement2D::TMotionModelOptions());
    std::vector<mrpt::poses::CPosePDFGaussian> steps;
    CActionCollection::Ptr acts;
    CSensoryFrame::Ptr sf;
    while (source.next(acts, sf))
        steps.emplace_back(*acts->getBestMovementEstimation()->poseChange);
    ASSERT_EQ(steps.size(), 2u);
    // (1, 0, 90°) ⊕ (2, 0, 90°) = (1, 2, 180°)
    EXPECT_NEAR(steps[0].mean.x(), 1.0, 1e-12);
    EXPECT_NEAR(steps[0].mean.y(), 2.0, 1e-12);
    EXPECT_NEAR(std::abs(steps[0].mean.phi()), M_PI, 1e-12);
    // the covariance of the composition exceeds that of the single increment
    const mrpt::poses::CPosePDFGaussian second(
        *forward(2.0).getBestMovementEstimation()->poseChange);
    EXPECT_GT(steps[0].cov.trace(), second.cov.trace());
    EXPECT_NEAR(steps[1].mean.x(), 0.5, 1e-12);
}

// Format #2 with a robot whose odometry comes late: by default the steps wait for every robot's
// first odometry; with standStillUntilOdometry() the others go on and the late robot stands
// still until its first reading, its increments counted from there.
TEST(ActionFrameSource, ARobotWithoutOdometryYetStandsStillWhenAsked)
{
    const auto waiting = teamSteps(false);
    ASSERT_EQ(waiting.size(), 2u);              // t = 3 and 4
    EXPECT_NEAR(waiting[0].first, 1.0, 1e-12);  // R1 from t = 1
    EXPECT_NEAR(waiting[0].second, 0.0, 1e-12);
    EXPECT_NEAR(waiting[1].first, 0.5, 1e-12);
    EXPECT_NEAR(waiting[1].second, 1.0, 1e-12);
    const auto standing = teamSteps(true);
    ASSERT_EQ(standing.size(), 4u);  // t = 1 to 4
    EXPECT_NEAR(standing[0].first, 0.0, 1e-12);
    for (const auto& [r1, r2] : {standing[1], standing[2], standing[3]})
        EXPECT_NEAR(r1, 0.5, 1e-12);
    EXPECT_NEAR(standing[0].second, 0.0, 1e-12);
    EXPECT_NEAR(standing[1].second, 0.0, 1e-12);
    EXPECT_NEAR(standing[2].second, 0.0, 1e-12);  // its first reading
    EXPECT_NEAR(standing[3].second, 1.0, 1e-12);
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
