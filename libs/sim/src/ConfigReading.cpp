#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>

namespace mrpt_vslam::sim {

double readDegrees(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::string& key, double default_rad)
{
    return mrpt::DEG2RAD(cfg.read_double(section, key, mrpt::RAD2DEG(default_rad)));
}

mrpt::poses::CPose3D readPose3D(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section,
                                const mrpt::poses::CPose3D& default_pose)
{
    const std::string& s = section;
    return mrpt::poses::CPose3D(cfg.read_double(s, "x", default_pose.x()),
                                cfg.read_double(s, "y", default_pose.y()),
                                cfg.read_double(s, "z", default_pose.z()),
                                readDegrees(cfg, s, "yaw_deg", default_pose.yaw()),
                                readDegrees(cfg, s, "pitch_deg", default_pose.pitch()),
                                readDegrees(cfg, s, "roll_deg", default_pose.roll()));
}

void checkConfig(bool ok, const std::string& section, const std::string& key,
                 const std::string& what)
{
    if (!ok) throw core::UsageError("[" + section + "] " + key + ": must be " + what);
}

}  // namespace mrpt_vslam::sim
