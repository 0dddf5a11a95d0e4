#include <mrpt_vslam/core/TextColumns.h>
#include <mrpt_vslam/core/UsageError.h>
#include <mrpt_vslam/sim/ConfigReading.h>
#include <mrpt_vslam/sim/OfficeWorld.h>
#include <mrpt_vslam/sim/RandomStreams.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mrpt_vslam::sim {

core::LandmarkFile TOfficeModel::cornerLandmarks() const
{
    core::LandmarkFile file;
    for (const TCornerLandmark& c : corners) {
        core::TLandmark lm;
        lm.id = c.id;
        lm.position = {c.position.x(), c.position.y(), c.position.z()};
        file.landmarks.push_back(lm);
    }
    return file;
}

namespace {

using Vec2 = Eigen::Vector2d;

/// Depth of the strip in front of a face that must be free for the face to be seen [m].
constexpr double kFrontProbe = 0.15;
/// Spacing of the probes along a face [m].
constexpr double kProbeStep = 0.05;

Vec2 vec(const mrpt::math::TPoint2D& p) { return {p.x, p.y}; }

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
    const Vec2 ab = b - a;
    const double u = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (a + u * ab - p).norm();
}

bool insidePolygon(const Vec2& p, const std::vector<mrpt::math::TPoint2D>& poly)
{
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        if ((poly[i].y > p.y()) != (poly[j].y > p.y()) &&
            p.x() <
                (poly[j].x - poly[i].x) * (p.y() - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
            inside = !inside;
    }
    return inside;
}

bool insideBox(const Vec2& p, const TBox& b)
{
    return p.x() > b.x_min && p.x() < b.x_max && p.y() > b.y_min && p.y() < b.y_max;
}

double distanceToBox(const Vec2& p, const TBox& b)
{
    const double dx = std::max({b.x_min - p.x(), 0.0, p.x() - b.x_max});
    const double dy = std::max({b.y_min - p.y(), 0.0, p.y() - b.y_max});
    if (dx > 0 || dy > 0) return std::hypot(dx, dy);
    return -std::min({p.x() - b.x_min, b.x_max - p.x(), p.y() - b.y_min, b.y_max - p.y()});
}

std::vector<std::pair<Vec2, Vec2>> boxEdges(const TBox& b)
{
    const Vec2 c00(b.x_min, b.y_min), c10(b.x_max, b.y_min), c11(b.x_max, b.y_max),
        c01(b.x_min, b.y_max);
    return {{c00, c10}, {c10, c11}, {c11, c01}, {c01, c00}};
}

/// λ ≥ 0 where the ray p + λ·d crosses segment [a, b], or +inf.
double raySegment(const Vec2& p, const Vec2& d, const Vec2& a, const Vec2& b)
{
    const Vec2 e = b - a;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (std::abs(den) < 1e-12) return std::numeric_limits<double>::infinity();
    const Vec2 ap = a - p;
    const double lambda = (ap.x() * e.y() - ap.y() * e.x()) / den;
    const double u = (ap.x() * d.y() - ap.y() * d.x()) / den;
    return lambda >= 0 && u >= 0 && u <= 1 ? lambda : std::numeric_limits<double>::infinity();
}

/** A vertical face from floor point a to b, seen from the side of `normal`, `height` tall. */
struct TVerticalFace {
    Vec2 a, b, normal;
    double height = 0;
    int own_box = -1;  ///< box the face belongs to, −1 for a room wall

    Vec2 axisS() const { return {-normal.y(), normal.x()}; }  // ẑ × normal
    Vec2 originXY() const { return (b - a).dot(axisS()) > 0 ? a : b; }
    double width() const { return (b - a).norm(); }
};

/// Appends the boxes of `key`: groups of "x_min y_min x_max y_max height".
void readBoxes(const mrpt::config::CConfigFileBase& cfg, const std::string& s,
               const std::string& key, TSurfaceKind kind, std::vector<TBox>& boxes)
{
    const std::vector<double> v = core::readNumberList(cfg, s, key, {});
    checkConfig(v.size() % 5 == 0, s, key, "groups of x_min y_min x_max y_max height");
    for (size_t i = 0; i < v.size(); i += 5) {
        TBox b{v[i], v[i + 1], v[i + 2], v[i + 3], v[i + 4], kind};
        checkConfig(b.x_min < b.x_max && b.y_min < b.y_max && b.height > 0, s, key,
                    "boxes with x_min < x_max, y_min < y_max, height > 0 (box " +
                        std::to_string(i / 5 + 1) + ")");
        boxes.push_back(b);
    }
}

}  // namespace

double OfficeWorld::clearance(double x, double y) const
{
    const Vec2 p(x, y);
    double d = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < room.size(); i++)
        d = std::min(d, distanceToSegment(p, vec(room[i]), vec(room[(i + 1) % room.size()])));
    if (!insidePolygon(p, room)) return -d;
    for (const TBox& b : boxes) d = std::min(d, distanceToBox(p, b));
    return d;
}

