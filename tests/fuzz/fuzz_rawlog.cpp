// The rawlog reader on any bytes, as every app reads its input: core::RawlogReader (its
// validating child process included) and every entry it returns. Errors are exceptions; a
// crash or a hang of this process is a bug.
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
        for (core::TRawlogEntry e; reader.next(e);) {
        }
        (void)reader.summary().describe();
    } catch (const std::exception&) {
    }
    return 0;
}
