#include <mrpt/system/os.h>
#include <mrpt_vslam/core/Version.h>

namespace mrpt_vslam::core {

std::string projectVersion() { return MRPT_VSLAM_VERSION; }

std::string mrptVersion()
{
    std::string v = mrpt::system::MRPT_getVersion();  // "MRPT 2.5.8"
    const std::string prefix = "MRPT ";
    if (v.rfind(prefix, 0) == 0) v.erase(0, prefix.size());
    return v;
}

std::string versionLine(const std::string& app)
{
    return app + " " + projectVersion() + " (MRPT " + mrptVersion() + ")\n";
}

}  // namespace mrpt_vslam::core
