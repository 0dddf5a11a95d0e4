#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/poses/CPose3D.h>

#include <string>

namespace mrpt_vslam::sim {

/** Reads an angle given in degrees under `key` (which ends in `_deg`) and returns it in
 *  radians, or `default_rad` when the key is absent. */
double readDegrees(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::string& key, double default_rad);

/** Reads a 6-DoF pose from the keys `x y z` [m] and `yaw_deg pitch_deg roll_deg` of `section`;
 *  absent keys keep the value of `default_pose`. */
mrpt::poses::CPose3D readPose3D(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section,
                                const mrpt::poses::CPose3D& default_pose);

/** Throws core::UsageError "[section] key: must be <what>" unless `ok`. */
void checkConfig(bool ok, const std::string& section, const std::string& key,
                 const std::string& what);

}  // namespace mrpt_vslam::sim
