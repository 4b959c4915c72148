#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "semantic_edge_vo/backend/mapper.h"
#include "semantic_edge_vo/backend/mapping_link.h"

namespace semantic_edge_vo {

/// A Mapper on its own thread behind a bounded queue. Its outcomes are taken (takeOutcomes) or,
/// when a delivery callback is given, handed to it on the mapping thread as they are made (the
/// Mapping nodelet publishes them). The destructor finishes the request being mapped.
class MappingThread : public MappingLink {
 public:
  using Delivery = std::function<void(MappingOutcome)>;
  /// @param[in] deliver called on the mapping thread with each outcome; empty: takeOutcomes() has them
  MappingThread(const OdometryOptions& options, const PinholeCamera& camera, Delivery deliver = nullptr);
  ~MappingThread() override;
  MappingThread(const MappingThread&) = delete;
  MappingThread& operator=(const MappingThread&) = delete;

  void post(MappingRequest request) override;
  std::vector<MappingOutcome> takeOutcomes() override;
  void waitForFrame(int frame_index) override;
  void waitUntilIdle() override;

 private:
  void run();
  /// Hands an outcome over (mutex_ held).
  void handOver(MappingOutcome outcome);
  /// Whether tracking waits for a request still queued (the window being solved should end).
  bool trackingWaitsBehind() const;

  Mapper mapper_;  ///< used by the mapping thread only
  std::size_t capacity_;
  Delivery deliver_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_, mapped_;
  std::deque<MappingRequest> queue_;
  std::vector<MappingOutcome> outcomes_;
  bool busy_ = false, stop_ = false;
  int mapped_up_to_ = -1;  ///< the newest frame with an outcome
  std::thread thread_;  ///< started once the rest is constructed
};

}  // namespace semantic_edge_vo
