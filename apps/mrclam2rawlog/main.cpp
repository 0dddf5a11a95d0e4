// mrclam2rawlog: imports a UTIAS MRCLAM dataset as an observation-only rawlog with ground truth
// beside it (see doc/real-data.md and doc/data-formats.md).
#include <mrpt/system/CTicTac.h>
#include <mrpt_vslam/core/ErrorMessage.h>
#include <mrpt_vslam/core/UsageError.h>

#include <iostream>

#include "MrclamCommandLine.h"
#include "MrclamDataset.h"
#include "MrclamImporter.h"

int main(int argc, char** argv)
{
    using namespace mrpt_vslam;
    try {
        const auto args = mrclam::TMrclamCommandLine::parse(argc, argv);
        if (args.request != mrclam::TMrclamCommandLine::Request::Run) {
            std::cout << args.message;
            return 0;
        }
        mrpt::system::CTicTac timer;
        auto dataset = mrclam::TMrclamDataset::load(args.dataset_dir, args.robots);
        dataset.delayCommands(args.command_delay);
        mrclam::MrclamImporter importer(dataset, args);
        const mrclam::TImportSummary summary = importer.run();
        if (!args.quiet) std::cout << summary.describe(args.out_rawlog, timer.Tac());
        return 0;
    } catch (const core::UsageError& e) {
        std::cerr << "mrclam2rawlog: error: " << e.what() << "\n";
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "mrclam2rawlog: error: " << core::oneLineMessage(e) << "\n";
        return 1;
    }
}
