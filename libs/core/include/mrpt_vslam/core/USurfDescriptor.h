#pragma once

#include <mrpt_vslam/core/IntegralImage.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace mrpt::img {
class CImage;
}

namespace mrpt_vslam::core {

/** Upright SURF (U-SURF) descriptor, Bay, Ess, Tuytelaars & Van Gool, "Speeded-Up Robust
 *  Features (SURF)", CVIU 110(3), 2008, Sec. 4.1, as used by Gil et al. (2010) for multi-robot
 *  visual SLAM. For a keypoint (x, y) at scale s:
 *
 *   1. Take the 20s × 20s square centred on the keypoint, aligned with the image axes (no
 *      orientation assignment: "upright").
 *   2. Sample a regular 20 × 20 grid in it, spacing s, at offsets (i + ½)s − 10s, i = 0..19.
 *   3. At each sample compute the Haar wavelet responses dx, dy of side 2s on the integral image
 *      (haarX(), haarY()).
 *   4. Weight them with a Gaussian of σ = 3.3s centred on the keypoint.
 *   5. Split the square into 4 × 4 sub-regions of 5 × 5 samples and accumulate in each
 *      v = (Σdx, Σdy, Σ|dx|, Σ|dy|).
 *   6. Normalise the 64-vector to unit length (invariance to contrast; the wavelets already
 *      cancel a brightness offset).
 *
 *  Layout: element 4·(4·r + c) + k holds component k of v for the sub-region in row r (top to
 *  bottom) and column c (left to right).
 *
 *  Sub-pixel sampling: the wavelet boxes have side exactly 2s and are centred exactly on the
 *  samples; their sums are exact integrals of the piecewise-constant image
 *  (IntegralImage::integralAt()), so neither the keypoint nor s is rounded to whole pixels. The
 *  box edges of neighbouring samples coincide (spacing s = half the box side), so one descriptor
 *  needs the integral at only 22 × 22 points, x + (j − 10.5)s, j = 0..21.
 *
 *  Border handling: no clamping or padding. A keypoint whose wavelet boxes do not all lie inside
 *  the image, i.e. with x − 10.5s < −½ or x + 10.5s > width − ½ (same for y and the height), gets
 *  no descriptor (std::nullopt), and so does a keypoint on a perfectly flat patch (zero vector, no
 *  direction to normalise).
 *
 *  Usage:
 *   1. Build once per image: `USurfDescriptor usurf(gray);` (integral image, O(width·height)).
 *   2. For each keypoint: `if (auto d = usurf.compute(x, y, s)) ...`.
 *   3. Match: `USurfDescriptor::bestMatch(query, candidates, 0.7)`.
 */
class USurfDescriptor {
  public:
    static constexpr size_t kSize = 64;  ///< descriptor length
    using TDescriptor = std::array<float, kSize>;

    /// Result of a nearest-neighbour search.
    struct TMatch {
        size_t index = 0;            ///< index of the nearest candidate
        double distance = 0;         ///< Euclidean distance to it
        double second_distance = 0;  ///< distance to the second nearest (+inf if only one)
    };

    /** Builds the integral image of `image` (colour images are converted to grayscale).
     *  \throw std::invalid_argument for an empty or non-8-bit image. */
    explicit USurfDescriptor(const mrpt::img::CImage& image);

    /** Descriptor of the keypoint at column x, row y [px] with SURF scale s [px] (the blob
     *  scale of the detector; the window is 20s wide).
     *  \return std::nullopt near the border or on a flat patch (see the class notes).
     *  \throw std::invalid_argument if x, y are not finite or s is not finite and positive. */
    std::optional<TDescriptor> compute(double x, double y, double scale) const;

    /** True when every wavelet box of compute(x, y, scale) lies inside the image.
     *  \throw std::invalid_argument as compute(). */
    bool fitsInImage(double x, double y, double scale) const;

    /// @name Haar wavelet responses of side 2s at (x, y) [gray levels]
    /// Mean of the right (bottom) half minus mean of the left (top) half of the 2s × 2s box
    /// centred on (x, y); a step edge of height H through the box centre gives H.
    /// The box must lie inside the image (unchecked).
    /// @{
    double haarX(double x, double y, double scale) const;
    double haarY(double x, double y, double scale) const;
    /// @}

    /// Euclidean distance between two descriptors.
    static double distance(const TDescriptor& a, const TDescriptor& b);

    /** Brute-force nearest neighbour of `query` among `candidates` with Lowe's ratio test:
     *  accepted when distance < ratio · second_distance (always, with a single candidate).
     *  \return std::nullopt if `candidates` is empty or the test fails.
     *  \throw std::invalid_argument unless 0 < ratio ≤ 1. */
    static std::optional<TMatch> bestMatch(const TDescriptor& query,
                                           const std::vector<TDescriptor>& candidates,
                                           double ratio = 0.7);

    const IntegralImage& integralImage() const { return m_integral; }

  private:
    IntegralImage m_integral;
};

}  // namespace mrpt_vslam::core
