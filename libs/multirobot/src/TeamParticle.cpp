#include <mrpt_vslam/multirobot/TeamParticle.h>

namespace mrpt_vslam::multirobot {

TTeamPathNode::~TTeamPathNode()
{
    std::shared_ptr<const TTeamPathNode> p = std::move(previous);
    while (p && p.use_count() == 1) {
        std::shared_ptr<const TTeamPathNode> next = std::move(p->previous);
        p = std::move(next);  // the old node dies with an empty `previous`: no recursion
    }
}

}  // namespace mrpt_vslam::multirobot
