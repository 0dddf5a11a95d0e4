#include <mrpt_vslam/core/SensorTiltCorrection.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace mrpt_vslam::core {

namespace {

/// n = R_cᵀ e_z, the robot's up axis in the stated frame, and its derivatives by pitch and roll.
struct TUp {
    Eigen::Vector3d n, d_pitch, d_roll;
};

TUp up(const Eigen::Vector2d& a)
{
    const double sp = std::sin(a[0]), cp = std::cos(a[0]), sr = std::sin(a[1]), cr = std::cos(a[1]);
    return {{-sp, cp * sr, cp * cr}, {-cp, -sp * sr, -sp * cr}, {0, cp * cr, -cp * sr}};
}

/** One point's readings at tilt `a`: each one's residual e = (nᵀz − c) / √v, v = nᵀ R n, at the
 *  height c that fits them best, and its Jacobian by (pitch, roll), v's included: with v held
 *  fixed the fit would read the tilt short by the share of the readings' spread that is their
 *  noise (errors in the variables). */
struct TPointResiduals {
    std::vector<double> e, a;  // a = ∂e/∂c = −1/√v
    std::vector<Eigen::RowVector2d> J;
    double total_weight = 0;  // Σ 1/v

    TPointResiduals(const std::vector<TPointReading>& readings, const TUp& u)
    {
        std::vector<double> h, v;
        std::vector<Eigen::RowVector2d> dh, dv;
        double sum = 0;
        for (const auto& r : readings) {
            h.push_back(u.n.dot(r.z));
            dh.emplace_back(u.d_pitch.dot(r.z), u.d_roll.dot(r.z));
            const Eigen::Vector3d Rn = r.R * u.n;
            v.push_back(u.n.dot(Rn));
            dv.emplace_back(2 * u.d_pitch.dot(Rn), 2 * u.d_roll.dot(Rn));
            total_weight += 1 / v.back();
            sum += h.back() / v.back();
        }
        const double c = sum / total_weight;
        for (size_t k = 0; k < readings.size(); k++) {
            const double s = std::sqrt(v[k]);
            e.push_back((h[k] - c) / s);
            a.push_back(-1 / s);
            J.push_back(dh[k] / s - (h[k] - c) * dv[k] / (2 * v[k] * s));
        }
    }
    /// e_k over its own σ: var(h_k − c) = v_k − 1/Σ(1/v).
    double whitened(size_t k) const
    {
        return e[k] / std::sqrt(std::max(1 - a[k] * a[k] / total_weight, 1e-12));
    }
};

}  // namespace

TSensorTiltCorrection TSensorTiltCorrection::estimate(
    const std::vector<std::vector<TPointReading>>& points, double huber)
{
    const double priorInfo = 1 / (M_PI * M_PI);
    TSensorTiltCorrection c;
    std::vector<const std::vector<TPointReading>*> used;  // the points read more than once
    for (const auto& p : points)
        if (p.size() > 1) {
            used.push_back(&p);
            c.readings += p.size();
        }
    c.points = used.size();
    Eigen::Matrix2d H;
    for (int iteration = 0; iteration < 30; iteration++) {
        const TUp u = up(c.delta);
        H = priorInfo * Eigen::Matrix2d::Identity();
        Eigen::Vector2d g = priorInfo * c.delta;
        for (const auto* p : used) {
            const TPointResiduals r(*p, u);
            // Huber (IRLS); the point's height eliminated: e and J less their projections on a
            std::vector<double> w(p->size(), 1.0);
            double aa = 0, ae = 0;
            Eigen::RowVector2d aJ = Eigen::RowVector2d::Zero();
            for (size_t k = 0; k < p->size(); k++) {
                const double n = std::abs(r.whitened(k));
                if (huber > 0 && n > huber) w[k] = huber / n;
                aa += w[k] * r.a[k] * r.a[k];
                ae += w[k] * r.a[k] * r.e[k];
                aJ += w[k] * r.a[k] * r.J[k];
            }
            for (size_t k = 0; k < p->size(); k++) {
                const Eigen::RowVector2d J = r.J[k] - r.a[k] * aJ / aa;
                H += w[k] * J.transpose() * J;
                g += w[k] * J.transpose() * (r.e[k] - r.a[k] * ae / aa);
            }
        }
        const Eigen::Vector2d step = -H.ldlt().solve(g);
        c.delta += step;
        if (step.cwiseAbs().maxCoeff() < 1e-10) break;
    }
    c.cov = H.inverse();
    if (huber > 0) {
        const TUp u = up(c.delta);
        for (const auto* p : used) {
            const TPointResiduals r(*p, u);
            for (size_t k = 0; k < p->size(); k++)
                c.outlier_readings += std::abs(r.whitened(k)) > huber;
        }
    }
    return c;
}

}  // namespace mrpt_vslam::core
