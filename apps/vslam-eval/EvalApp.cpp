#include "EvalApp.h"

#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>

#include <filesystem>
#include <iostream>

#include "Plots.h"

namespace mrpt_vslam::eval {

void EvalApp::run()
{
    result = core::evaluateRunFolder(params);
    const auto out = std::filesystem::path(core::resolveInputs(params).out_dir);
    plotPaths(result, params.align, (out / "paths.png").string());
    plotErrors(result, params.align, (out / "errors.png").string());
    if (result.landmarks)
        plotLandmarkErrors(*result.landmarks, (out / "landmark_errors.png").string());
    printSummary(std::cout);
}

void EvalApp::printSummary(std::ostream& os) const
{
    const auto line = [&](const std::string& what, const core::TTrajectoryMetrics& m) {
        os << mrpt::format(
            "%-22s ATE RMSE %.3f m (max %.3f m), heading RMSE %.2f deg, %.0f%% of "
            "frames under the heading threshold\n",
            what.c_str(), m.ate_rmse, m.ate_max, mrpt::RAD2DEG(m.heading_rmse),
            100 * m.heading_share_under_threshold);
    };
    for (const auto& r : result.robots) {
        const std::string robot = r.files.robot.empty() ? "" : r.files.robot + " ";
        line(robot + "estimate:", r.estimate.unaligned);
        line(robot + "estimate aligned:", r.estimate.aligned);  // SE(2)-aligned to the truth
        if (r.odometry) line(robot + "odometry:", r.odometry->unaligned);
    }
    if (const auto& l = result.landmarks)
        os << mrpt::format(
            "landmarks:             %zu true, %zu estimated: %zu matched, %zu "
            "false (%zu duplicated), %zu missed; error mean %.3f m, max %.3f m\n",
            l->num_true, l->num_estimated, l->num_matched, l->num_false, l->num_duplicates,
            l->num_missed, l->error_mean, l->error_max);
}

}  // namespace mrpt_vslam::eval
