#include <mrpt_vslam/sim/TexturedScene.h>

namespace mrpt_vslam::sim {

bool TexturedScene::isVisibleFrom(const Eigen::Vector3d& point, const Eigen::Vector3d& eye,
                                  double tolerance) const
{
    const Eigen::Vector3d d = point - eye;
    const double limit = 1.0 - tolerance / d.norm();
    for (const TexturedRectangle& r : rectangles) {
        const std::optional<double> lambda = r.intersect(eye, d);
        if (lambda && *lambda < limit) return false;
    }
    return true;
}

}  // namespace mrpt_vslam::sim
