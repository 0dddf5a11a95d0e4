// An outside MRPT program: finds the installed package, creates the map from .ini text through
// MRPT's registry (linking is enough to register it), and serializes it.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/TMetricMapInitializer.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <iostream>

int main()
{
    mrpt::config::CConfigFileMemory cfg("[M]\nceilingLightsMap_count = 1\n");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, "M");
    const mrpt::maps::CMultiMetricMap maps(inits);
    const auto lights = maps.mapByClass<mrpt_vslam::omni_fastslam::CCeilingLightsMap>();
    if (!lights) return 1;
    mrpt::io::CMemoryStream buf;
    mrpt::serialization::archiveFrom(buf) << *lights;
    std::cout << "consumer ok: " << lights->asString() << "\n";
    return 0;
}
