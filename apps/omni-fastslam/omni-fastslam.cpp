// omni-fastslam: FastSLAM 2.0 with an upward fisheye camera and ceiling lights
// (Gamallo et al. 2013).
#include <mrpt_vslam/apps/OmniFastSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

int main(int argc, char** argv)
{
    using namespace mrpt_vslam;
    try {
        auto args = core::AppArguments::parse(
            argc, argv, "omni-fastslam",
            "FastSLAM 2.0 for an upward fisheye camera looking at ceiling lights, with "
            "hierarchical Hungarian data association and delayed landmark initialization "
            "(Gamallo, Mucientes, Regueiro). Reads a rawlog in either MRPT format of one robot's "
            "odometry and its upward camera's images (CObservationImage) or the lights' bearings "
            "(CObservationBearingRange; any label unless the config names one); writes the run "
            "folder described in doc/omni-fastslam.md.");
        if (args.request != core::AppArguments::Request::Run) {
            std::cout << args.message;
            return 0;
        }
        apps::OmniFastSLAMApp app(std::move(args));
        app.initialize();
        app.run();
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << "omni-fastslam: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "omni-fastslam: error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
