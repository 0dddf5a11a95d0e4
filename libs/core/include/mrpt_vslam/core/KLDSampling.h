#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/random/RandomGenerators.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mrpt_vslam::core {

/** The options of KLD-sampling, with the keys and units of MRPT's mrpt::slam::TKLDParams (ini
 *  section `[KLD_options]`; KLD_binSize_PHI in degrees there). Kept here rather than taken from
 *  mrpt-slam: that library alone makes an app load mrpt-vision and every OpenCV module at
 *  start-up. The defaults are the ones measured best with omni-fastslam (doc/omni-fastslam.md). */
struct TKLDParams : public mrpt::config::CLoadableOptions {
    double KLD_binSize_XY = 0.1;                  ///< [m]
    double KLD_binSize_PHI = mrpt::DEG2RAD(2.0);  ///< [rad]
    double KLD_delta = 0.01;                      ///< [-] δ of Fox 2003, Eq. 12
    double KLD_epsilon = 0.05;                    ///< [-] ε of Fox 2003, Eq. 12
    unsigned int KLD_minSampleSize = 10;          ///< [-]
    unsigned int KLD_maxSampleSize = 2000;        ///< [-]
    double KLD_minSamplesPerBin = 0;              ///< [-]

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                            const std::string& section) override;
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                          const std::string& section) const override;
};

/** Throws std::invalid_argument naming the first key of `params` out of its range: bin sizes,
 *  KLD_epsilon > 0, KLD_delta in (0, 1), 1 <= KLD_minSampleSize <= KLD_maxSampleSize,
 *  KLD_minSamplesPerBin >= 0. */
void validateKLDParams(const TKLDParams& params);

/** The number of samples KLD-sampling asks for once they occupy `bins` bins (Fox 2003, Eq. 12):
 *  n = (k − 1)/(2ε) · (1 − 2/(9(k − 1)) + √(2/(9(k − 1))) z_{1−δ})³, so that with probability
 *  1 − δ the Kullback-Leibler divergence between the sample-based and the true posterior stays
 *  below ε; then at least KLD_minSampleSize and KLD_minSamplesPerBin · k, at most
 *  KLD_maxSampleSize. */
size_t kldSampleCount(size_t bins, const TKLDParams& params);

/** Resampling with an adaptive sample size (KLD-sampling, Fox 2003, Table 1): draws particle
 *  indices by weight, one at a time, counting the (x, y, φ) bins of size KLD_binSize_XY and
 *  KLD_binSize_PHI their poses fall in, until the drawn count reaches kldSampleCount() of the
 *  bins occupied so far. The same generator state gives the same indices.
 *
 *  \param log_w the particles' log-weights (any offset) \param poses their poses
 *  \throw std::invalid_argument on empty or mismatched input, or invalid params
 *  \return the indices of the new particle set, in the order drawn */
std::vector<size_t> kldResample(const std::vector<double>& log_w,
                                const std::vector<mrpt::math::TPose2D>& poses,
                                const TKLDParams& params, mrpt::random::CRandomGenerator& rng);

}  // namespace mrpt_vslam::core
