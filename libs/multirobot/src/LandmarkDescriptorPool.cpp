#include <mrpt_vslam/multirobot/LandmarkDescriptorPool.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::multirobot {

namespace {
/// Cells per axis that the grid keys tell apart (21 bits per axis; farther cells share keys).
constexpr int64_t kKeySpan = int64_t{1} << 21;
}  // namespace

LandmarkDescriptorPool::LandmarkDescriptorPool(double cell_size) : m_cell(cell_size)
{
    if (!(cell_size > 0) || !std::isfinite(cell_size))
        throw std::invalid_argument("landmark pool: cell size must be finite and > 0");
}

int64_t LandmarkDescriptorPool::cellIndex(double v) const
{
    // clamped so that the cast is defined for any finite coordinate
    constexpr double kLimit = 1e15;
    return static_cast<int64_t>(std::clamp(std::floor(v / m_cell), -kLimit, kLimit));
}

int64_t LandmarkDescriptorPool::cellKey(int64_t ix, int64_t iy, int64_t iz) const
{
    // ±1e6 cells per axis, far beyond any indoor map
    constexpr int64_t kOffset = kKeySpan / 2, kMask = kKeySpan - 1;
    return ((ix + kOffset) & kMask) | (((iy + kOffset) & kMask) << 21) |
           (((iz + kOffset) & kMask) << 42);
}

void LandmarkDescriptorPool::index(uint32_t id)
{
    const Eigen::Vector3d& p = m_positions[id];
    m_grid[cellKey(cellIndex(p.x()), cellIndex(p.y()), cellIndex(p.z()))].push_back(id);
}

std::optional<uint32_t> LandmarkDescriptorPool::landmarkOfIdentity(int64_t identity) const
{
    const auto it = m_identities.find(identity);
    if (it == m_identities.end()) return std::nullopt;
    return it->second;
}

std::vector<std::pair<int64_t, uint32_t>> LandmarkDescriptorPool::identities() const
{
    std::vector<std::pair<int64_t, uint32_t>> out(m_identities.begin(), m_identities.end());
    std::sort(out.begin(), out.end());
    return out;
}

uint32_t LandmarkDescriptorPool::add(const TDescriptor& descriptor, const Eigen::Vector3d& position)
{
    const auto id = static_cast<uint32_t>(m_descriptors.size());
    addWithId(id, descriptor, position);
    return id;
}

void LandmarkDescriptorPool::addWithId(uint32_t id, const TDescriptor& descriptor,
                                       const Eigen::Vector3d& position)
{
    if (!position.allFinite())
        throw std::invalid_argument("landmark pool: non-finite landmark position");
    if (contains(id))
        throw std::invalid_argument("landmark pool: duplicated landmark id " + std::to_string(id));
    if (id >= m_descriptors.size()) {
        m_descriptors.resize(id + 1);
        m_positions.resize(id + 1, Eigen::Vector3d::Zero());
        m_used.resize(id + 1, false);
    }
    m_descriptors[id] = descriptor;
    m_positions[id] = position;
    m_used[id] = true;
    index(id);
}

size_t LandmarkDescriptorPool::forgetAllBut(const std::vector<uint32_t>& held)
{
    const auto isHeld = [&](uint32_t id) {
        return id / 32 < held.size() && (held[id / 32] >> (id % 32) & 1u);
    };
    std::vector<bool> identity(m_used.size(), false);
    for (const auto& [key, id] : m_identities) identity[id] = true;
    size_t searchable = 0;
    for (auto it = m_grid.begin(); it != m_grid.end();) {
        auto& ids = it->second;
        ids.erase(std::remove_if(ids.begin(), ids.end(),
                                 [&](uint32_t id) { return !isHeld(id) && !identity[id]; }),
                  ids.end());
        searchable += ids.size();
        it = ids.empty() ? m_grid.erase(it) : std::next(it);
    }
    return searchable;
}

float LandmarkDescriptorPool::squaredDistance(const TDescriptor& a, const TDescriptor& b)
{
    float e = 0;
    for (size_t i = 0; i < a.size(); i++) {
        const float d = a[i] - b[i];
        e += d * d;
    }
    return e;
}

void LandmarkDescriptorPool::findCandidates(const Eigen::Vector3d& center, double radius,
                                            const TDescriptor& query, double max_E,
                                            std::vector<TLandmarkCandidate>& out) const
{
    if (!center.allFinite() || !(radius >= 0)) return;
    const size_t first = out.size();
    const double r2 = radius * radius;
    const auto consider = [&](const std::vector<uint32_t>& ids) {
        for (const uint32_t id : ids) {
            if ((m_positions[id] - center).squaredNorm() > r2) continue;
            const float E = squaredDistance(query, m_descriptors[id]);
            if (E <= max_E) out.push_back({id, E});
        }
    };
    const Eigen::Vector3d lo = center.array() - radius, hi = center.array() + radius;
    const int64_t x0 = cellIndex(lo.x()), x1 = cellIndex(hi.x()), y0 = cellIndex(lo.y()),
                  y1 = cellIndex(hi.y()), z0 = cellIndex(lo.z()), z1 = cellIndex(hi.z());
    // a query box of more cells than the grid holds (a radius far larger than the cells) visits
    // the occupied cells instead; so does one wider than the keys' span, where keys would repeat
    const double boxCells = (static_cast<double>(x1 - x0) + 1) *
                            (static_cast<double>(y1 - y0) + 1) * (static_cast<double>(z1 - z0) + 1);
    if (boxCells > static_cast<double>(m_grid.size()) || x1 - x0 >= kKeySpan ||
        y1 - y0 >= kKeySpan || z1 - z0 >= kKeySpan) {
        for (const auto& [key, ids] : m_grid) consider(ids);
    } else {
        for (int64_t ix = x0; ix <= x1; ix++)
            for (int64_t iy = y0; iy <= y1; iy++)
                for (int64_t iz = z0; iz <= z1; iz++) {
                    const auto it = m_grid.find(cellKey(ix, iy, iz));
                    if (it != m_grid.end()) consider(it->second);
                }
    }
    std::sort(
        out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
        [](const auto& a, const auto& b) { return a.E < b.E || (a.E == b.E && a.id < b.id); });
}

}  // namespace mrpt_vslam::multirobot
