#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/core/IntegralImage.h>

#include <vector>

namespace mrpt_vslam::core {

/** SURF fast-Hessian interest-point detector, Bay, Ess, Tuytelaars & Van Gool, "Speeded-Up
 *  Robust Features (SURF)", CVIU 110(3), 2008, Sec. 3:
 *
 *   1. Box-filter approximations Dxx, Dyy, Dxy of the Gaussian second derivatives on the
 *      integral image (Sec. 3.2, Fig. 1), for filter sizes L = 9, 15, 21, 27 (σ = 1.2·L/9),
 *      normalised by the filter area L²; blob response det(H) = Dxx·Dyy − (0.9·Dxy)².
 *   2. Scale space (Sec. 3.3): octave o has the four sizes L = 3·(2^(o+1)·(i + 1) + 1),
 *      i = 0..3 (9-15-21-27, 15-27-39-51, 27-51-75-99, ...), sampled every initial_step·2^o
 *      pixels. A size shared with a finer octave reuses that octave's response map.
 *   3. Localisation (Sec. 3.4): responses above the threshold that are maxima of their
 *      3 × 3 × 3 neighbourhood in (x, y, scale), for the two middle sizes of each octave, then
 *      the maximum of a quadratic fitted by finite differences (Brown & Lowe 2002) gives the
 *      sub-pixel position and sub-scale filter size.
 *
 *  Each keypoint carries its SURF scale s = 1.2·L/9 [px], which is what USurfDescriptor
 *  expects, and the sign of the Laplacian Dxx + Dyy (+1 for a dark blob on a bright
 *  background, −1 for the reverse), which SURF uses for fast matching.
 *
 *  Choices the paper leaves open:
 *  - Filter responses are exact integer box sums, computed only where the whole filter lies
 *    inside the image; a candidate needs its full neighbourhood (the next size's filter at
 *    ±1 sample) inside the image.
 *  - Equal neighbours: a sample is kept if it is strictly greater than the neighbours before it
 *    in (scale, row, column) order and not smaller than those after it, so a plateau of two
 *    equal maxima gives exactly one keypoint.
 *  - The quadratic fit is rejected (no keypoint) when its Hessian is singular or its maximum
 *    lies more than one sample away in any of x, y, scale.
 *
 *  Usage:
 *   1. `USurfDescriptor usurf(gray);` (or `IntegralImage ii(gray);`)
 *   2. `auto kps = FastHessianDetector(options).detect(usurf.integralImage());`
 *   3. For each keypoint: `usurf.compute(kp.x, kp.y, kp.scale)` (upright SURF).
 */
class FastHessianDetector {
  public:
    /// Detector parameters; the ini keys are the member names.
    struct TOptions : public mrpt::config::CLoadableOptions {
        /** [gray levels²] minimum det(H) of a keypoint. A Gaussian blob of amplitude A
         *  [gray levels] peaks at about A²/32. */
        double hessian_threshold = 100.0;
        int octaves = 4;       ///< number of octaves, ≥ 1
        int initial_step = 1;  ///< [px] sampling step of the first octave, ≥ 1

        /// Throws std::invalid_argument naming the ini key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// Box-filter responses at one pixel and filter size, normalised by the area L².
    struct THessian {
        double dxx = 0;  ///< [gray levels] ≈ σ² ∂²I/∂x² (x: columns, to the right)
        double dyy = 0;  ///< [gray levels] ≈ σ² ∂²I/∂y² (y: rows, downwards)
        double dxy = 0;  ///< [gray levels] ≈ σ² ∂²I/∂x∂y
        /// det(H_approx) = Dxx·Dyy − (0.9·Dxy)² (Sec. 3.2).
        double determinant() const { return dxx * dyy - 0.81 * dxy * dxy; }
        /// Laplacian Dxx + Dyy (trace of H).
        double trace() const { return dxx + dyy; }
    };

    /// One interest point.
    struct TKeypoint {
        double x = 0;            ///< [px] column (sub-pixel)
        double y = 0;            ///< [px] row (sub-pixel)
        double scale = 0;        ///< [px] SURF scale s = 1.2·L/9 (sub-scale)
        double response = 0;     ///< [gray levels²] det(H) at the fitted maximum
        int laplacian_sign = 0;  ///< +1: dark blob on bright background, −1: bright on dark
    };

    /// Detector with the default options.
    FastHessianDetector();
    /// \throw std::invalid_argument if the options are invalid (TOptions::validate()).
    explicit FastHessianDetector(const TOptions& options);

    /// Keypoints of the image, in no particular order; the response maps are computed on up
    /// to `threads` threads (rows in parallel; the same keypoints whatever the count).
    std::vector<TKeypoint> detect(const IntegralImage& integral, unsigned threads = 1) const;

    /** Box responses of filter size L (odd multiple of 3, ≥ 9) centred on pixel (col, row). The
     *  filter must lie inside the image: (L − 1)/2 ≤ col ≤ width − 1 − (L − 1)/2, same for rows
     *  (unchecked). */
    static THessian boxHessian(const IntegralImage& integral, int col, int row, int filter_size);

    /// Filter size L of layer i (0..3) of octave o (0-based): 3·(2^(o+1)·(i + 1) + 1).
    static int filterSize(int octave, int layer);

    /// SURF scale s = 1.2·L/9 [px] of filter size L.
    static double scaleOfFilterSize(double filter_size) { return 1.2 * filter_size / 9.0; }

    const TOptions& options() const { return m_options; }

  private:
    TOptions m_options;
};

}  // namespace mrpt_vslam::core