double OfficeWorld::distanceAhead(double x, double y, double heading, double eye_height) const
{
    const Vec2 p(x, y), d(std::cos(heading), std::sin(heading));
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < room.size(); i++)
        best = std::min(best, raySegment(p, d, vec(room[i]), vec(room[(i + 1) % room.size()])));
    for (const TBox& b : boxes)
        if (b.height > eye_height)
            for (const auto& [a, e] : boxEdges(b)) best = std::min(best, raySegment(p, d, a, e));
    return best;
}

TOfficeModel OfficeWorld::build(const TexturePainter& painter) const
{
    TOfficeModel model;
    const auto add_face = [&](const TFaceRequest& request, const Eigen::Vector3d& origin,
                              const Eigen::Vector3d& axis_s, const Eigen::Vector3d& axis_t) {
        const size_t index = model.scene.rectangles.size();
        mrpt::random::CRandomGenerator rng(deriveStreamSeed(texture_seed, RandomStream::Textures,
                                                            static_cast<uint32_t>(index + 1)));
        const TPaintedTexture tex = painter.paint(request, rng);
        model.scene.rectangles.emplace_back(origin, axis_s, axis_t, request.width, request.height,
                                            tex.image, tex.pixels_per_metre);
        const TexturedRectangle& rect = model.scene.rectangles.back();
        for (const Eigen::Vector2d& st : tex.corners)
            model.corners.push_back(
                {static_cast<int>(model.corners.size()) + 1, rect.pointAt(st.x(), st.y()), index});
    };

    const auto add_vertical = [&](const TVerticalFace& face, TSurfaceKind kind) {
        TFaceRequest request;
        request.kind = kind;
        request.width = face.width();
        request.height = face.height;
        const Vec2 origin = face.originXY(), axis_s = face.axisS();

        // Probe the strip in front of the face: what stands there hides the face up to its top.
        const int probes = std::max(1, static_cast<int>(request.width / kProbeStep));
        const double step = request.width / probes;
        int hidden = 0;
        for (int i = 0; i < probes; i++) {
            const Vec2 q = origin + (i + 0.5) * step * axis_s + kFrontProbe * face.normal;
            double top = insidePolygon(q, room) ? 0.0 : wall_height;
            for (size_t k = 0; k < boxes.size(); k++)
                if (static_cast<int>(k) != face.own_box && insideBox(q, boxes[k]))
                    top = std::max(top, boxes[k].height);
            if (top <= 0) continue;
            hidden++;
            std::vector<TWallSpan>& spans = request.keep_clear;
            if (!spans.empty() && spans.back().s1 >= i * step - 1e-9) {
                spans.back().s1 = (i + 1) * step;
                spans.back().top = std::max(spans.back().top, top);
            } else {
                spans.push_back({i * step, (i + 1) * step, top});
            }
        }
        const double min_width = kind == TSurfaceKind::Desk ? 0.8 : 0.4;
        if (kind != TSurfaceKind::Wall && (2 * hidden > probes || request.width < min_width))
            request.kind = TSurfaceKind::Panel;
        if (face.own_box < 0)
            for (const TDoor& door : doors) {
                if (distanceToSegment({door.x, door.y}, face.a, face.b) > 0.02) continue;
                const double s = (Vec2(door.x, door.y) - origin).dot(axis_s);
                request.doors.push_back({s - door.width / 2, s + door.width / 2, door_height});
            }
        add_face(request, Eigen::Vector3d(origin.x(), origin.y(), face.height),
                 Eigen::Vector3d(axis_s.x(), axis_s.y(), 0), -Eigen::Vector3d::UnitZ());
    };

    for (size_t i = 0; i < room.size(); i++) {
        const Vec2 a = vec(room[i]), b = vec(room[(i + 1) % room.size()]);
        const Vec2 d = (b - a).normalized();
        add_vertical({a, b, Vec2(-d.y(), d.x()), wall_height, -1}, TSurfaceKind::Wall);
    }
    for (size_t k = 0; k < boxes.size(); k++) {
        const TBox& box = boxes[k];
        const Vec2 normals[4] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
        const auto edges = boxEdges(box);
        for (size_t e = 0; e < 4; e++)
            add_vertical(
                {edges[e].first, edges[e].second, normals[e], box.height, static_cast<int>(k)},
                box.front);
        const TFaceRequest top{
            TSurfaceKind::Panel, box.y_max - box.y_min, box.x_max - box.x_min, {}, {}};
        add_face(top, Eigen::Vector3d(box.x_min, box.y_min, box.height), Eigen::Vector3d::UnitY(),
                 Eigen::Vector3d::UnitX());
    }

    double x_min = 1e18, x_max = -1e18, y_min = 1e18, y_max = -1e18;
    for (const auto& p : room) {
        x_min = std::min(x_min, p.x), x_max = std::max(x_max, p.x);
        y_min = std::min(y_min, p.y), y_max = std::max(y_max, p.y);
    }
    const TFaceRequest floor{TSurfaceKind::Floor, y_max - y_min, x_max - x_min, {}, {}};
    add_face(floor, Eigen::Vector3d(x_min, y_min, 0), Eigen::Vector3d::UnitY(),
             Eigen::Vector3d::UnitX());
    const TFaceRequest ceiling{TSurfaceKind::Ceiling, x_max - x_min, y_max - y_min, {}, {}};
    add_face(ceiling, Eigen::Vector3d(x_min, y_min, wall_height), Eigen::Vector3d::UnitX(),
             Eigen::Vector3d::UnitY());
    return model;
}

