#pragma once

#include <mrpt/config/CConfigFile.h>

#include <string>

namespace mrpt_vslam::sim::test {

/// The shipped sports-hall scenario configuration.
inline std::string sportsHallIni()
{
    return std::string(MRPT_VSLAM_SOURCE_DIR) +
           "/share/mrpt-vslam/config/vslam-sim/sports-hall.ini";
}

inline mrpt::config::CConfigFile sportsHallConfig()
{
    return mrpt::config::CConfigFile(sportsHallIni());
}

/// The shipped office-team scenario configuration.
inline std::string officeTeamIni()
{
    return std::string(MRPT_VSLAM_SOURCE_DIR) +
           "/share/mrpt-vslam/config/vslam-sim/office-team.ini";
}

inline mrpt::config::CConfigFile officeTeamConfig()
{
    return mrpt::config::CConfigFile(officeTeamIni());
}

}  // namespace mrpt_vslam::sim::test
