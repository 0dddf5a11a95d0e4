#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
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