void OfficeWorld::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s)
{
    std::vector<double> xy;
    for (const auto& p : room) xy.insert(xy.end(), {p.x, p.y});
    xy = core::readNumberList(cfg, s, "room", xy);
    checkConfig(xy.size() % 2 == 0 && xy.size() >= 6, s, "room",
                "a polygon of at least 3 points x1 y1 x2 y2 ...");
    room.clear();
    for (size_t i = 0; i < xy.size(); i += 2) room.emplace_back(xy[i], xy[i + 1]);
    double area2 = 0;
    for (size_t i = 0; i < room.size(); i++) {
        const auto& a = room[i];
        const auto& b = room[(i + 1) % room.size()];
        area2 += a.x * b.y - b.x * a.y;
        checkConfig(std::hypot(b.x - a.x, b.y - a.y) > 0.1, s, "room",
                    "a polygon with edges longer than 0.1 m");
    }
    checkConfig(std::abs(area2) > 1e-6, s, "room", "a polygon with a non-zero area");
    if (area2 < 0) std::reverse(room.begin(), room.end());

    MRPT_LOAD_CONFIG_VAR(wall_height, double, cfg, s);
    MRPT_LOAD_CONFIG_VAR(door_height, double, cfg, s);
    checkConfig(wall_height > 0.5, s, "wall_height", "> 0.5");
    checkConfig(door_height > 0.5 && door_height < wall_height - 0.1, s, "door_height",
                "in (0.5, wall_height - 0.1)");
    texture_seed = cfg.read_uint64_t(s, "texture_seed", texture_seed);

    std::vector<double> dv;
    for (const TDoor& d : doors) dv.insert(dv.end(), {d.x, d.y, d.width});
    dv = core::readNumberList(cfg, s, "doors", dv);
    checkConfig(dv.size() % 3 == 0, s, "doors", "groups of x y width");
    doors.clear();
    for (size_t i = 0; i < dv.size(); i += 3) {
        const TDoor d{dv[i], dv[i + 1], dv[i + 2]};
        const std::string which = "door " + std::to_string(i / 3 + 1);
        bool on_wall = false;
        for (size_t k = 0; k < room.size(); k++) {
            const Vec2 a = vec(room[k]), b = vec(room[(k + 1) % room.size()]);
            if (distanceToSegment({d.x, d.y}, a, b) > 0.02) continue;
            const double u = (Vec2(d.x, d.y) - a).dot((b - a).normalized());
            on_wall =
                on_wall || (u - d.width / 2 >= 0.1 && u + d.width / 2 <= (b - a).norm() - 0.1);
        }
        checkConfig(d.width > 0.3 && on_wall, s, "doors",
                    "on a room wall, wider than 0.3 m and 0.1 m from its ends (" + which + ")");
        doors.push_back(d);
    }

    boxes.clear();
    readBoxes(cfg, s, "partitions", TSurfaceKind::Wall, boxes);
    readBoxes(cfg, s, "cabinets", TSurfaceKind::Cabinet, boxes);
    readBoxes(cfg, s, "shelves", TSurfaceKind::Shelf, boxes);
    readBoxes(cfg, s, "desks", TSurfaceKind::Desk, boxes);
    for (size_t i = 0; i < boxes.size(); i++) {
        const TBox& b = boxes[i];
        const std::string which =
            "box " + std::to_string(i + 1) + " of partitions, cabinets, " + "shelves, desks";
        checkConfig(b.height <= wall_height, s, "partitions/cabinets/shelves/desks",
                    "no taller than wall_height (" + which + ")");
        for (const Vec2& c : {Vec2(b.x_min, b.y_min), Vec2(b.x_max, b.y_min),
                              Vec2(b.x_max, b.y_max), Vec2(b.x_min, b.y_max)}) {
            double d = std::numeric_limits<double>::infinity();
            for (size_t k = 0; k < room.size(); k++)
                d = std::min(d,
                             distanceToSegment(c, vec(room[k]), vec(room[(k + 1) % room.size()])));
            checkConfig(insidePolygon(c, room) && d >= 0.01, s, "partitions/cabinets/shelves/desks",
                        "inside the room, at least 0.01 m from the walls (" + which + ")");
        }
        for (size_t j = 0; j < i; j++) {
            const TBox& o = boxes[j];
            const bool overlap = b.x_min < o.x_max - 1e-9 && o.x_min < b.x_max - 1e-9 &&
                                 b.y_min < o.y_max - 1e-9 && o.y_min < b.y_max - 1e-9;
            checkConfig(!overlap, s, "partitions/cabinets/shelves/desks",
                        "boxes that do not overlap (" + which + " overlaps box " +
                            std::to_string(j + 1) + ")");
        }
    }
}

}  // namespace mrpt_vslam::sim
