#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/viewmap/PlanarEssentialMatrix.h>
#include <mrpt_vslam/viewmap/ViewFeatures.h>
#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace mrpt_vslam::viewmap {

/** Predicted observation of a stored view (doc/core-features.md §4) with its uncertainty:
 *  ẑ = h(x_v, x_l) and S = H P Hᵀ from the EKF, without the observation noise R. */
struct TPrediction {
    TViewObservation z;                           ///< ẑ = (φ̂, β̂) [rad]
    Eigen::Matrix2d S = Eigen::Matrix2d::Zero();  ///< [rad²] covariance of ẑ
};

/** Where the points of a stored view can appear in the current image, given the prediction
 *  (doc/view-slam.md §4.1; the "predicted area" of the captions of Figs 4-5 of Valiente et
 *  al., J. Robotics 2012): the point λ p_l (λ > 0) of the view, moved by a motion M_j drawn from
 *  N(ẑ, S), is seen from the robot in the direction of R_z(β_j) λ p_l + s t_j
 *  (t_j = (cos φ_j, sin φ_j, 0), s > 0 the unknown baseline). Over all depths these directions
 *  sweep, in closed form, the arc of the epipolar great circle of E(φ_j, β_j) p_l from the
 *  epipole t_j (λ → 0) to the direction at infinity R_z(β_j) p_l (λ → ∞): the part of the
 *  circle with positive depths (PlanarEssentialMatrix::depthSign()). The area is the union of
 *  these arcs over the motions, widened by a tolerance:
 *
 *   - motions [ours]: the square in the eigenbasis of S with corners at ±k σ along both
 *     eigenvectors, k = search_sigmas; its 9 samples are the centre ẑ, ±k σ along each
 *     eigenvector and the 4 diagonal combinations (a 3 × 3 grid);
 *   - at each sample, p_v is inside when its Sampson residual on the sphere
 *     (PlanarEssentialMatrix::residual) is ≤ tolerance and its projection on the epipolar plane
 *     lies on the arc, extended by the tolerance (as an angle) at both ends;
 *   - between samples [ours]: the epipolar constraint c = p_vᵀ E(φ, β) p_l is continuous in
 *     (φ, β), so when it changes sign along one of the 12 edges of the grid the pair is exactly
 *     epipolar for a motion on that edge. That motion is found by regula falsi on the edge
 *     (epipole and direction at infinity interpolated between the samples) and the test above
 *     is made there in double precision; when the crossing is off the arc, also at the two ends
 *     of the band around it, where the arc has moved. This fills the area between the
 *     samples' bands, which would otherwise leave gaps as soon as k σ exceeds the tolerance
 *     (the 9 bands alone miss 12 % of the points λ p_l moved by motions of the hull, measured
 *     with σ up to 8°; the filled area misses none).
 *   - The filling is only tried for pairs whose c changes sign over the samples and whose
 *     projection lies within half the spans of the hull in φ and β (plus the tolerance) of the
 *     arc of some sample (no arc of the hull reaches farther); ViewFeatureMatcher tries it only
 *     for the points that would be among the two nearest descriptors.
 *
 *  With S = 0 the area is the tolerance band around the arc of ẑ; it grows with S. Measured
 *  against the brute-force union over a 41 × 41 grid of motions of the hull (tests): every
 *  pair inside the shrunk union (half the tolerance, hull × 0.9) is accepted and none outside
 *  the grown one (2 × tolerance, hull × 1.1). What stays approximate are corners of the band
 *  near the ends of the arcs inside a cell of the grid: of the pairs well inside the area of S,
 *  0.1 % are not in the area of 4 S. When k σ reaches 90° along an eigenvector the prediction
 *  no longer restricts anything (the epipolar constraint may change sign twice along an edge):
 *  the area is the whole sphere.
 *
 *  Usage: `PredictedSearchArea area(prediction, 3.0, DEG2RAD(1.5));
 *          if (area.contains(p_v, p_l)) ...` (ViewFeatureMatcher tests all pairs at once).
 */
