#include <mrpt_vslam/multirobot/StereoFrontEnd.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <tuple>

namespace mrpt_vslam::multirobot {

// Step 5: continue the tracks of the previous frame (m_points) or start new ones.
void StereoFrontEnd::track(std::vector<TPoint>& current)
{
    const std::vector<TPoint>& previous = m_points;
    const double radius2 = m_options.track_search_radius * m_options.track_search_radius;

    struct TClaim {
        size_t previous = 0;
        double distance = 0;
    };
    std::vector<std::optional<TClaim>> claims(current.size());
    std::vector<core::USurfDescriptor::TDescriptor> candidates;
    std::vector<size_t> candidate_index;
    for (size_t i = 0; i < current.size(); i++) {
        candidates.clear();
        candidate_index.clear();
        for (size_t j = 0; j < previous.size(); j++) {
            const double dr = current[i].pixel.row - previous[j].pixel.row;
            const double dc = current[i].pixel.col - previous[j].pixel.col;
            if (dr * dr + dc * dc > radius2) continue;
            candidates.push_back(previous[j].descriptor);
            candidate_index.push_back(j);
        }
        const auto m = core::USurfDescriptor::bestMatch(current[i].descriptor, candidates,
                                                        m_options.track_ratio);
        if (m && m->distance <= m_options.track_max_descriptor_distance)
            claims[i] = TClaim{candidate_index[m->index], m->distance};
    }

    // One current point per previous point: the nearest descriptor keeps it.
    constexpr size_t kNone = std::numeric_limits<size_t>::max();
    std::vector<size_t> owner(previous.size(), kNone);
    for (size_t i = 0; i < current.size(); i++) {
        if (!claims[i]) continue;
        size_t& o = owner[claims[i]->previous];
        if (o == kNone || claims[i]->distance < claims[o]->distance) o = i;
    }

    m_stats.tracked = 0;
    for (size_t i = 0; i < current.size(); i++) {
        if (claims[i] && owner[claims[i]->previous] == i) {
            const TPoint& p = previous[claims[i]->previous];
            current[i].track_id = p.track_id;
            current[i].track_length = p.track_length + 1;
            m_stats.tracked++;
        } else {
            current[i].track_id = m_next_track_id++;
            current[i].track_length = 1;
        }
    }
}

// Step 6: tracks of at least min_track_length frames; longest, then nearest, then oldest first.
std::vector<size_t> StereoFrontEnd::selectEmitted()
{
    std::vector<size_t> eligible;
    for (size_t i = 0; i < m_points.size(); i++)
        if (m_points[i].track_length >= static_cast<uint32_t>(m_options.min_track_length))
            eligible.push_back(i);
    m_stats.eligible = eligible.size();
    const auto key = [&](size_t i) {
        const TPoint& p = m_points[i];
        return std::make_tuple(-static_cast<int64_t>(p.track_length), p.point.z, p.track_id);
    };
    std::sort(eligible.begin(), eligible.end(),
              [&](size_t a, size_t b) { return key(a) < key(b); });
    const auto cap = static_cast<size_t>(m_options.max_landmarks_per_frame);
    if (cap > 0 && eligible.size() > cap) eligible.resize(cap);
    return eligible;
}

}  // namespace mrpt_vslam::multirobot
