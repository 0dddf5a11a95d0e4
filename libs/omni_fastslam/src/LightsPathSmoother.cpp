#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/omni_fastslam/LightsPathSmoother.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

namespace mrpt_vslam::omni_fastslam {

using core::requireKey;
using mrpt::math::TPose2D;

void LightsPathSmoother::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                      const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(smooth_path, bool, cfg, section);
    const int iterations =
        cfg.read_int(section, "max_iterations", static_cast<int>(max_iterations));
    requireKey(iterations >= 1 && iterations <= 1000, section, "max_iterations",
               "must be 1 to 1000");
    max_iterations = static_cast<unsigned int>(iterations);
    const int round_count = cfg.read_int(section, "rounds", static_cast<int>(rounds));
    requireKey(round_count >= 1 && round_count <= 100, section, "rounds", "must be 1 to 100");
    rounds = static_cast<unsigned int>(round_count);
    MRPT_LOAD_CONFIG_VAR(huber, double, cfg, section);
    requireKey(huber >= 0, section, "huber", "must be >= 0 (0: no Huber)");
    MRPT_LOAD_CONFIG_VAR(merge_distance, double, cfg, section);
    requireKey(merge_distance >= 0, section, "merge_distance", "must be >= 0 (0: no merging)");
}

void LightsPathSmoother::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                                    const std::string& section) const
{
    cfg.write(section, "smooth_path", smooth_path);
    cfg.write(section, "max_iterations", max_iterations);
    cfg.write(section, "rounds", rounds);
    cfg.write(section, "huber", huber);
    cfg.write(section, "merge_distance", merge_distance);
}

void LightsPathSmoother::onReset(const TPose2D&, double) { m_steps.clear(); }

void LightsPathSmoother::onStep(const core::TOdometryGaussian& motion,
                                const std::vector<TBearingMeasurement>& z)
{
    m_steps.push_back({motion, z});
}

namespace {

/// σ of the weak prior that keeps each light at its filter estimate along directions no
/// bearing constrains (the height of a planar model's lights) [m]
constexpr double kLightPriorStd = 100;
/// σ of the wall that keeps a light from coming nearer than the map's nearest reading range to
/// a camera that reads it [m]
constexpr double kNearRangeStd = 0.01;

/// One bearing of a light from a pose, whitened by its Q (planar model: φ alone).
struct TBearingTerm {
    size_t pose, light;
    size_t step;  ///< frame, for merging
    Eigen::Vector2d z;
    Eigen::Matrix2d W;  ///< W r is the whitened residual, Wᵀ W = Q⁻¹
};

/** The least-squares problem: poses 1..T (pose 0 fixed) and the lights, the odometry between
 *  consecutive poses and the bearings. A bearing also pays for its light nearer than
 *  `min_range` to the camera: its direction from there says little (Jacobians grow as
 *  1/range), and a light smoothed onto a pose would escape its bearings' costs. */
class Problem {
  public:
    Problem(const BearingMeasurementModel& model, double huber, double min_range)
        : m_model(model), m_huber(huber), m_min_range(min_range)
    {
    }

    std::vector<TPose2D> poses;
    std::vector<Eigen::Vector3d> lights, prior;
    std::vector<Eigen::Matrix3d> prior_cov;        ///< the filter's covariance of each light
    std::vector<core::TOdometryGaussian> motions;  ///< [k − 1]: from pose k − 1 to pose k
    std::vector<TBearingTerm> terms;

    /// Σ of the robust squared whitened residuals.
    double cost() const
    {
        double c = 0;
        for (size_t k = 1; k < poses.size(); k++) c += odometryResidual(k).squaredNorm();
        for (const auto& t : terms) {
            const double near = nearRangeResidual(t);
            c += robust(bearingResidual(t).squaredNorm()) + near * near;
        }
        for (size_t j = 0; j < lights.size(); j++)
            c += (lights[j] - prior[j]).squaredNorm() / (kLightPriorStd * kLightPriorStd);
        return c;
    }

    /// Bearings whose whitened residual is beyond the Huber threshold.
    size_t outliers() const
    {
        if (m_huber <= 0) return 0;
        return static_cast<size_t>(std::count_if(terms.begin(), terms.end(), [&](const auto& t) {
            return bearingResidual(t).norm() > m_huber;
        }));
    }

