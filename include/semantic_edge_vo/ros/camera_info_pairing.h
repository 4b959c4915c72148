#pragma once
#include <deque>
#include <vector>

#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

namespace semantic_edge_vo {

/// Pairs each image with the camera_info nearest its stamp within `tolerance` (drivers that stamp
/// the two a little apart are paired too). An image whose camera_info has not come yet waits up to
/// `wait` (wall time); images leave in arrival order. Not thread-safe: the caller serializes.
class CameraInfoPairing {
 public:
  struct Pair {
    sensor_msgs::ImageConstPtr image;
    sensor_msgs::CameraInfoConstPtr info;  ///< null: none within the tolerance in time
  };

  /// @param[in] tolerance s between an image's stamp and its camera_info's
  /// @param[in] wait s an image waits for its camera_info
  /// @param[in] max_waiting images held at most; beyond, the oldest leaves without one
  CameraInfoPairing(double tolerance, double wait, std::size_t max_waiting)
      : tolerance_(tolerance), wait_(wait), max_waiting_(max_waiting) {}

  /// Each returns the images that leave (paired, or without a camera_info), oldest first.
  std::vector<Pair> addImage(const sensor_msgs::ImageConstPtr& image, const ros::WallTime& now);
  std::vector<Pair> addInfo(const sensor_msgs::CameraInfoConstPtr& info, const ros::WallTime& now);
  std::vector<Pair> expire(const ros::WallTime& now);

  std::size_t waiting() const { return waiting_.size(); }
  /// Wall time of the newest camera_info (zero: none yet).
  ros::WallTime lastInfoArrival() const { return last_info_arrival_; }

 private:
  struct Waiting {
    sensor_msgs::ImageConstPtr image;
    ros::WallTime arrival;
  };
  sensor_msgs::CameraInfoConstPtr match(const ros::Time& stamp) const;
  std::vector<Pair> release(const ros::WallTime& now);

  double tolerance_, wait_;
  std::size_t max_waiting_;
  std::deque<Waiting> waiting_;
  std::deque<sensor_msgs::CameraInfoConstPtr> infos_;  ///< recent, in arrival order
  ros::WallTime last_info_arrival_;
  static constexpr std::size_t kRememberedInfos = 20;
};

}  // namespace semantic_edge_vo
