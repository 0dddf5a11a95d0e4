#pragma once

#include <mrpt_vslam/core/FixedSizePool.h>

#include <memory>
#include <utility>
#include <vector>

namespace mrpt_vslam::core {

/** One step of a particle's history in a particle filter over paths (FastSLAM): the step's
 *  `State` and the node of the step before. Nodes are shared between the copies resampling
 *  makes, so a copy costs one pointer, not a path. */
template <class State>
struct TPathNode {
    double timestamp = 0;  ///< [s]
    State state;
    mutable std::shared_ptr<const TPathNode> previous;  ///< mutable: see the destructor

    /// The state is built in place from `state_args` (a step is copied once, not per hop).
    template <class... StateArgs>
    TPathNode(double t, std::shared_ptr<const TPathNode> prev, StateArgs&&... state_args)
        : timestamp(t), state{std::forward<StateArgs>(state_args)...}, previous(std::move(prev))
    {
    }
    TPathNode(const TPathNode&) = delete;
    TPathNode& operator=(const TPathNode&) = delete;

    /// Releases a chain of nodes nobody else holds iteratively (a long run would otherwise
    /// recurse once per step).
    ~TPathNode()
    {
        std::shared_ptr<const TPathNode> p = std::move(previous);
        while (p && p.use_count() == 1) {
            std::shared_ptr<const TPathNode> next = std::move(p->previous);
            p = std::move(next);  // the old node dies with an empty `previous`: no recursion
        }
    }
};

/// A node for the step after `previous`, from the pool of path nodes (resampling releases
/// them by the thousand each step); its state is `State{state_args...}`.
template <class State, class... StateArgs>
std::shared_ptr<const TPathNode<State>> newPathNode(
    double t, std::shared_ptr<const TPathNode<State>> previous, StateArgs&&... state_args)
{
    return std::allocate_shared<const TPathNode<State>>(PoolAllocator<TPathNode<State>>(), t,
                                                        std::move(previous),
                                                        std::forward<StateArgs>(state_args)...);
}

/// The nodes of the path that ends at `newest`, oldest first.
template <class State>
std::vector<const TPathNode<State>*> nodesOldestFirst(const TPathNode<State>* newest)
{
    std::vector<const TPathNode<State>*> nodes;
    for (const TPathNode<State>* n = newest; n; n = n->previous.get()) nodes.push_back(n);
    return {nodes.rbegin(), nodes.rend()};
}

}  // namespace mrpt_vslam::core
