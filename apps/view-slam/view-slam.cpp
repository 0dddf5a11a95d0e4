// view-slam: view-based omnidirectional EKF SLAM with information-based view initialization
// (Valiente et al. 2015).
#include <mrpt_vslam/apps/ViewSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

int main(int argc, char** argv)
{
    using namespace mrpt_vslam;
    try {
        auto args = core::AppArguments::parse(
            argc, argv, "view-slam",
            "View-based EKF SLAM with a single omnidirectional camera and information-based "
            "view initialization (Valiente, Ghaffari Jadidi, Valls Miro, Gil, Reinoso). Reads a "
            "rawlog in either MRPT format of one robot's odometry and its omnidirectional images "
            "(CObservationImage; any label unless the config names one); writes the run folder "
            "described in doc/view-slam.md.");
        if (args.request != core::AppArguments::Request::Run) {
            std::cout << args.message;
            return 0;
        }
        apps::ViewSLAMApp app(std::move(args));
        app.initialize();
        app.run();
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << "view-slam: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "view-slam: error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
