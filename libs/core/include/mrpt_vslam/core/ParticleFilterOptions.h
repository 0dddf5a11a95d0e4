#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CConfigFileBase.h>

#include <string>

namespace mrpt_vslam::core {

/** Loads `options` from `section` as CParticleFilter::TParticleFilterOptions::loadFromConfigFile()
 *  does, with the values the project recommends for the keys MRPT requires besides sampleSize:
 *  PF_algorithm = pfOptimalProposal (FastSLAM 2.0), resamplingMethod = prSystematic, BETA = 0.5,
 *  adaptiveSampleSize = false. Throws std::invalid_argument naming the key unless PF_algorithm is
 *  pfStandardProposal or pfOptimalProposal (the proposals this project's filters implement),
 *  resamplingMethod one of MRPT's, BETA in [0, 1], powFactor in (0, 1] and
 *  max_loglikelihood_dyn_range finite and > 0 (checked before MRPT's loader, which would ask an
 *  auxiliary filter for its own keys and assert on a negative range). */
void loadParticleFilterOptions(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                               mrpt::bayes::CParticleFilter::TParticleFilterOptions& options);

}  // namespace mrpt_vslam::core
