#include <mrpt/core/initializer.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>
#include <mrpt_vslam/omni_fastslam/registerAllClasses.h>

void mrpt_vslam::omni_fastslam::registerAllClasses_omni_fastslam()
{
    mrpt::rtti::registerClass(CLASS_ID(mrpt_vslam::omni_fastslam::CCeilingLightsMap));
}

MRPT_INITIALIZER(registerAllClasses_omni_fastslam_at_load)
{
    mrpt_vslam::omni_fastslam::registerAllClasses_omni_fastslam();
}
