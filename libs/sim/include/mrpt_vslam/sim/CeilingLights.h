#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt_vslam/core/LandmarkFile.h>

#include <vector>

namespace mrpt_vslam::sim {

/** One ceiling light: a horizontal, downward-facing bright disk. */
struct TCeilingLight {
    int id = 0;                     ///< 1-based identifier (as in Table I of Gamallo et al. 2013)
    mrpt::math::TPoint3D position;  ///< [m] centre of the disk in the world frame
};

/** Ceiling lights laid out on a grid of columns (x) and rows (y), as in Gamallo et al. 2013,
 *  Table I. Column i holds the first `column_rows[i]` rows (ascending y); ids run column by
 *  column, rows ascending within a column, from 1, then through `extra_lights`. Also holds when
 * lights near the windows are washed out by daylight (Gamallo et al. 2013, Sec. IV: "big windows
 * ... occluding the landmarks near them"). */
class CeilingLights : public mrpt::config::CLoadableOptions {
  public:
    /// @name Parameters (ini section [Lights])
    /// @{
    std::vector<double> column_x{4.5, 13.5, 22.5, 31.5};  ///< [m] x of each column
    std::vector<double> row_y{-5.5, -1.0, 3.5, 8.0};      ///< [m] y of each row
    std::vector<int> column_rows{4, 4, 4, 2};             ///< [-] rows present per column
    /// [m] lights off the grid, as pairs x y ... (ini: extra_lights); ids follow the grid's
    std::vector<double> extra_lights;
    double height = 6.5;          ///< [m] z of the lights
    double radius = 0.22;         ///< [m] radius of each light disk
    double washout_x_min = 27.0;  ///< [m] lights with x ≥ this are near the windows
    /// [s] washout intervals [t0, t1) as pairs t0 t1 ... (ini: washout_intervals)
    std::vector<double> washout_intervals{40.0, 100.0};
    /// @}

    /// All lights, ordered by id.
    std::vector<TCeilingLight> lights() const;
    /// The lights as ground-truth landmarks (id, centre).
    core::LandmarkFile asLandmarkFile() const;
    /// Whether `light` is washed out (invisible) at time t [s] from the start of the run.
    bool isWashedOut(const TCeilingLight& light, double t) const;

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
};

}  // namespace mrpt_vslam::sim
