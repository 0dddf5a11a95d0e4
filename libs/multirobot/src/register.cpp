#include <mrpt/core/initializer.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>
#include <mrpt_vslam/multirobot/registerAllClasses.h>

void mrpt_vslam::multirobot::registerAllClasses_multirobot()
{
    mrpt::rtti::registerClass(CLASS_ID(mrpt_vslam::multirobot::CVisualLandmarksMap));
}

MRPT_INITIALIZER(registerAllClasses_multirobot_at_load)
{
    mrpt_vslam::multirobot::registerAllClasses_multirobot();
}
