#pragma once
#include <vector>

#include "semantic_edge_vo/backend/mapper.h"

namespace semantic_edge_vo {

/// Where an Odometry's mapping runs: a Mapper on a thread of its own in this object
/// (MappingThread), or in another component that answers the same requests (the Mapping nodelet,
/// reached by the Tracking nodelet's link). Every request posted gets one outcome, in order (one
/// dropped or failed too); a new keyframe gets a provisional outcome before its settled one.
class MappingLink {
 public:
  virtual ~MappingLink() = default;
  /// Hands a request over; when mapping's queue is full its oldest request is dropped.
  virtual void post(MappingRequest request) = 0;
  /// The outcomes since the last call, in order.
  virtual std::vector<MappingOutcome> takeOutcomes() = 0;
  /// Waits until there is an outcome for this frame or a later one (a provisional one counts).
  /// Throws std::runtime_error when mapping does not answer (another component).
  virtual void waitForFrame(int frame_index) = 0;
  /// Waits until every request posted has its outcome; throws as waitForFrame().
  virtual void waitUntilIdle() = 0;
};

}  // namespace semantic_edge_vo