    /// Levenberg-Marquardt from the current values; returns the iterations made.
    size_t solve(unsigned int max_iterations)
    {
        double current = cost(), lambda = 1e-4;
        size_t it = 0;
        while (it < max_iterations) {
            it++;
            Eigen::SparseMatrix<double> H;
            Eigen::VectorXd g;
            normalEquations(H, g);
            bool accepted = false;
            while (!accepted && lambda < 1e10) {
                Eigen::SparseMatrix<double> damped = H;
                for (int i = 0; i < damped.rows(); i++)
                    damped.coeffRef(i, i) += lambda * std::max(H.coeff(i, i), 1e-9);
                const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(damped);
                if (ldlt.info() != Eigen::Success) {
                    lambda *= 10;
                    continue;
                }
                const Eigen::VectorXd delta = ldlt.solve(-g);
                const auto saved_poses = poses;
                const auto saved_lights = lights;
                apply(delta);
                const double next = cost();
                if (next < current) {
                    accepted = true;
                    const bool converged = current - next < 1e-10 * current;
                    current = next;
                    lambda = std::max(lambda / 10, 1e-12);
                    if (converged) return it;
                } else {
                    poses = saved_poses;
                    lights = saved_lights;
                    lambda *= 10;
                }
            }
            if (!accepted) break;
        }
        return it;
    }

    /** The marginal covariance of each light at the current values; the filter's where that
     *  is not positive definite or H cannot be factored, counted in `*kept_from_filter`. */
    std::vector<Eigen::Matrix3d> lightCovariances(size_t* kept_from_filter = nullptr) const
    {
        Eigen::SparseMatrix<double> H;
        Eigen::VectorXd g;
        normalEquations(H, g);
        const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
        if (ldlt.info() != Eigen::Success) {
            if (kept_from_filter) *kept_from_filter += lights.size();
            return prior_cov;
        }
        std::vector<Eigen::Matrix3d> covs(lights.size());
        for (size_t j = 0; j < lights.size(); j++) {
            const size_t col = lightIndex(j);
            Eigen::MatrixXd E = Eigen::MatrixXd::Zero(H.rows(), 3);
            for (int c = 0; c < 3; c++) E(static_cast<Eigen::Index>(col) + c, c) = 1;
            const Eigen::MatrixXd X = ldlt.solve(E);
            covs[j] = X.middleRows(static_cast<Eigen::Index>(col), 3);
            covs[j] = 0.5 * (covs[j] + covs[j].transpose()).eval();
            if (covs[j].llt().info() == Eigen::Success) continue;
            covs[j] = prior_cov[j];
            if (kept_from_filter) ++*kept_from_filter;
        }
        return covs;
    }

  private:
    const BearingMeasurementModel& m_model;
    double m_huber, m_min_range;

    size_t poseIndex(size_t k) const { return 3 * (k - 1); }  // k ≥ 1
    size_t lightIndex(size_t j) const { return 3 * (poses.size() - 1) + 3 * j; }

    double robust(double s2) const
    {
        if (m_huber <= 0 || s2 <= m_huber * m_huber) return s2;
        return 2 * m_huber * std::sqrt(s2) - m_huber * m_huber;
    }

    /** Whitened x_k ⊖ x_{k−1} − u_k (the odometry Gaussians are in the frame of x_{k−1}), and
     *  its Jacobians where asked for. */
    Eigen::Vector3d odometryResidual(size_t k, Eigen::Matrix3d* J_prev = nullptr,
                                     Eigen::Matrix3d* J = nullptr) const
    {
        const TPose2D& a = poses[k - 1];
        const TPose2D& b = poses[k];
        const TPose2D& u = motions[k - 1].mean;
        const double c = std::cos(a.phi), s = std::sin(a.phi);
        const double dx = b.x - a.x, dy = b.y - a.y;
        const Eigen::Vector3d e(c * dx + s * dy - u.x, -s * dx + c * dy - u.y,
                                mrpt::math::wrapToPi(b.phi - a.phi - u.phi));
        const Eigen::Matrix3d& L = motions[k - 1].L;
        if (J_prev) {
            Eigen::Matrix3d Ja, Jb;
            Ja << -c, -s, -s * dx + c * dy, s, -c, -c * dx - s * dy, 0, 0, -1;
            Jb << c, s, 0, -s, c, 0, 0, 0, 1;
            *J_prev = L.triangularView<Eigen::Lower>().solve(Ja);
            *J = L.triangularView<Eigen::Lower>().solve(Jb);
        }
        return L.triangularView<Eigen::Lower>().solve(e);
    }

