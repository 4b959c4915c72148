#include "semantic_edge_vo/ros/odometry_message.h"

#include <boost/make_shared.hpp>

#include "semantic_edge_vo/ros/conversions.h"

namespace semantic_edge_vo {
namespace {

void copyCovariance(const Matrix6d& covariance, boost::array<double, 36>* out) {
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) (*out)[static_cast<std::size_t>(6 * r + c)] = covariance(r, c);
}

/// Translation variances of a covariance made "not known" (arbitrary units).
Matrix6d withUnknownTranslation(Matrix6d covariance) {
  covariance.topRows<3>().setZero();
  covariance.leftCols<3>().setZero();
  covariance.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() * OdometryMessageBuilder::kUnknownVariance;
  return covariance;
}

}  // namespace

nav_msgs::OdometryPtr OdometryMessageBuilder::build(const ros::Time& stamp, const Eigen::Isometry3d& T_odom_base,
                                                    const Matrix6d& base_covariance, bool metric) {
  auto odometry = boost::make_shared<nav_msgs::Odometry>();
  odometry->header.stamp = stamp;
  odometry->header.frame_id = frames_.odom_frame;
  odometry->child_frame_id = frames_.base_frame;
  odometry->pose.pose = toPoseMsg(T_odom_base);
  const Matrix6d pose_covariance = inParentAxes(base_covariance, T_odom_base.linear());
  copyCovariance(metric ? pose_covariance : withUnknownTranslation(pose_covariance), &odometry->pose.covariance);

  Matrix6d twist_covariance = Matrix6d::Identity() * kUnknownVariance;
  const double dt = previous_ ? (stamp - previous_->stamp).toSec() : 0.0;
  if (dt > 0.0 && dt <= max_twist_gap_) {
    const Vector6d twist = bodyTwist(previous_->T_odom_base, T_odom_base, dt);
    odometry->twist.twist.linear.x = twist(0);
    odometry->twist.twist.linear.y = twist(1);
    odometry->twist.twist.linear.z = twist(2);
    odometry->twist.twist.angular.x = twist(3);
    odometry->twist.twist.angular.y = twist(4);
    odometry->twist.twist.angular.z = twist(5);
    // Both poses' errors against their keyframe, as if independent, over the interval squared.
    twist_covariance = (base_covariance + previous_->base_covariance) / (dt * dt);
    if (!metric) twist_covariance = withUnknownTranslation(twist_covariance);
  }
  copyCovariance(twist_covariance, &odometry->twist.covariance);
  previous_ = Published{stamp, T_odom_base, base_covariance};
  return odometry;
}

}  // namespace semantic_edge_vo
