#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {

StampOrder::Verdict StampOrder::accept(const ros::Time& stamp) {
  Verdict verdict = Verdict::kNext;
  if (started_ && stamp <= last_) {
    if ((last_ - stamp).toSec() <= restart_jump_) return Verdict::kNotIncreasing;
    verdict = Verdict::kRestart;
  }
  started_ = true;
  last_ = stamp;
  return verdict;
}

}  // namespace semantic_edge_vo
