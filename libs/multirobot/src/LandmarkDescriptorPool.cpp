#include <mrpt_vslam/multirobot/LandmarkDescriptorPool.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mrpt_vslam::multirobot {

LandmarkDescriptorPool::LandmarkDescriptorPool(double cell_size) : m_cell(cell_size)
{
    if (!(cell_size > 0) || !std::isfinite(cell_size))
        throw std::invalid_argument("landmark pool: cell size must be finite and > 0");
}

int64_t LandmarkDescriptorPool::cellIndex(double v) const
{
    return static_cast<int64_t>(std::floor(v / m_cell));
}

int64_t LandmarkDescriptorPool::cellKey(int64_t ix, int64_t iy, int64_t iz) const
{
    // 21 bits per axis: ±1e6 cells, far beyond any indoor map
    constexpr int64_t kOffset = 1 << 20, kMask = (1 << 21) - 1;
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
    const Eigen::Vector3d lo = center.array() - radius, hi = center.array() + radius;
    for (int64_t ix = cellIndex(lo.x()); ix <= cellIndex(hi.x()); ix++)
        for (int64_t iy = cellIndex(lo.y()); iy <= cellIndex(hi.y()); iy++)
            for (int64_t iz = cellIndex(lo.z()); iz <= cellIndex(hi.z()); iz++) {
                const auto it = m_grid.find(cellKey(ix, iy, iz));
                if (it == m_grid.end()) continue;
                for (const uint32_t id : it->second) {
                    if ((m_positions[id] - center).squaredNorm() > r2) continue;
                    const float E = squaredDistance(query, m_descriptors[id]);
                    if (E <= max_E) out.push_back({id, E});
                }
            }
    std::sort(
        out.begin() + static_cast<std::ptrdiff_t>(first), out.end(),
        [](const auto& a, const auto& b) { return a.E < b.E || (a.E == b.E && a.id < b.id); });
}

}  // namespace mrpt_vslam::multirobot