class PredictedSearchArea {
  public:
    static constexpr size_t kSamples = 9;

    /** \throw std::invalid_argument for a non-finite ẑ, an S that is not symmetric PSD, a
     *  search_sigmas < 0 or a tolerance outside (0, π/2). */
    PredictedSearchArea(const TPrediction& prediction, double search_sigmas, double tolerance);

    /// Whether the view ray p_l may be seen as the current ray p_v (unit rays, robot frames).
    bool contains(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const;

    /** The 9 motions; sample 3·i + j is ẑ + (i − 1) k σ₁ v₁ + (j − 1) k σ₂ v₂ with (σ², v) the
     *  eigenpairs of S, so sample 4 is ẑ. */
    const std::array<TViewObservation, kSamples>& samples() const { return m_samples; }
    /// True when k σ ≥ 90°: every pair is inside.
    bool wholeSphere() const { return m_whole_sphere; }
    double tolerance() const { return m_tolerance; }

    /// @name Batch test (what ViewFeatureMatcher runs; contains() is its one-pair case)
    /// @{
    /// Current rays, structure of arrays padded with zeros, with the E_jᵀ p_v terms of the
    /// Sampson residual.
    struct TCurrentRays {
        std::vector<float> x, y, z;
        std::array<std::vector<float>, kSamples> et_pv2;  ///< |E_jᵀ p_v|² per sample
    };
    /// Per-sample terms of one view ray p_l (E_j p_l and its arc).
    struct TViewRay {
        std::array<std::array<float, 3>, kSamples> e_pl;  ///< E_j p_l
        std::array<float, kSamples> e_pl2, inv_e_pl2;     ///< |E_j p_l|², its inverse (0: none)
        std::array<std::array<float, 3>, kSamples> mid;   ///< middle of the arc (unit)
        std::array<float, kSamples> cos_half;             ///< cos(half arc + tolerance)
        /// cos(half arc + tolerance + reach): farther than that from the arc at every sample,
        /// a current ray is on no arc of the hull's motions
        std::array<float, kSamples> cos_near;
        Eigen::Vector3d p_l;                      ///< the view ray
        std::array<Eigen::Vector3d, kSamples> r;  ///< R_z(β_j) p_l
    };
    /// Scratch of test(), reused from one call to the next.
    struct TWorkspace {
        std::array<std::vector<float>, kSamples> c;  ///< p_vᵀ E_j p_l
        std::vector<float> c_min, c_max;             ///< extremes of c over the samples
        std::vector<int32_t> near;                   ///< 0 / 1: near an arc at some sample
        std::vector<int32_t> inside;  ///< 0 / 1 (32 bits, like the floats, so that it vectorizes)
    };
    TCurrentRays prepareCurrent(const Eigen::Matrix3Xd& rays) const;
    TViewRay prepareView(const Eigen::Vector3d& p_l) const;
    /** Tests view ray `l` against the current rays begin..end − 1: element i of the result is
     *  1 when current ray begin + i is inside, 0 otherwise (stored in `ws`). */
    const std::vector<int32_t>& test(const TCurrentRays& current, size_t begin, size_t end,
                                     const TViewRay& l, TWorkspace& ws) const;
    /** test() in two steps: the 9 samples for all rays (ws.inside), then, for the rays that
     *  needsFilling(), the exact test between the samples. */
    void testSamples(const TCurrentRays& current, size_t begin, size_t end, const TViewRay& l,
                     TWorkspace& ws) const;
    /// Ray begin + i is outside the samples' bands but may lie between them.
    static bool needsFilling(const TWorkspace& ws, size_t i);
    /// Whether ray begin + i (needsFilling()) is inside between the samples.
    bool betweenSamples(const TCurrentRays& current, size_t begin, size_t i, const TViewRay& l,
                        const TWorkspace& ws) const;
    /// @}

  private:
    enum class TArcTest { Inside, OffBand, OffArc };
    /** The test, in double precision, for the motion of epipole t (unit, horizontal) and
     *  direction at infinity r = R_z(β) p_l (between the samples). */
    TArcTest arcTest(const Eigen::Vector3d& t, const Eigen::Vector3d& r,
                     const Eigen::Vector3d& p_v) const;
    /// √(|E p_l|² + |Eᵀ p_v|² − 2c²) of the Sampson residual, for the same motion.
    static double sampsonDenominator(const Eigen::Vector3d& t, const Eigen::Vector3d& r,
                                     const Eigen::Vector3d& p_v);

    std::array<TViewObservation, kSamples> m_samples;
    std::array<Eigen::Matrix3d, kSamples> m_E;  ///< PlanarEssentialMatrix::fromMotion per sample
    std::array<Eigen::Vector3d, kSamples> m_t;  ///< (cos φ_j, sin φ_j, 0)
    std::array<Eigen::Matrix3d, kSamples> m_R;  ///< R_z(β_j)
    double m_tolerance, m_cos_tolerance, m_sin_tolerance;
    double m_reach = 0;  ///< [rad] half the spans of the hull in φ and β, plus the tolerance
    bool m_whole_sphere = false;
};

/** Data association of a stored view with the current image (doc/view-slam.md §4.1,
 *  §4 step 4): for each view point, the nearest current point by descriptor distance among those
 *  with the same sign of the Laplacian (SURF's fast matching) inside the predicted area
 *  (PredictedSearchArea; or anywhere with restrict_search_area = false), accepted when
 *   - its distance is ≤ max_descriptor_distance,
 *   - Lowe's ratio test passes: distance < max_ratio × the second nearest in the same set
 *     (passed by a single candidate, as USurfDescriptor::bestMatch),
 *   - mutual consistency: a current point claimed by several view points goes to the nearest.
 *  Matches are sorted by current index. Descriptor distances stop early once a candidate can
 *  no longer be among the two nearest, and the area's exact test between its samples
 *  (PredictedSearchArea::betweenSamples) is only made for candidates that would be.
 */
class ViewFeatureMatcher {
  public:
    /// Parameters; ini keys are the member names, angles in degrees with `_deg`.
    struct TOptions : public mrpt::config::CLoadableOptions {
        double search_sigmas = 3.0;  ///< k: the motions span ±k σ of S
        /** [rad] (`area_tolerance_deg`, 1.5°): about 3 times the RMS Sampson residual of
         *  inliers on the rendered images (0.2-0.4°), like RANSAC's 1° threshold. */
        double area_tolerance = 0.026179938779914945;
        double max_ratio = 0.8;  ///< Lowe's ratio, in (0, 1]
        /** Largest descriptor distance of a match. 0.5 [ours]: on 40 rendered pairs, matches
         *  farther than that were wrong (residual > 0.6° under the true motion) twice as often
         *  as right with restricted matching, ten times unrestricted. */
        double max_descriptor_distance = 0.5;
        bool restrict_search_area = true;  ///< false: whole image, same tests otherwise

        /// Throws std::invalid_argument naming the ini key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    /// One correspondence.
    struct TMatch {
        uint32_t current = 0;  ///< index into the current features
        uint32_t view = 0;     ///< index into the view's features
        float distance = 0;    ///< descriptor distance (Euclidean, as USurfDescriptor::distance)
    };

    struct TResult {
        std::vector<TMatch> matches;  ///< sorted by current index
        /// descriptor comparisons: the pairs inside the area at a sample or maybe between them
        size_t candidates_compared = 0;
    };

    ViewFeatureMatcher();
    /// \throw std::invalid_argument if the options are invalid (TOptions::validate()).
    explicit ViewFeatureMatcher(const TOptions& options);

    /** Matches of the view's points in the current image.
     *  \throw std::invalid_argument for features of inconsistent sizes, or as
     *  PredictedSearchArea for a bad prediction. */
    TResult match(const TViewFeatures& current, const TViewFeatures& view,
                  const TPrediction& prediction) const;

    const TOptions& options() const { return m_options; }

  private:
    TOptions m_options;
};

}  // namespace mrpt_vslam::viewmap
