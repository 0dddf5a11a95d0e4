#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt_vslam/core/ObservationSelector.h>

using mrpt::obs::CObservationBearingRange;
using mrpt::obs::CObservationImage;
using mrpt_vslam::core::ObservationSelector;

TEST(ObservationSelector, AnEmptyLabelTakesEveryObservationOfTheClass)
{
    mrpt::obs::CSensoryFrame frame;
    for (const char* label : {"", "RB", "OTHER"}) {
        auto obs = CObservationBearingRange::Create();
        obs->sensorLabel = label;
        frame.insert(obs);
    }
    frame.insert(CObservationImage::Create());
    EXPECT_EQ(ObservationSelector::allIn<CObservationBearingRange>(frame, "").size(), 3u);
    EXPECT_EQ(ObservationSelector::allIn<CObservationBearingRange>(frame, "RB").size(), 1u);
    EXPECT_EQ(ObservationSelector::firstIn<CObservationBearingRange>(frame, "RB")->sensorLabel,
              "RB");
    EXPECT_EQ(ObservationSelector::firstIn<CObservationImage>(frame, "RB"), nullptr);
    EXPECT_EQ(ObservationSelector::of<CObservationBearingRange>("OTHER").eraseFrom(frame), 1u);
    EXPECT_EQ(frame.size(), 3u);
}

TEST(ObservationSelector, MessagesNameTheClassAndTheLabelWhenThereIsOne)
{
    EXPECT_EQ(ObservationSelector::of<CObservationImage>("").describe(), "CObservationImage");
    EXPECT_EQ(ObservationSelector::of<CObservationImage>("CAM").describe(),
              "CObservationImage labelled 'CAM'");
    CObservationBearingRange obs;
    EXPECT_EQ(ObservationSelector::nameOf(obs), "CObservationBearingRange");
    obs.sensorLabel = "R1_RB";
    EXPECT_EQ(ObservationSelector::nameOf(obs), "R1_RB");
}
