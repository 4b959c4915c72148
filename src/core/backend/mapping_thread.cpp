#include "semantic_edge_vo/backend/mapping_thread.h"

#include <algorithm>

namespace semantic_edge_vo {

MappingThread::MappingThread(const OdometryOptions& options, const PinholeCamera& camera, Delivery deliver)
    : mapper_(options, camera), capacity_(static_cast<std::size_t>(std::max(1, options.mapping_queue))), deliver_(std::move(deliver)) {
  mapper_.onProvisionalKeyframe([this](MappingOutcome outcome) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      handOver(std::move(outcome));
    }
    mapped_.notify_all();
  });
  mapper_.stopWindowWhen([this] { return trackingWaitsBehind(); });
  thread_ = std::thread([this] { run(); });
}

MappingThread::~MappingThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  wake_.notify_all();
  thread_.join();
}

void MappingThread::handOver(MappingOutcome outcome) {
  mapped_up_to_ = std::max(mapped_up_to_, outcome.frame_index);
  if (deliver_) deliver_(std::move(outcome));
  else outcomes_.push_back(std::move(outcome));
}

void MappingThread::post(MappingRequest request) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.size() >= capacity_) {
      MappingOutcome dropped;
      dropped.frame_index = queue_.front().frame->index;
      dropped.dropped = true;
      queue_.pop_front();
      handOver(std::move(dropped));
    }
    queue_.push_back(std::move(request));
  }
  wake_.notify_one();
}

bool MappingThread::trackingWaitsBehind() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::any_of(queue_.begin(), queue_.end(),
                     [](const MappingRequest& request) { return request.tracking_waits && request.tracking_waits->load(); });
}

std::vector<MappingOutcome> MappingThread::takeOutcomes() {
  std::vector<MappingOutcome> outcomes;
  std::lock_guard<std::mutex> lock(mutex_);
  outcomes.swap(outcomes_);
  return outcomes;
}

void MappingThread::waitForFrame(int frame_index) {
  std::unique_lock<std::mutex> lock(mutex_);
  mapped_.wait(lock, [this, frame_index] { return mapped_up_to_ >= frame_index || (queue_.empty() && !busy_); });
}

void MappingThread::waitUntilIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait(lock, [this] { return queue_.empty() && !busy_; });
}

void MappingThread::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    MappingRequest request = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    lock.unlock();
    MappingOutcome outcome;
    try {
      outcome = mapper_.map(request);
    } catch (const std::exception& e) {
      outcome = MappingOutcome();
      outcome.frame_index = request.frame->index;
      outcome.dropped = true;
      outcome.error = e.what();
    }
    lock.lock();
    busy_ = false;
    handOver(std::move(outcome));
    mapped_.notify_all();
    if (queue_.empty()) idle_.notify_all();
  }
}

}  // namespace semantic_edge_vo
