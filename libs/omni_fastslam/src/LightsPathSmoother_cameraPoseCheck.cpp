#include <mrpt_vslam/omni_fastslam/LightsPathSmoother.h>

#include <cmath>
#include <map>

namespace mrpt_vslam::omni_fastslam {

namespace {

/// Bearing z read as the point where its ray, from the camera on the robot at the origin,
/// meets the plane z = `height`, in the robot's plane: its (x, y) and covariance (the
/// bearing's Q through the Jacobian, by central differences). None where the ray does not
/// rise to that plane.
std::optional<std::pair<Eigen::Vector2d, Eigen::Matrix2d>> pointOnPlane(
    const BearingMeasurementModel& model, const TBearingMeasurement& z, double height)
{
    const mrpt::math::TPose2D origin(0, 0, 0);
    const auto o = model.rayOriginInMap(origin);
    const auto meet = [&](const Eigen::Vector2d& angles) -> std::optional<Eigen::Vector2d> {
        const auto d = model.rayDirectionInMap(angles, origin);
        if (d.z() < 1e-3) return std::nullopt;  // (nearly) horizontal or downwards
        const double s = (height - o.z()) / d.z();
        if (s <= 0) return std::nullopt;
        return Eigen::Vector2d(o.x() + s * d.x(), o.y() + s * d.y());
    };
    const auto p = meet(z.z);
    if (!p) return std::nullopt;
    constexpr double h = 1e-6;
    Eigen::Matrix2d J;
    for (int i = 0; i < 2; i++) {
        Eigen::Vector2d plus = z.z, minus = z.z;
        plus[i] += h;
        minus[i] -= h;
        const auto a = meet(plus), b = meet(minus);
        if (!a || !b) return std::nullopt;
        J.col(i) = (*a - *b) / (2 * h);
    }
    return std::make_pair(*p, J * z.Q * J.transpose());
}

}  // namespace

std::optional<core::TSensorPoseCorrection> LightsPathSmoother::cameraPoseCheck(
    const TOmniFastSLAMParticle& p) const
{
    const auto steps = recordedStepsOf(p);
    const BearingMeasurementModel model = p.map.measurementModel();
    if (model.isPlanar()) return std::nullopt;
    std::map<int64_t, double> heightOf;
    for (const auto& l : p.map.landmarks()) heightOf[l.id] = l.mean.z();
    core::ReadingPairing<int64_t> pairing(  // per light
        [&](int64_t, size_t step) -> const core::TOdometryGaussian& {
            return m_steps.at(step - 1).motion;
        });
    std::vector<core::TReadingPair> pairs;
    for (size_t k = 1; k < steps.size(); k++)
        for (const auto& c : steps[k]->state.correspondences) {
            const auto height = heightOf.find(c.landmark_id);
            if (height == heightOf.end()) continue;  // a light the map no longer has
            const auto point =
                pointOnPlane(model, m_steps[k - 1].z.at(c.measurement), height->second);
            if (!point) continue;
            if (auto pair = pairing.add(c.landmark_id, k, point->first, point->second))
                pairs.push_back(*pair);
        }
    if (pairs.empty()) return std::nullopt;
    // the points' scale is that of the lights' heights in the map, not the camera's
    return core::TSensorPoseCorrection::estimate(pairs, {}, 3, false);
}

}  // namespace mrpt_vslam::omni_fastslam
