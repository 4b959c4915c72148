#include "semantic_edge_vo/ros/nodelet_mapping_link.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include <boost/make_shared.hpp>

namespace semantic_edge_vo {

namespace {
/// A session id no other odometry of this manager, or of one started before it, has had.
std::uint64_t newSession() {
  static std::mutex mutex;
  static std::uint64_t last = 0;
  std::lock_guard<std::mutex> lock(mutex);
  const auto now = static_cast<std::uint64_t>(std::chrono::system_clock::now().time_since_epoch().count());
  last = std::max(last + 1, now);
  return last;
}
}  // namespace

NodeletMappingLink::NodeletMappingLink(const ros::NodeHandle& node, const OdometryOptions& options, const PinholeCamera& camera,
                                       std::function<ros::Time(int)> stamp_of, const std::vector<std::string>* class_names,
                                       const MessageTracer* tracer)
    : options_(std::make_shared<const OdometryOptions>(options)),
      camera_(camera),
      session_(newSession()),
      stamp_of_(std::move(stamp_of)),
      class_names_(class_names),
      tracer_(tracer) {
  ros::NodeHandle handle(node);
  publisher_ = handle.advertise<MappingRequestMessage>("mapping_request", 100);
  handle.setCallbackQueue(&queue_);
  // Deep: outcomes pile up while tracking is busy with a frame; the bound is mapping's queue.
  subscriber_ = handle.subscribe("mapping_outcome", 1000, &NodeletMappingLink::onOutcome, this);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

NodeletMappingLink::~NodeletMappingLink() {
  spinner_->stop();
  subscriber_.shutdown();
}

void NodeletMappingLink::post(MappingRequest request) {
  auto message = boost::make_shared<MappingRequestMessage>();
  message->session = session_;
  message->options = options_;
  message->camera = camera_;
  message->stamp = stamp_of_(request.frame->index);
  message->class_names = *class_names_;
  message->request = std::move(request);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++posted_;
  }
  publisher_.publish(boost::shared_ptr<const MappingRequestMessage>(message));
  tracer_->published(publisher_, message.get(), message->stamp);
}

void NodeletMappingLink::onOutcome(const boost::shared_ptr<const MappingOutcomeMessage>& message) {
  tracer_->received(subscriber_.getTopic(), message.get(), message->stamp);
  if (message->session != session_) return;  // another odometry's (this one's predecessor)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    settled_ += !message->outcome.provisional;
    mapped_up_to_ = std::max(mapped_up_to_, message->outcome.frame_index);
    outcomes_.push_back(message->outcome);
  }
  answered_.notify_all();
}

std::vector<MappingOutcome> NodeletMappingLink::takeOutcomes() {
  std::vector<MappingOutcome> outcomes;
  std::lock_guard<std::mutex> lock(mutex_);
  outcomes.swap(outcomes_);
  return outcomes;
}

void NodeletMappingLink::waitForFrame(int frame_index) {
  std::unique_lock<std::mutex> lock(mutex_);
  waitFor(lock, [&] { return mapped_up_to_ >= frame_index || settled_ >= posted_; }, "frame " + std::to_string(frame_index));
}

void NodeletMappingLink::waitUntilIdle() {
  std::unique_lock<std::mutex> lock(mutex_);
  waitFor(lock, [&] { return settled_ >= posted_; }, std::to_string(posted_ - settled_) + " frames");
}

void NodeletMappingLink::waitFor(std::unique_lock<std::mutex>& lock, const std::function<bool()>& done, const std::string& what) {
  // Without a Mapping nodelet nothing will answer: no need to wait for the timeout to say so.
  const bool listened = publisher_.getNumSubscribers() > 0;
  if (listened && answered_.wait_for(lock, std::chrono::duration<double>(kAnswerTimeoutS), done)) return;
  if (!listened && done()) return;
  settled_ = posted_;  // given up: the next wait is for the next requests only
  if (!listened)
    throw std::runtime_error("nothing subscribes to " + publisher_.getTopic() +
                             ": load semantic_edge_vo/Mapping in the same nodelet manager as Tracking");
  throw std::runtime_error("the Mapping nodelet did not answer " + what + " within " + std::to_string(static_cast<int>(kAnswerTimeoutS)) + " s");
}

}  // namespace semantic_edge_vo
