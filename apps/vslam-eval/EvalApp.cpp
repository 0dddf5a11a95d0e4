#include "EvalApp.h"

#include <cstdio>
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
    const auto landmarkErrors = (out / "landmark_errors.png").string();
    if (result.landmarks)
        plotLandmarkErrors(*result.landmarks, landmarkErrors);
    else
        std::remove(landmarkErrors.c_str());  // an earlier evaluation's, with landmarks
    core::printEvalSummary(std::cout, result);
}

}  // namespace mrpt_vslam::eval