    /// Whitened z − h(m, x) and, if asked, its Jacobians.
    Eigen::Vector2d bearingResidual(const TBearingTerm& t,
                                    BearingMeasurementModel::Matrix23* J_x = nullptr,
                                    BearingMeasurementModel::Matrix23* J_m = nullptr) const
    {
        const auto pred = m_model.predictWithJacobians(lights[t.light], poses[t.pose]);
        if (!pred.valid) {
            if (J_x) J_x->setZero(), J_m->setZero();
            return Eigen::Vector2d::Zero();
        }
        if (J_x) {
            *J_x = -t.W * pred.H_x;
            *J_m = -t.W * pred.H_m;
        }
        return t.W * BearingMeasurementModel::innovation(t.z, pred.z);
    }

    /** Whitened min_range − r where the light is nearer than min_range to the camera that
     *  reads it (r from the camera's origin; planar: in the plane), else 0; its Jacobians
     *  where asked for. */
    double nearRangeResidual(const TBearingTerm& t, Eigen::RowVector3d* J_x = nullptr,
                             Eigen::RowVector3d* J_m = nullptr) const
    {
        if (J_x) J_x->setZero(), J_m->setZero();
        if (m_min_range <= 0) return 0;
        const TPose2D& x = poses[t.pose];
        const Eigen::Vector3d c = m_model.rayOriginInMap(x);
        Eigen::Vector3d d = lights[t.light] - c;
        if (m_model.isPlanar()) d.z() = 0;
        const double r = d.norm();
        if (r >= m_min_range) return 0;
        if (J_x && r > 0) {
            const Eigen::RowVector3d u = d.transpose() / (r * kNearRangeStd);
            // the camera's origin moves with (x, y) and turns about the robot's origin with yaw
            const Eigen::Vector3d dc_dyaw(x.y - c.y(), c.x() - x.x, 0);
            *J_m = -u;
            *J_x << u.x(), u.y(), u.dot(dc_dyaw);
        }
        return (m_min_range - r) / kNearRangeStd;
    }

    void normalEquations(Eigen::SparseMatrix<double>& H, Eigen::VectorXd& g) const
    {
        const auto n = static_cast<Eigen::Index>(lightIndex(lights.size()));
        g = Eigen::VectorXd::Zero(n);
        std::vector<Eigen::Triplet<double>> triplets;
        const auto addBlock = [&](size_t row, size_t col, const Eigen::Matrix3d& B) {
            for (int r = 0; r < 3; r++)
                for (int c = 0; c < 3; c++)
                    triplets.emplace_back(static_cast<int>(row) + r, static_cast<int>(col) + c,
                                          B(r, c));
        };
        // the variables of a term: pose k (none for k = 0) and, for bearings, light j
        const auto addTerm = [&](size_t k, const Eigen::MatrixXd& J_pose, std::optional<size_t> j,
                                 const Eigen::MatrixXd& J_light, const Eigen::VectorXd& r) {
            if (k > 0) {
                addBlock(poseIndex(k), poseIndex(k), J_pose.transpose() * J_pose);
                g.segment<3>(static_cast<Eigen::Index>(poseIndex(k))) += J_pose.transpose() * r;
            }
            if (!j) return;
            addBlock(lightIndex(*j), lightIndex(*j), J_light.transpose() * J_light);
            g.segment<3>(static_cast<Eigen::Index>(lightIndex(*j))) += J_light.transpose() * r;
            if (k > 0) {
                const Eigen::Matrix3d B = J_pose.transpose() * J_light;
                addBlock(poseIndex(k), lightIndex(*j), B);
                addBlock(lightIndex(*j), poseIndex(k), B.transpose());
            }
        };
        for (size_t k = 1; k < poses.size(); k++) {
            Eigen::Matrix3d Ja, Jb;
            const Eigen::Vector3d r = odometryResidual(k, &Ja, &Jb);
            addTerm(k, Jb, std::nullopt, Eigen::Matrix3d::Zero(), r);
            if (k == 1) continue;
            addBlock(poseIndex(k - 1), poseIndex(k - 1), Ja.transpose() * Ja);
            addBlock(poseIndex(k - 1), poseIndex(k), Ja.transpose() * Jb);
            addBlock(poseIndex(k), poseIndex(k - 1), Jb.transpose() * Ja);
            g.segment<3>(static_cast<Eigen::Index>(poseIndex(k - 1))) += Ja.transpose() * r;
        }
        for (const auto& t : terms) {
            BearingMeasurementModel::Matrix23 J_x, J_m;
            Eigen::Vector2d r = bearingResidual(t, &J_x, &J_m);
            // Huber by reweighting: the weight of the robust cost's gradient at this residual
            const double s = r.norm();
            if (m_huber > 0 && s > m_huber) {
                const double w = std::sqrt(m_huber / s);
                r *= w;
                J_x *= w;
                J_m *= w;
            }
            addTerm(t.pose, J_x, t.light, J_m, r);
            Eigen::RowVector3d N_x, N_m;
            const double near = nearRangeResidual(t, &N_x, &N_m);
            if (near != 0) addTerm(t.pose, N_x, t.light, N_m, Eigen::VectorXd::Constant(1, near));
        }
        for (size_t j = 0; j < lights.size(); j++) {
            const double w = 1 / (kLightPriorStd * kLightPriorStd);
            addBlock(lightIndex(j), lightIndex(j), w * Eigen::Matrix3d::Identity());
            g.segment<3>(static_cast<Eigen::Index>(lightIndex(j))) += w * (lights[j] - prior[j]);
        }
        H.resize(n, n);
        H.setFromTriplets(triplets.begin(), triplets.end());
    }

