// Whole filter steps on fuzzed observations: the bytes make a CObservationBearingRange (its
// readings, noise, covariances, sensor pose and limits: NaN, inf, huge, empty, negative) and
// two steps of each FastSLAM filter run on it with a small odometry increment: the omni FastSLAM
// (bearings of ceiling lights) and the multi-robot filter with one robot (range-bearing).
// Refusing an observation is an exception; a crash, a hang or a sanitizer report is a bug.
#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/multirobot/CMultiRobotVisualSLAM.h>
#include <mrpt_vslam/omni_fastslam/COmniFastSLAM.h>

#include <cstdint>
#include <exception>

#include "FuzzInput.h"

namespace {
using namespace mrpt_vslam;

mrpt::obs::CObservationBearingRange::Ptr observation(fuzz::FuzzInput& in, const std::string& label)
{
    auto o = std::make_shared<mrpt::obs::CObservationBearingRange>();
    o->sensorLabel = label;
    o->minSensorDistance = static_cast<float>(in.number());
    o->maxSensorDistance = static_cast<float>(in.number());
    o->fieldOfView_yaw = static_cast<float>(in.number());
    o->fieldOfView_pitch = static_cast<float>(in.number());
    o->sensor_std_range = static_cast<float>(in.number());
    o->sensor_std_yaw = static_cast<float>(in.number());
    o->sensor_std_pitch = static_cast<float>(in.number());
    o->validCovariances = (in.byte() & 1) != 0;
    if (in.byte() & 1) {
        const double x = in.number(), y = in.number(), z = in.number();
        o->setSensorPose(mrpt::poses::CPose3D(x, y, z, in.number(), in.number(), in.number()));
    }
    const size_t n = in.byte() % 17;
    for (size_t i = 0; i < n; i++) {
        mrpt::obs::CObservationBearingRange::TMeasurement m;
        m.range = static_cast<float>(in.number());
        m.yaw = in.number();
        m.pitch = in.number();
        m.landmarkID = static_cast<int32_t>(in.byte()) - 1;
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++) m.covariance(r, c) = in.number();
        o->sensedData.push_back(m);
    }
    return o;
}

mrpt::obs::CActionCollection odometry(fuzz::FuzzInput& in)
{
    mrpt::obs::CActionRobotMovement2D act;
    act.computeFromOdometry(
        mrpt::poses::CPose2D(in.finite(-0.5, 0.5), in.finite(-0.5, 0.5), in.finite(-0.5, 0.5)),
        mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    mrpt::obs::CActionCollection acts;
    acts.insert(act);
    return acts;
}

template <class FILTER>
void twoSteps(FILTER& filter, fuzz::FuzzInput& in, const std::string& label)
{
    mrpt::bayes::CParticleFilter pf;
    pf.m_options.PF_algorithm = (in.byte() & 1) != 0
                                    ? mrpt::bayes::CParticleFilter::pfOptimalProposal
                                    : mrpt::bayes::CParticleFilter::pfStandardProposal;
    pf.setVerbosityLevel(mrpt::system::LVL_ERROR);
    for (int step = 0; step < 2; step++) {
        auto acts = odometry(in);
        mrpt::obs::CSensoryFrame frame;
        frame.insert(observation(in, label));
        try {
            pf.executeOn(filter, &acts, &frame);
        } catch (const std::exception&) {
            return;  // refused: the filter is not meant to go on
        }
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    fuzz::FuzzInput in(data, size);
    {
        omni_fastslam::COmniFastSLAM filter(omni_fastslam::CCeilingLightsMap(), 4, 1);
        filter.reset({0, 0, 0}, 0);
        twoSteps(filter, in, filter.options.bearings_label);
    }
    {
        multirobot::CMultiRobotVisualSLAM filter(multirobot::CVisualLandmarksMap(), 4, 1);
        filter.options.robots = {"R1"};
        filter.reset({{0, 0, 0}}, 0);
        twoSteps(filter, in, "");
    }
    return 0;
}
