// multirobot-vslam: one Rao-Blackwellized particle filter over a robot team's paths and a shared
// map of 3D visual landmarks (Gil et al. 2010).
#include <mrpt_vslam/apps/MultiRobotVSLAMApp.h>
#include <mrpt_vslam/core/AppArguments.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

int main(int argc, char** argv)
{
    using namespace mrpt_vslam;
    try {
        auto args = core::AppArguments::parse(
            argc, argv, "multirobot-vslam",
            "Multi-robot stereo visual SLAM (Gil, Reinoso, Ballesta, Julia, Paya 2010): one "
            "Rao-Blackwellized particle filter over the paths of a robot team and one shared map "
            "of 3D landmarks with U-SURF descriptors. Reads a rawlog in either MRPT format: one "
            "robot's odometry and landmark readings (CObservationBearingRange, "
            "CObservationVisualLandmarks or CObservationStereoImages; any label unless the config "
            "names one), or a team's, labelled <ROBOT>_ODOM and <ROBOT>_RB, <ROBOT>_LANDMARKS or "
            "<ROBOT>_STEREO; writes the run folder described in doc/multirobot.md. With --listen, "
            "the robots stream their readings live (vslam-robot-node, doc/team-online.md).",
            true);
        if (args.request != core::AppArguments::Request::Run) {
            std::cout << args.message;
            return 0;
        }
        apps::MultiRobotVSLAMApp app(std::move(args));
        app.initialize();
        app.run();
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << "multirobot-vslam: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "multirobot-vslam: error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
