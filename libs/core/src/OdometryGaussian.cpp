#include <mrpt/core/bits_math.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt_vslam/core/OdometryGaussian.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/core/ParallelFor.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>
#include <stdexcept>

namespace mrpt_vslam::core {

void TMotionNoiseFloor::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                           const std::string& section)
{
    std_xy = cfg.read_double(section, "min_motion_std_xy", std_xy);
    std_phi =
        mrpt::DEG2RAD(cfg.read_double(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(std_phi)));
    requireKey(std_xy > 0 && std::isfinite(std_xy), section, "min_motion_std_xy", "must be > 0");
    requireKey(std_phi > 0 && std::isfinite(std_phi), section, "min_motion_std_phi_deg",
               "must be > 0");
}

void TMotionNoiseFloor::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                         const std::string& section) const
{
    cfg.write(section, "min_motion_std_xy", std_xy);
    cfg.write(section, "min_motion_std_phi_deg", mrpt::RAD2DEG(std_phi));
}

TOdometryGaussian TOdometryGaussian::from(const mrpt::obs::CActionRobotMovement2D* odometry,
                                          const TMotionNoiseFloor& floor)
{
    TOdometryGaussian g;
    if (odometry) {
        mrpt::math::CMatrixDouble33 cov;
        mrpt::poses::CPose2D mean;
        odometry->poseChange->getCovarianceAndMean(cov, mean);
        g.mean = mean.asTPose();
        g.cov = cov.asEigen();
    }
    g.cov.diagonal() += Eigen::Vector3d(floor.std_xy * floor.std_xy, floor.std_xy * floor.std_xy,
                                        floor.std_phi * floor.std_phi);
    if (!g.cov.allFinite() || !std::isfinite(g.mean.x) || !std::isfinite(g.mean.y) ||
        !std::isfinite(g.mean.phi))
        throw std::runtime_error("odometry with a non-finite increment or covariance");
    const Eigen::LLT<Eigen::Matrix3d> llt(g.cov);
    if (llt.info() != Eigen::Success)
        throw std::runtime_error("odometry covariance is not positive definite");
    g.L = llt.matrixL();
    return g;
}

Eigen::Vector3d drawGaussian(mrpt::random::CRandomGenerator& rng, const Eigen::Matrix3d& L)
{
    Eigen::Vector3d n;
    for (int i = 0; i < 3; i++) n[i] = rng.drawGaussian1D_normalized();
    return L * n;
}

namespace {
/// The generator and the normal distribution that CRandomGenerator::drawGaussian1D_normalized()
/// draws with (protected members of MRPT 2.5's CRandomGenerator)
struct GeneratorParts : mrpt::random::CRandomGenerator {
    static mrpt::random::Generator_MT19937& bits(CRandomGenerator& rng)
    {
        return rng.*(&GeneratorParts::m_MT19937);
    }
    static std::normal_distribution<double>& normal(CRandomGenerator& rng)
    {
        return rng.*(&GeneratorParts::m_normdistribution);
    }
};
}  // namespace

const std::vector<Eigen::Vector3d>& drawStandardNormals(mrpt::random::CRandomGenerator& rng,
                                                        size_t count,
                                                        std::vector<Eigen::Vector3d>& n,
                                                        unsigned threads)
{
    n.resize(count);
    const size_t total = 3 * count;
    if (total == 0) return n;
    const auto at = [&](size_t v) -> double& { return n[v / 3][static_cast<Eigen::Index>(v % 3)]; };
    auto& bits = GeneratorParts::bits(rng);
    auto& normal = GeneratorParts::normal(rng);
    // The polar method as std::normal_distribution runs it: a pair of uniforms in the unit disc
    // gives two normals, the second kept for the next draw. A value kept from the last pair
    // (the distribution then differs from a fresh one) comes first; then the pairs are drawn in
    // order (serially: the generator's sequence), their logarithms and roots on the threads.
    size_t first = 0;
    if (!(normal == std::normal_distribution<double>(normal.param()))) at(first++) = normal(bits);
    struct TPair {
        double x, y, r2;
    };
    std::vector<TPair> pairs((total - first) / 2);
    for (auto& p : pairs) {
        do {
            p.x = 2.0 * std::generate_canonical<double, 53>(bits) - 1.0;
            p.y = 2.0 * std::generate_canonical<double, 53>(bits) - 1.0;
            p.r2 = p.x * p.x + p.y * p.y;
        } while (p.r2 > 1.0 || p.r2 == 0.0);
    }
    const double stddev = normal.stddev(), mean = normal.mean();
    parallelFor(pairs.size(), threads, [&](size_t i) {
        const TPair& p = pairs[i];
        const double mult = std::sqrt(-2 * std::log(p.r2) / p.r2);
        at(first + 2 * i) = p.y * mult * stddev + mean;
        at(first + 2 * i + 1) = p.x * mult * stddev + mean;
    });
    if (first + 2 * pairs.size() < total) at(total - 1) = normal(bits);  // keeps its pair's x
    return n;
}

}  // namespace mrpt_vslam::core
