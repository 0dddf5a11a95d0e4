#include <mrpt/core/bits_math.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>

#include <sstream>

namespace mrpt_vslam::sim {

std::vector<double> readNumberList(const mrpt::config::CConfigFileBase& cfg,
                                   const std::string& section, const std::string& key,
                                   const std::vector<double>& default_values)
{
    if (!cfg.keyExists(section, key)) return default_values;
    std::string text = cfg.read_string(section, key, "");
    for (char& ch : text)
        if (ch == ',') ch = ' ';
    std::istringstream is(text);
    std::vector<double> values;
    std::string item;
    while (is >> item) {
        size_t used = 0;
        double value = 0;
        try {
            value = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != item.size())
            throw core::UsageError("[" + section + "] " + key + ": '" + item + "' is not a number");
        values.push_back(value);
    }
    return values;
}

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
