#include <mrpt_vslam/sim/OfficeTopView.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace mrpt_vslam::sim {

mrpt::img::CImage drawOfficeTopView(const OfficeWorld& world, const TOfficeModel& model,
                                    const std::vector<std::vector<mrpt::math::TPose2D>>& paths,
                                    double pixels_per_metre)
{
    double x_min = 1e18, x_max = -1e18, y_min = 1e18, y_max = -1e18;
    for (const auto& p : world.room) {
        x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x);
        y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
    }
    constexpr int kMargin = 12;
    const double ppm = pixels_per_metre;
    cv::Mat img(static_cast<int>(std::ceil((y_max - y_min) * ppm)) + 2 * kMargin,
                static_cast<int>(std::ceil((x_max - x_min) * ppm)) + 2 * kMargin, CV_8UC3,
                cv::Scalar(255, 255, 255));
    const auto px = [&](double x, double y) {
        return cv::Point(static_cast<int>(std::lround(kMargin + (x - x_min) * ppm)),
                         static_cast<int>(std::lround(kMargin + (y_max - y) * ppm)));
    };

    for (const TBox& b : world.boxes) {
        const cv::Scalar fill =
            b.front == TSurfaceKind::Wall ? cv::Scalar(110, 110, 110) : cv::Scalar(190, 190, 190);
        cv::rectangle(img, px(b.x_min, b.y_max), px(b.x_max, b.y_min), fill, cv::FILLED);
        cv::rectangle(img, px(b.x_min, b.y_max), px(b.x_max, b.y_min), cv::Scalar(60, 60, 60), 1);
    }
    for (size_t i = 0; i < world.room.size(); i++) {
        const auto& a = world.room[i];
        const auto& b = world.room[(i + 1) % world.room.size()];
        cv::line(img, px(a.x, a.y), px(b.x, b.y), cv::Scalar(0, 0, 0), 3);
    }
    for (const TDoor& d : world.doors) {
        // Along the wall the door is on: the room edge nearest to its centre.
        double best = 1e18;
        Eigen::Vector2d dir(1, 0);
        for (size_t i = 0; i < world.room.size(); i++) {
            const Eigen::Vector2d a(world.room[i].x, world.room[i].y);
            const auto& q = world.room[(i + 1) % world.room.size()];
            const Eigen::Vector2d e = Eigen::Vector2d(q.x, q.y) - a;
            const double u =
                std::clamp((Eigen::Vector2d(d.x, d.y) - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
            const double dist = (a + u * e - Eigen::Vector2d(d.x, d.y)).norm();
            if (dist < best) best = dist, dir = e.normalized();
        }
        const Eigen::Vector2d p0 = Eigen::Vector2d(d.x, d.y) - 0.5 * d.width * dir;
        const Eigen::Vector2d p1 = Eigen::Vector2d(d.x, d.y) + 0.5 * d.width * dir;
        cv::line(img, px(p0.x(), p0.y()), px(p1.x(), p1.y()), cv::Scalar(120, 180, 220), 3);
    }
    for (const TCornerLandmark& c : model.corners)
        cv::circle(img, px(c.position.x(), c.position.y()), 1, cv::Scalar(0, 140, 255), cv::FILLED);

    const cv::Scalar colours[] = {cv::Scalar(40, 40, 220), cv::Scalar(220, 90, 30),
                                  cv::Scalar(40, 160, 40), cv::Scalar(160, 40, 160)};
    for (size_t r = 0; r < paths.size(); r++) {
        const cv::Scalar colour = colours[r % 4];
        const auto& path = paths[r];
        for (size_t k = 1; k < path.size(); k++)
            cv::line(img, px(path[k - 1].x, path[k - 1].y), px(path[k].x, path[k].y), colour, 2,
                     cv::LINE_AA);
        if (path.empty()) continue;
        const auto& s = path.front();
        cv::circle(img, px(s.x, s.y), 5, colour, cv::FILLED, cv::LINE_AA);
        cv::arrowedLine(img, px(s.x, s.y),
                        px(s.x + 0.6 * std::cos(s.phi), s.y + 0.6 * std::sin(s.phi)), colour, 2,
                        cv::LINE_AA, 0, 0.4);
        cv::putText(img, "R" + std::to_string(r + 1), px(s.x - 0.3, s.y - 0.45),
                    cv::FONT_HERSHEY_SIMPLEX, 0.45, colour, 1, cv::LINE_AA);
    }
    return mrpt::img::CImage(img, mrpt::img::DEEP_COPY);
}

}  // namespace mrpt_vslam::sim
