#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/sim/CeilingLights.h>
#include <mrpt_vslam/sim/ConfigReading.h>

#include <algorithm>

namespace mrpt_vslam::sim {

std::vector<TCeilingLight> CeilingLights::lights() const
{
    std::vector<TCeilingLight> out;
    for (size_t c = 0; c < column_x.size(); c++) {
        for (int r = 0; r < column_rows[c]; r++) {
            TCeilingLight light;
            light.id = static_cast<int>(out.size()) + 1;
            light.position = {column_x[c], row_y[static_cast<size_t>(r)], height};
            out.push_back(light);
        }
    }
    for (size_t i = 0; i + 1 < extra_lights.size(); i += 2) {
        TCeilingLight light;
        light.id = static_cast<int>(out.size()) + 1;
        light.position = {extra_lights[i], extra_lights[i + 1], height};
        out.push_back(light);
    }
    return out;
}

core::LandmarkFile CeilingLights::asLandmarkFile() const
{
    core::LandmarkFile file;
    for (const TCeilingLight& l : lights()) {
        core::TLandmark lm;
        lm.id = l.id;
        lm.position = l.position;
        file.landmarks.push_back(lm);
    }
    return file;
}

bool CeilingLights::isWashedOut(const TCeilingLight& light, double t) const
{
    if (light.position.x < washout_x_min) return false;
    for (size_t i = 0; i + 1 < washout_intervals.size(); i += 2)
        if (t >= washout_intervals[i] && t < washout_intervals[i + 1]) return true;
    return false;
}

void CeilingLights::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                       const std::string& s)
{
    column_x = core::readNumberList(cfg, s, "column_x", column_x);
    row_y = core::readNumberList(cfg, s, "row_y", row_y);
    const std::vector<double> rows =
        core::readNumberList(cfg, s, "column_rows", {column_rows.begin(), column_rows.end()});
    column_rows.assign(rows.begin(), rows.end());
    extra_lights = core::readNumberList(cfg, s, "extra_lights", extra_lights);
    MRPT_LOAD_CONFIG_VAR(height, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(radius, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(washout_x_min, double, cfg, s);
    washout_intervals = core::readNumberList(cfg, s, "washout_intervals", washout_intervals);

    checkConfig(!column_x.empty() && !row_y.empty(), s, "column_x, row_y", "non-empty lists");
    checkConfig(column_rows.size() == column_x.size(), s, "column_rows",
                "one count per entry of column_x");
    checkConfig(std::all_of(rows.begin(), rows.end(),
                            [&](double n) {
                                return n >= 0 && n <= static_cast<double>(row_y.size()) &&
                                       n == static_cast<int>(n);
                            }),
                s, "column_rows", "integers in [0, number of rows]");
    checkConfig(extra_lights.size() % 2 == 0, s, "extra_lights", "pairs x y");
    checkConfig(radius > 0, s, "radius", "> 0");
    checkConfig(washout_intervals.size() % 2 == 0, s, "washout_intervals", "pairs t0 t1");
    for (size_t i = 0; i < washout_intervals.size(); i += 2)
        checkConfig(washout_intervals[i] <= washout_intervals[i + 1], s, "washout_intervals",
                    "pairs with t0 <= t1");
}

}  // namespace mrpt_vslam::sim
