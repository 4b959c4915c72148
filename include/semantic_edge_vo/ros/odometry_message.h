#pragma once
#include <optional>

#include <nav_msgs/Odometry.h>

#include "semantic_edge_vo/common/pose_uncertainty.h"
#include "semantic_edge_vo/config/live_options.h"

namespace semantic_edge_vo {

/// nav_msgs/Odometry of base_link in odom for each published pose: the pose with its tracking
/// covariance in odom's axes, the twist in base_link's axes from the previous published pose and
/// its covariance (docs/architecture.md, "Pose covariance and twist"). Serial use only.
class OdometryMessageBuilder {
 public:
  /// A variance this large means "not known": positions in an arbitrary scale, a twist without a
  /// previous pose.
  static constexpr double kUnknownVariance = 1e6;

  /// @param[in] max_twist_gap s between two poses beyond which the twist is unknown
  OdometryMessageBuilder(FrameNames frames, double max_twist_gap) : frames_(std::move(frames)), max_twist_gap_(max_twist_gap) {}

  /// @param[in] base_covariance of base_link's pose, in its own axes (baseCovariance)
  /// @param[in] metric whether positions are in metres (else their variances are unknown)
  nav_msgs::OdometryPtr build(const ros::Time& stamp, const Eigen::Isometry3d& T_odom_base, const Matrix6d& base_covariance,
                              bool metric);

  /// The next pose follows none (the odometry started over): its twist is unknown.
  void restart() { previous_.reset(); }

 private:
  struct Published {
    ros::Time stamp;
    Eigen::Isometry3d T_odom_base;
    Matrix6d base_covariance;
  };
  FrameNames frames_;
  double max_twist_gap_;
  std::optional<Published> previous_;
};

}  // namespace semantic_edge_vo
