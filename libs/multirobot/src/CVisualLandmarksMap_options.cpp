#include <mrpt/config/CConfigFileBase.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>

#include <cmath>
#include <ostream>

namespace mrpt_vslam::multirobot {

using core::requireKey;

void CVisualLandmarksMap::TInsertionOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(D0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(E0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(p0, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(search_radius, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(grid_cell_size, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(joint_association, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(associate_by_identity, bool, cfg, section);
    requireKey(D0 > 0 && std::isfinite(D0), section, "D0", "must be finite and > 0");
    requireKey(E0 >= 0 && E0 <= 4, section, "E0",
               "must be in [0, 4] (squared distance of unit descriptors)");
    requireKey(p0 > 0 && std::isfinite(p0), section, "p0", "must be finite and > 0");
    requireKey(search_radius > 0 && std::isfinite(search_radius), section, "search_radius",
               "must be finite and > 0");
    requireKey(!(joint_association && associate_by_identity), section, "associate_by_identity",
               "cannot be combined with joint_association");
    requireKey(grid_cell_size > 0 && std::isfinite(grid_cell_size), section, "grid_cell_size",
               "must be finite and > 0");
}

void CVisualLandmarksMap::TInsertionOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CVisualLandmarksMap::TInsertionOptions] ------------ \n\n";
    LOADABLEOPTS_DUMP_VAR(D0, double);
    LOADABLEOPTS_DUMP_VAR(E0, double);
    LOADABLEOPTS_DUMP_VAR(p0, double);
    LOADABLEOPTS_DUMP_VAR(search_radius, double);
    LOADABLEOPTS_DUMP_VAR(grid_cell_size, double);
    LOADABLEOPTS_DUMP_VAR(joint_association, bool);
    LOADABLEOPTS_DUMP_VAR(associate_by_identity, bool);
}

void CVisualLandmarksMap::TRenderOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(draw_ellipsoids, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(ellipsoid_quantiles, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(point_size, float, cfg, section);
    requireKey(ellipsoid_quantiles > 0, section, "ellipsoid_quantiles", "must be > 0");
    requireKey(point_size > 0, section, "point_size", "must be > 0");
}

void CVisualLandmarksMap::TRenderOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CVisualLandmarksMap::TRenderOptions] ------------ \n\n";
    LOADABLEOPTS_DUMP_VAR(draw_ellipsoids, bool);
    LOADABLEOPTS_DUMP_VAR(ellipsoid_quantiles, double);
    LOADABLEOPTS_DUMP_VAR(point_size, float);
}

}  // namespace mrpt_vslam::multirobot
