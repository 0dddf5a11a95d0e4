// The rawlog reader on any bytes, as every app reads its input: core::RawlogReader (its
// validating child process included) and the filter steps core::ActionFrameSource makes of its
// entries (both formats; format #2 with the odometry of robots R1 and R2, as the seeds name
// them). Errors are exceptions; a crash or a hang of this process is a bug.
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationImage.h>
#include <mrpt/obs/CObservationStereoImages.h>
#include <mrpt_vslam/core/ActionFrameSource.h>
#include <mrpt_vslam/core/RawlogReader.h>

#include <cstdint>
#include <exception>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace mrpt_vslam;
    const std::string file = fuzz::writeScratchFile("input.rawlog", data, size);
    try {
        core::RawlogReader reader(file);
        using core::ObservationSelector;
        core::ActionFrameSource steps(
            reader,
            {ObservationSelector::of<mrpt::obs::CObservationBearingRange>(""),
             ObservationSelector::ofOneSensor<mrpt::obs::CObservationImage>("", "image_label"),
             ObservationSelector::of<mrpt::obs::CObservationStereoImages>("")},
            {}, {"R1_ODOM", "R2_ODOM"});
        mrpt::obs::CActionCollection::Ptr actions;
        mrpt::obs::CSensoryFrame::Ptr frame;
        try {
            while (steps.next(actions, frame)) {
            }
        } catch (const std::exception&) {  // a step's error: the reader goes on
        }
        for (core::TRawlogEntry e; reader.next(e);) {
        }
        (void)reader.summary().describe();
    } catch (const std::exception&) {
    }
    return 0;
}
