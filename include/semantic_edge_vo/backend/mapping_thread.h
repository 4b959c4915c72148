#pragma once
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "semantic_edge_vo/backend/mapper.h"

namespace semantic_edge_vo {

/// Runs a Mapper on its own thread (parallel mapping): tracking posts the frames it trusted and
/// collects what mapping made of them before tracking the next frame (a new keyframe twice: as
/// provisional before its window runs, then settled); it never waits, except for waitUntilIdle()
/// (a new map) and the destructor (the request being mapped is finished).
class MappingThread {
 public:
  /// @param[in] mapper used from the thread only, until waitUntilIdle() returns; must outlive this object
  MappingThread(Mapper* mapper, std::size_t queue_size);
  ~MappingThread();
  MappingThread(const MappingThread&) = delete;
  MappingThread& operator=(const MappingThread&) = delete;

  /// Queues a request; when the queue is full its oldest request is dropped.
  void post(MappingRequest request);
  /// The outcomes of the requests mapped since the last call, in order. Throws std::runtime_error
  /// with what a request failed with (it was dropped; mapping goes on).
  std::vector<MappingOutcome> takeOutcomes();
  /// Waits until the queue is empty and no request is being mapped (the caller may then use the mapper).
  void waitUntilIdle();
  /// Waits until mapping has an outcome for this frame or a later one (a new keyframe's provisional
  /// outcome counts), or has gone idle (the request was dropped).
  void waitForFrame(int frame_index);
  /// Requests dropped from a full queue so far.
  int dropped() const;

 private:
  void run();

  Mapper* mapper_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_, mapped_;
  std::deque<MappingRequest> queue_;
  std::vector<MappingOutcome> outcomes_;
  std::string error_;
  bool busy_ = false, stop_ = false;
  int dropped_ = 0;
  int mapped_up_to_ = -1;  ///< the newest frame with an outcome
  std::thread thread_;  ///< started once the rest is constructed
};

}  // namespace semantic_edge_vo
