// TTeamMessage: every field through encode/decode; foreign or damaged bytes refused.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt_vslam/team/TeamMessage.h>

#include <stdexcept>

using mrpt_vslam::team::TTeamMessage;

TEST(TeamMessage, ReadingRoundTrips)
{
    auto obs = mrpt::obs::CObservationBearingRange::Create();
    obs->sensorLabel = "R2_RANGE_BEARING";
    obs->timestamp = mrpt::Clock::fromDouble(1248446480.179);
    obs->sensedData.resize(2);
    obs->sensedData[1].range = 2.5f;
    obs->sensedData[1].yaw = 0.25f;
    obs->sensedData[1].landmarkID = 7;
    TTeamMessage m;
    m.type = TTeamMessage::Type::Reading;
    m.robot = "R2";
    m.seq = 123456789012ULL;
    m.sent_time = 1764338400.125;
    m.watermark = obs->timestamp + std::chrono::milliseconds(50);
    m.observation = obs;
    const auto bytes = m.encode();
    const auto d = TTeamMessage::decode(bytes.data(), bytes.size());
    EXPECT_EQ(d.type, m.type);
    EXPECT_EQ(d.robot, "R2");
    EXPECT_EQ(d.seq, m.seq);
    EXPECT_EQ(d.sent_time, m.sent_time);
    EXPECT_EQ(d.watermark, m.watermark);  // exactly: timestamps are sent as ticks
    const auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationBearingRange>(d.observation);
    ASSERT_TRUE(o);
    EXPECT_EQ(o->timestamp, obs->timestamp);
    EXPECT_EQ(o->sensorLabel, obs->sensorLabel);
    ASSERT_EQ(o->sensedData.size(), 2u);
    EXPECT_EQ(o->sensedData[1].range, 2.5f);
    EXPECT_EQ(o->sensedData[1].landmarkID, 7);
}

TEST(TeamMessage, WelcomeCarriesTheTeamClock)
{
    TTeamMessage m;
    m.type = TTeamMessage::Type::Welcome;
    m.robot = "R1";
    m.seq = 42;
    m.data_time = mrpt::Clock::fromDouble(1275350400.5);
    m.sent_time = 1764338400.0;
    const auto bytes = m.encode();
    const auto d = TTeamMessage::decode(bytes.data(), bytes.size());
    EXPECT_EQ(d.type, TTeamMessage::Type::Welcome);
    EXPECT_EQ(d.seq, 42u);
    EXPECT_EQ(d.data_time, m.data_time);
    EXPECT_EQ(d.sent_time, m.sent_time);
    EXPECT_FALSE(d.observation);
}

TEST(TeamMessage, RefusesForeignOrDamagedBytes)
{
    const std::vector<uint8_t> foreign{1, 2, 3, 4, 5, 6, 7, 8};
    EXPECT_THROW(TTeamMessage::decode(foreign.data(), foreign.size()), std::runtime_error);
    TTeamMessage m;
    m.type = TTeamMessage::Type::Ack;
    m.robot = "R1";
    auto bytes = m.encode();
    EXPECT_THROW(TTeamMessage::decode(bytes.data(), bytes.size() - 3), std::runtime_error);
    bytes.push_back(0);
    EXPECT_THROW(TTeamMessage::decode(bytes.data(), bytes.size()), std::runtime_error);
    TTeamMessage reading;
    reading.type = TTeamMessage::Type::Reading;  // without an observation
    EXPECT_THROW(reading.encode(), std::logic_error);
}
