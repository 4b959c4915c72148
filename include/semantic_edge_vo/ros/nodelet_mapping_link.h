#pragma once
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <ros/spinner.h>
#include <ros/subscriber.h>

#include "semantic_edge_vo/backend/mapping_link.h"
#include "semantic_edge_vo/ros/mapping_messages.h"
#include "semantic_edge_vo/ros/message_tracer.h"

namespace semantic_edge_vo {

/// The Tracking nodelet's link to the Mapping nodelet: an odometry's requests go out on
/// `mapping_request`, its outcomes come back on `mapping_outcome`, received on a thread of their
/// own (tracking may be waiting for them in its frame callback).
class NodeletMappingLink : public MappingLink {
 public:
  /// @param[in] stamp_of the stamp of a frame by its odometry index (called from post())
  /// @param[in] class_names of the frames' intake, read at each post()
  /// @param[in] tracer outlives this object
  NodeletMappingLink(const ros::NodeHandle& node, const OdometryOptions& options, const PinholeCamera& camera,
                     std::function<ros::Time(int)> stamp_of, const std::vector<std::string>* class_names, const MessageTracer* tracer);
  ~NodeletMappingLink() override;

  void post(MappingRequest request) override;
  std::vector<MappingOutcome> takeOutcomes() override;
  void waitForFrame(int frame_index) override;
  void waitUntilIdle() override;

  /// How long a wait lasts before mapping counts as not answering.
  static constexpr double kAnswerTimeoutS = 10.0;

 private:
  void onOutcome(const boost::shared_ptr<const MappingOutcomeMessage>& message);
  /// Waits (lock held) until `done` or the timeout; then throws, the requests not answered given up.
  void waitFor(std::unique_lock<std::mutex>& lock, const std::function<bool()>& done, const std::string& what);

  std::shared_ptr<const OdometryOptions> options_;
  PinholeCamera camera_;
  std::uint64_t session_;
  std::function<ros::Time(int)> stamp_of_;
  const std::vector<std::string>* class_names_;
  const MessageTracer* tracer_;
  ros::Publisher publisher_;

  std::mutex mutex_;
  std::condition_variable answered_;
  std::vector<MappingOutcome> outcomes_;
  long posted_ = 0, settled_ = 0;  ///< requests posted; outcomes received other than provisional ones
  int mapped_up_to_ = -1;          ///< the newest frame with an outcome

  ros::CallbackQueue queue_;  ///< the outcomes' (before the spinner and subscriber, which use it)
  ros::Subscriber subscriber_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

}  // namespace semantic_edge_vo
