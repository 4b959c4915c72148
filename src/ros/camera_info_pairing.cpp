#include "semantic_edge_vo/ros/camera_info_pairing.h"

#include <cmath>

namespace semantic_edge_vo {

sensor_msgs::CameraInfoConstPtr CameraInfoPairing::match(const ros::Time& stamp) const {
  sensor_msgs::CameraInfoConstPtr best;
  double best_gap = tolerance_;
  for (const auto& info : infos_) {
    const double gap = std::abs((info->header.stamp - stamp).toSec());
    if (gap <= best_gap) {
      best = info;
      best_gap = gap;
    }
  }
  return best;
}

std::vector<CameraInfoPairing::Pair> CameraInfoPairing::release(const ros::WallTime& now) {
  std::vector<Pair> leaving;
  while (!waiting_.empty()) {
    const Waiting& front = waiting_.front();
    sensor_msgs::CameraInfoConstPtr info = match(front.image->header.stamp);
    const bool expired = (now - front.arrival).toSec() > wait_ || waiting_.size() > max_waiting_;
    if (!info && !expired) break;  // it waits, and so do the images behind it: order is kept
    leaving.push_back({front.image, info});
    waiting_.pop_front();
  }
  return leaving;
}

std::vector<CameraInfoPairing::Pair> CameraInfoPairing::addImage(const sensor_msgs::ImageConstPtr& image, const ros::WallTime& now) {
  waiting_.push_back({image, now});
  return release(now);
}

std::vector<CameraInfoPairing::Pair> CameraInfoPairing::addInfo(const sensor_msgs::CameraInfoConstPtr& info, const ros::WallTime& now) {
  infos_.push_back(info);
  while (infos_.size() > kRememberedInfos) infos_.pop_front();
  last_info_arrival_ = now;
  return release(now);
}

std::vector<CameraInfoPairing::Pair> CameraInfoPairing::expire(const ros::WallTime& now) { return release(now); }

}  // namespace semantic_edge_vo