    void apply(const Eigen::VectorXd& delta)
    {
        for (size_t k = 1; k < poses.size(); k++) {
            const auto d = delta.segment<3>(static_cast<Eigen::Index>(poseIndex(k)));
            poses[k] = TPose2D(poses[k].x + d[0], poses[k].y + d[1],
                               mrpt::math::wrapToPi(poses[k].phi + d[2]));
        }
        for (size_t j = 0; j < lights.size(); j++)
            lights[j] += delta.segment<3>(static_cast<Eigen::Index>(lightIndex(j)));
    }
};

/// W with Wᵀ W = Q⁻¹ (planar model: the φ row only).
Eigen::Matrix2d whitening(const Eigen::Matrix2d& Q, bool planar)
{
    if (planar) {
        Eigen::Matrix2d W = Eigen::Matrix2d::Zero();
        W(0, 0) = 1 / std::sqrt(Q(0, 0));
        return W;
    }
    const Eigen::Matrix2d L = Q.llt().matrixL();
    return L.inverse();
}

/// The closest pair of lights nearer than `distance` that no frame measured together.
std::optional<std::pair<size_t, size_t>> mergeablePair(const Problem& problem, double distance)
{
    std::vector<std::set<size_t>> steps(problem.lights.size());
    for (const auto& t : problem.terms) steps[t.light].insert(t.step);
    std::optional<std::pair<size_t, size_t>> best;
    double best_d = distance;
    for (size_t a = 0; a < problem.lights.size(); a++)
        for (size_t b = a + 1; b < problem.lights.size(); b++) {
            const double d = (problem.lights[a] - problem.lights[b]).norm();
            if (d >= best_d || steps[a].empty() || steps[b].empty()) continue;
            const bool together = std::any_of(steps[a].begin(), steps[a].end(),
                                              [&](size_t s) { return steps[b].count(s) > 0; });
            if (together) continue;
            best_d = d;
            best = std::make_pair(a, b);
        }
    return best;
}

}  // namespace

std::vector<const TOmniFastSLAMPath::TStep*> LightsPathSmoother::recordedStepsOf(
    const TOmniFastSLAMParticle& p) const
{
    auto steps = p.path.stepsOldestFirst();
    if (steps.size() != m_steps.size() + 1)
        throw std::logic_error("LightsPathSmoother: the particle's path has " +
                               std::to_string(steps.size()) + " steps for " +
                               std::to_string(m_steps.size()) +
                               " recorded steps (register it before the filter's reset())");
    return steps;
}

