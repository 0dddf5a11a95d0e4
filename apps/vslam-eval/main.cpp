#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

#include "EvalApp.h"
#include "EvalCommandLine.h"

int main(int argc, char** argv)
{
    try {
        const auto params = mrpt_vslam::eval::parseEvalCommandLine(argc, argv);
        if (!params) return 0;  // --help or --version
        mrpt_vslam::eval::EvalApp app;
        app.params = *params;
        app.run();
        return 0;
    } catch (const mrpt_vslam::core::UsageError& e) {
        std::cerr << "vslam-eval: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "vslam-eval: error: " << mrpt_vslam::core::oneLineMessage(e) << "\n";
    }
    return 1;
}
