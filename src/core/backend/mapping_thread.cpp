#include "semantic_edge_vo/backend/mapping_thread.h"

#include <algorithm>
#include <stdexcept>

namespace semantic_edge_vo {

MappingThread::MappingThread(Mapper* mapper, std::size_t queue_size)
    : mapper_(mapper), capacity_(queue_size < 1 ? 1 : queue_size) {
  mapper_->onProvisionalKeyframe([this](MappingOutcome outcome) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      mapped_up_to_ = std::max(mapped_up_to_, outcome.frame_index);
      outcomes_.push_back(std::move(outcome));
    }
    mapped_.notify_all();
  });
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
  mapper_->onProvisionalKeyframe(nullptr);
}

void MappingThread::post(MappingRequest request) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (queue_.size() >= capacity_) {
      queue_.pop_front();
      ++dropped_;
    }
    queue_.push_back(std::move(request));
  }
  wake_.notify_one();
}

std::vector<MappingOutcome> MappingThread::takeOutcomes() {
  std::vector<MappingOutcome> outcomes;
  std::string error;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    outcomes.swap(outcomes_);
    error.swap(error_);
  }
  if (!error.empty()) throw std::runtime_error("mapping: " + error);
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

int MappingThread::dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
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
    std::string error;
    try {
      outcome = mapper_->map(request);
    } catch (const std::exception& e) {
      error = e.what();
    }
    lock.lock();
    busy_ = false;
    mapped_up_to_ = std::max(mapped_up_to_, request.frame->index);
    if (error.empty()) outcomes_.push_back(std::move(outcome));
    else error_ = error;
    mapped_.notify_all();
    if (queue_.empty()) idle_.notify_all();
  }
}

}  // namespace semantic_edge_vo
