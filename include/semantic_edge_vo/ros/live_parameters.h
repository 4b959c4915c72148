#pragma once
#include <functional>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>

namespace semantic_edge_vo {

/// The parameters of a nodelet that users tune while it runs (dynamic_reconfigure: rqt_reconfigure,
/// `rosrun dynamic_reconfigure dynparam set /<nodelet>/live ...`), served under `~live/`, apart
/// from the parameters the nodelet reads once at start (RosParameterSource skips `live/`).
template <typename Config>
class LiveParameters {
 public:
  /// @param[in] current the values the nodelet runs with (its config): the server starts from them
  /// @param[in] apply called with each new set of values, on a manager thread
  LiveParameters(const ros::NodeHandle& private_node, const Config& current, std::function<void(const Config&)> apply)
      : server_(mutex_, ros::NodeHandle(private_node, "live")) {
    Config start = current;
    server_.updateConfig(start);  // before the callback: the config file's values, not the .cfg's
    server_.setCallback([apply](Config& config, std::uint32_t) { apply(config); });
  }

 private:
  boost::recursive_mutex mutex_;
  dynamic_reconfigure::Server<Config> server_;
};

}  // namespace semantic_edge_vo
