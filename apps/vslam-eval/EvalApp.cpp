#include "EvalApp.h"

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
    core::printEvalSummary(std::cout, result);
}

}  // namespace mrpt_vslam::eval
