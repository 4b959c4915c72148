#pragma once
#include <ros/time.h>

namespace semantic_edge_vo {

/// The order of a stream's stamps. Each stamp must come after the last accepted one; a stamp more
/// than `restart_jump` before it means the stream started over (a bag played again or looped, a
/// camera driver restarted, simulated time reset), and whoever consumes the stream starts over too.
/// A step back no larger than that (a reordered or repeated frame) is refused.
class StampOrder {
 public:
  enum class Verdict {
    kNext,           ///< after the last accepted stamp (or the first): accepted
    kNotIncreasing,  ///< at or shortly before it: refused, the last accepted stamp stays
    kRestart,        ///< more than restart_jump before it: accepted, the stream started over
  };

  /// @param restart_jump s; 0: any step back is a restart (a consumer of an already ordered stream)
  explicit StampOrder(double restart_jump) : restart_jump_(restart_jump) {}

  Verdict accept(const ros::Time& stamp);
  /// The last accepted stamp (zero before the first).
  const ros::Time& last() const { return last_; }

 private:
  double restart_jump_;
  ros::Time last_;
  bool started_ = false;
};

}  // namespace semantic_edge_vo