LightsPathSmoother::TResult LightsPathSmoother::smooth(const TOmniFastSLAMParticle& p) const
{
    const auto steps = recordedStepsOf(p);
    const BearingMeasurementModel model = p.map.measurementModel();
    Problem problem(model, options.huber, p.map.sensorLimitsInUse().min_range);
    for (const auto* s : steps) problem.poses.push_back(s->state.robot_in_map);
    for (const auto& s : m_steps) problem.motions.push_back(s.motion);

    const auto& landmarks = p.map.landmarks();
    std::map<int64_t, size_t> index_of_id;
    for (size_t j = 0; j < landmarks.size(); j++) {
        index_of_id[landmarks[j].id] = j;
        problem.lights.push_back(landmarks[j].mean);
        problem.prior_cov.push_back(landmarks[j].cov);
    }
    problem.prior = problem.lights;
    for (size_t k = 1; k < steps.size(); k++)
        for (const auto& c : steps[k]->state.correspondences) {
            const auto it = index_of_id.find(c.landmark_id);
            if (it == index_of_id.end()) continue;  // a light the map no longer has
            const TBearingMeasurement& m = m_steps[k - 1].z.at(c.measurement);
            problem.terms.push_back({k, it->second, k, m.z, whitening(m.Q, model.isPlanar())});
        }

    TResult result;
    result.initial_cost = problem.cost();
    result.iterations = problem.solve(options.max_iterations);
    // the bearings associated again at the smoothed poses (the filter's level-1 method),
    // with the lights' least-squares covariances
    for (unsigned int round = 1; round < options.rounds; round++) {
        CCeilingLightsMap lights = p.map;
        lights.clear();
        const auto covs = problem.lightCovariances();
        for (size_t j = 0; j < problem.lights.size(); j++)
            lights.addLandmark(problem.lights[j], covs[j]);
        problem.terms.clear();
        for (size_t k = 1; k < steps.size(); k++) {
            const auto& z = m_steps[k - 1].z;
            if (z.empty()) continue;
            Eigen::VectorXd log_p_new(static_cast<Eigen::Index>(z.size()));
            for (size_t l = 0; l < z.size(); l++)
                log_p_new(static_cast<Eigen::Index>(l)) = lights.logPNew(z[l]);
            const auto assoc = CCeilingLightsMap::solveAssociation(
                lights.landmarkLogLikelihoods(z, problem.poses[k]), log_p_new,
                p.map.insertionOptions.association_method);
            for (size_t l = 0; l < z.size(); l++)
                if (assoc[l] >= 0)
                    problem.terms.push_back({k, static_cast<size_t>(assoc[l]), k, z[l].z,
                                             whitening(z[l].Q, model.isPlanar())});
        }
        result.iterations += problem.solve(options.max_iterations);
    }
    result.bearings = problem.terms.size();
    // lights mapped twice: merged into the one with more bearings, then solved again
    std::vector<bool> removed(landmarks.size(), false);
    while (options.merge_distance > 0) {
        const auto pair = mergeablePair(problem, options.merge_distance);
        if (!pair) break;
        auto [a, b] = *pair;
        size_t na = 0, nb = 0;
        for (const auto& t : problem.terms) {
            if (t.light == a) na++;
            if (t.light == b) nb++;
        }
        if (nb > na) std::swap(a, b);
        for (auto& t : problem.terms)
            if (t.light == b) t.light = a;
        problem.lights[a] = (static_cast<double>(na) * problem.lights[a] +
                             static_cast<double>(nb) * problem.lights[b]) /
                            static_cast<double>(na + nb);
        problem.prior[a] = problem.lights[a];
        removed[b] = true;
        result.merged++;
        result.iterations += problem.solve(options.max_iterations);
    }
    result.final_cost = problem.cost();
    result.outliers = problem.outliers();
    const double h = options.huber;
    if (h > 0)
        result.outlier_probability =
            model.isPlanar() ? std::erfc(h / std::sqrt(2.0)) : std::exp(-h * h / 2);

    for (size_t k = 0; k < steps.size(); k++)
        result.path.emplace_back(steps[k]->timestamp, problem.poses[k]);
    result.map = p.map;
    result.map.clear();
    const auto covs = problem.lightCovariances(&result.lights_with_filter_covariance);
    for (size_t j = 0; j < landmarks.size(); j++)
        if (!removed[j])
            result.map.addLandmark(problem.lights[j], covs[j], landmarks[j].type,
                                   landmarks[j].counter);
    return result;
}

}  // namespace mrpt_vslam::omni_fastslam
