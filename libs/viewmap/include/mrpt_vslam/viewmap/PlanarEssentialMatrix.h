#pragma once

#include <mrpt_vslam/viewmap/ViewObservation.h>

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace mrpt_vslam::viewmap {

/** Essential matrix of a planar motion (doc/core-features.md §4). With p_v the unit ray of a
 *  point in the current robot frame and p_l the unit ray of the same point in the stored view
 *  (z axis vertical in both):
 *
 *      p_vᵀ E p_l = 0,   E = [t]× R_z(β),   t = (cos φ, sin φ, 0),
 *
 *          [ 0           0          sin φ ]
 *      E = [ 0           0         −cos φ ]     (up to scale)
 *          [ sin(β − φ)  cos(β − φ)  0     ]
 *
 *  so only e = (e13, e23, e31, e32) is stored (unit norm), and each match gives the linear
 *  equation [p_v,x p_l,z, p_v,y p_l,z, p_v,z p_l,x, p_v,z p_l,y] · e = 0. (φ, β) is the
 *  observation h of ViewObservation.h: φ the bearing of the view seen from the robot, β the
 *  relative heading.
 *
 *  Recovery: φ = atan2(e13, −e23) up to π (the sign of E), β = φ + atan2(e31, e32) (unique).
 *  Cheirality picks φ or φ + π: the depths of λ_v p_v − λ_l R_z(β) p_l = t must be positive.
 *
 *  Rays are 3 × n matrices, column k holding match k; they must have unit length.
 */
class PlanarEssentialMatrix {
  public:
    /// Depth-sign count of the cheirality test (see cheirality()).
    struct TCheirality {
        size_t in_front = 0;  ///< matches with λ_v > 0 and λ_l > 0 for t = (cos φ, sin φ, 0)
        size_t behind = 0;    ///< matches with both depths < 0, i.e. in front for −t
    };

    /** Checks a set of matches: as many rays in both frames, all finite and of unit length.
     *  \throw std::invalid_argument naming the first offending ray. */
    static void checkRays(const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l);

    /// E of the motion (φ, β).
    static PlanarEssentialMatrix fromMotion(double phi, double beta);

    /** Linear solve over the matches listed in `indices`: e is the right singular vector
     *  of the n × 4 system with the smallest singular value.
     *  \return nullopt with fewer than 4 matches or when the null space is not one-dimensional
     *  (all rays alike, zero baseline with exact data, all rays horizontal).
     *  \throw std::invalid_argument if the ray sets differ in size, an index is out of range or
     *  a ray is not a finite unit vector. */
    static std::optional<PlanarEssentialMatrix> fit(const Eigen::Matrix3Xd& rays_v,
                                                    const Eigen::Matrix3Xd& rays_l,
                                                    const std::vector<size_t>& indices);
    /// fit() over all matches.
    static std::optional<PlanarEssentialMatrix> fit(const Eigen::Matrix3Xd& rays_v,
                                                    const Eigen::Matrix3Xd& rays_l);

    /// (e13, e23, e31, e32), unit norm.
    const Eigen::Vector4d& coefficients() const { return m_e; }
    /// The full 3 × 3 matrix.
    const Eigen::Matrix3d& matrix() const { return m_E; }

    /// (φ, β) read from E as it stands: φ = atan2(e13, −e23) is only defined up to π.
    const TViewObservation& motionUpToPi() const { return m_motion; }

    /** Cheirality of one match for t = (cos φ, sin φ, 0) with (φ, β) = motionUpToPi(): the
     *  least-squares depths of λ_v p_v − λ_l R_z(β) p_l = t are both positive (+1), both negative
     *  (−1, in front for −t), or neither: mixed signs or parallel rays (0). */
    int depthSign(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const;

    /// depthSign() counted over the listed matches.
    TCheirality cheirality(const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
                           const std::vector<size_t>& indices) const;

    /** (φ, β) with φ chosen by cheirality: motionUpToPi() if most listed matches lie in front,
     *  φ + π if most lie behind; nullopt on a tie (e.g. no match with parallax). */
    std::optional<TViewObservation> motion(const Eigen::Matrix3Xd& rays_v,
                                           const Eigen::Matrix3Xd& rays_l,
                                           const std::vector<size_t>& indices) const;

    /** Epipolar residual of one match [rad]: the Sampson distance on the sphere,
     *  |c| / √(|g_v|² + |g_l|²) with c = p_vᵀ E p_l and g_v, g_l the gradients of c projected on
     *  the tangent planes of p_v, p_l: to first order, the smallest rotation of the two rays
     *  (root of the sum of squared angles) that satisfies the constraint. */
    double residual(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const;

  private:
    explicit PlanarEssentialMatrix(const Eigen::Vector4d& e);

    Eigen::Vector4d m_e;
    Eigen::Matrix3d m_E;        ///< full matrix of m_e
    TViewObservation m_motion;  ///< motionUpToPi()
    Eigen::Matrix3d m_R;        ///< R_z(β)
    Eigen::Vector3d m_t;        ///< (cos φ, sin φ, 0)
};

}  // namespace mrpt_vslam::viewmap
