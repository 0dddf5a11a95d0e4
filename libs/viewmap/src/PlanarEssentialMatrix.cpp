#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/viewmap/PlanarEssentialMatrix.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace mrpt_vslam::viewmap {
namespace {

/** σ3 / σ1 of the n × 4 system below which its null space counts as more than one-dimensional.
 *  Exact degenerate data gives ~1e-16; the noiseless random scenes of 4 matches of the tests all
 *  stay above. */
constexpr double kRankTolerance = 1e-9;
/// Tolerance on |p| − 1 of an input ray.
constexpr double kUnitTolerance = 1e-6;

void checkRaysAt(const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
                 const std::vector<size_t>& indices)
{
    if (rays_v.cols() != rays_l.cols()) {
        throw std::invalid_argument(
            mrpt::format("PlanarEssentialMatrix: %d rays in the robot frame but %d in the view",
                         int(rays_v.cols()), int(rays_l.cols())));
    }
    for (size_t k : indices) {
        if (k >= size_t(rays_v.cols())) {
            throw std::invalid_argument(
                mrpt::format("PlanarEssentialMatrix: match index %zu out of range (%d matches)", k,
                             int(rays_v.cols())));
        }
        for (const Eigen::Matrix3Xd* rays : {&rays_v, &rays_l}) {
            const double n = rays->col(Eigen::Index(k)).norm();
            if (!(std::abs(n - 1) <= kUnitTolerance)) {
                throw std::invalid_argument(mrpt::format(
                    "PlanarEssentialMatrix: ray %zu has length %g, unit rays expected", k, n));
            }
        }
    }
}

std::vector<size_t> allIndices(const Eigen::Matrix3Xd& rays)
{
    std::vector<size_t> indices(size_t(rays.cols()));
    std::iota(indices.begin(), indices.end(), size_t(0));
    return indices;
}

Eigen::Matrix3d rotZ(double angle)
{
    return Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

}  // namespace

PlanarEssentialMatrix PlanarEssentialMatrix::fromMotion(double phi, double beta)
{
    // e13 = sin φ, e23 = −cos φ, e31 = sin(β − φ), e32 = cos(β − φ); |e| = √2.
    const Eigen::Vector4d e(std::sin(phi), -std::cos(phi), std::sin(beta - phi),
                            std::cos(beta - phi));
    return PlanarEssentialMatrix(e / std::sqrt(2.0));
}

void PlanarEssentialMatrix::checkRays(const Eigen::Matrix3Xd& rays_v,
                                      const Eigen::Matrix3Xd& rays_l)
{
    checkRaysAt(rays_v, rays_l, allIndices(rays_v));
}

std::optional<PlanarEssentialMatrix> PlanarEssentialMatrix::fit(const Eigen::Matrix3Xd& rays_v,
                                                                const Eigen::Matrix3Xd& rays_l,
                                                                const std::vector<size_t>& indices)
{
    checkRaysAt(rays_v, rays_l, indices);
    if (indices.size() < 4) return std::nullopt;
    // One row per match: [p_v,x p_l,z, p_v,y p_l,z, p_v,z p_l,x, p_v,z p_l,y] · e = 0.
    Eigen::MatrixX4d A(indices.size(), 4);
    for (size_t i = 0; i < indices.size(); i++) {
        const auto pv = rays_v.col(Eigen::Index(indices[i]));
        const auto pl = rays_l.col(Eigen::Index(indices[i]));
        A.row(Eigen::Index(i)) << pv.x() * pl.z(), pv.y() * pl.z(), pv.z() * pl.x(),
            pv.z() * pl.y();
    }
    const Eigen::JacobiSVD<Eigen::MatrixX4d> svd(A, Eigen::ComputeFullV);
    const Eigen::Vector4d sigma = svd.singularValues();  // descending
    if (!(sigma(2) > kRankTolerance * sigma(0))) return std::nullopt;
    return PlanarEssentialMatrix(svd.matrixV().col(3).normalized());
}

std::optional<PlanarEssentialMatrix> PlanarEssentialMatrix::fit(const Eigen::Matrix3Xd& rays_v,
                                                                const Eigen::Matrix3Xd& rays_l)
{
    return fit(rays_v, rays_l, allIndices(rays_v));
}

PlanarEssentialMatrix::PlanarEssentialMatrix(const Eigen::Vector4d& e) : m_e(e)
{
    m_E.setZero();
    m_E(0, 2) = e(0);
    m_E(1, 2) = e(1);
    m_E(2, 0) = e(2);
    m_E(2, 1) = e(3);
    // φ = atan2(e13, −e23), β = φ + atan2(e31, e32).
    m_motion.phi = std::atan2(e(0), -e(1));
    m_motion.beta = mrpt::math::wrapToPi(m_motion.phi + std::atan2(e(2), e(3)));
    m_R = rotZ(m_motion.beta);
    m_t = Eigen::Vector3d(std::cos(m_motion.phi), std::sin(m_motion.phi), 0);
}

int PlanarEssentialMatrix::depthSign(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const
{
    // Least squares of [p_v, −R p_l] (λ_v, λ_l)ᵀ = t; unit columns.
    const Eigen::Vector3d b = -m_R * p_l;
    const double ab = p_v.dot(b), det = 1 - ab * ab;
    if (!(det > 1e-12)) return 0;  // parallel rays: no depth
    const double at = p_v.dot(m_t), bt = b.dot(m_t);
    const double lambda_v = (at - ab * bt) / det, lambda_l = (bt - ab * at) / det;
    if (lambda_v > 0 && lambda_l > 0) return 1;
    if (lambda_v < 0 && lambda_l < 0) return -1;
    return 0;
}

PlanarEssentialMatrix::TCheirality PlanarEssentialMatrix::cheirality(
    const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
    const std::vector<size_t>& indices) const
{
    checkRaysAt(rays_v, rays_l, indices);
    TCheirality count;
    for (size_t k : indices) {
        const int sign = depthSign(rays_v.col(Eigen::Index(k)), rays_l.col(Eigen::Index(k)));
        count.in_front += sign > 0;
        count.behind += sign < 0;
    }
    return count;
}

std::optional<TViewObservation> PlanarEssentialMatrix::motion(
    const Eigen::Matrix3Xd& rays_v, const Eigen::Matrix3Xd& rays_l,
    const std::vector<size_t>& indices) const
{
    const TCheirality count = cheirality(rays_v, rays_l, indices);
    if (count.in_front == count.behind) return std::nullopt;
    TViewObservation z = m_motion;
    // −E: the same β, the opposite translation.
    if (count.behind > count.in_front) z.phi = mrpt::math::wrapToPi(z.phi + M_PI);
    return z;
}

double PlanarEssentialMatrix::residual(const Eigen::Vector3d& p_v, const Eigen::Vector3d& p_l) const
{
    const Eigen::Vector3d Ep_l = m_E * p_l, Etp_v = m_E.transpose() * p_v;
    const double c = p_v.dot(Ep_l);
    // Gradients of c, restricted to the tangent planes of the unit rays.
    const double den2 = (Ep_l - c * p_v).squaredNorm() + (Etp_v - c * p_l).squaredNorm();
    if (!(den2 > 0)) return c == 0 ? 0.0 : std::numeric_limits<double>::infinity();
    return std::abs(c) / std::sqrt(den2);
}

}  // namespace mrpt_vslam::viewmap
