// stereo-frontend: the stereo front-end of the multi-robot visual SLAM (Gil et al. 2010), as a
// rawlog-to-rawlog filter (see doc/stereo-frontend.md).
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

#include "FrontEndCommandLine.h"
#include "StereoFrontEndApp.h"

int main(int argc, char** argv)
{
    using namespace mrpt_vslam;
    try {
        auto args = multirobot::TFrontEndCommandLine::parse(argc, argv);
        if (args.request != multirobot::TFrontEndCommandLine::Request::Run) {
            std::cout << args.message;
            return 0;
        }
        multirobot::StereoFrontEndApp app(std::move(args));
        app.initialize();
        app.run();
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << "stereo-frontend: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "stereo-frontend: error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
