#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace mrpt_vslam::core {

/** Compass search (a pattern search without derivatives) from `centre`: it tries the points
 *  one step away along each axis, ± in turn; a point `improves(p)` accepts (it evaluates p and
 *  returns true when p is better than every point so far, keeping it) becomes the centre. The
 *  steps halve when no point improves, or after `max_moves` moves at one step size, until the
 *  largest step is below `min_step`. The cap bounds the work where the cost is flat: a cost
 *  that falls by rounding-sized amounts along a valley (exact fits along a curve) would
 *  otherwise be followed for minutes at the smallest steps. */
template <std::size_t N, class Improves>
void compassSearch(std::array<double, N> centre, std::array<double, N> step, double min_step,
                   Improves&& improves, int max_moves = 64)
{
    int moves = 0;
    while (*std::max_element(step.begin(), step.end()) > min_step) {
        bool moved = false;
        for (std::size_t axis = 0; axis < N; axis++) {
            for (const double sign : {1.0, -1.0}) {
                auto p = centre;
                p[axis] += sign * step[axis];
                if (improves(p)) {
                    centre = p;
                    moved = true;
                }
            }
        }
        if (!moved || ++moves == max_moves) {
            for (double& s : step) s /= 2;
            moves = 0;
        }
    }
}

}  // namespace mrpt_vslam::core
