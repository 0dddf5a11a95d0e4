#include <mrpt/core/initializer.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt_vslam/viewmap/CViewMap.h>
#include <mrpt_vslam/viewmap/registerAllClasses.h>

void mrpt_vslam::viewmap::registerAllClasses_viewmap()
{
    mrpt::rtti::registerClass(CLASS_ID(mrpt_vslam::viewmap::CViewMap));
}

MRPT_INITIALIZER(registerAllClasses_viewmap_at_load)
{
    mrpt_vslam::viewmap::registerAllClasses_viewmap();
}
