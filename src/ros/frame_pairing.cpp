#include "semantic_edge_vo/ros/frame_pairing.h"

namespace semantic_edge_vo {

FramePairing::Entry& FramePairing::entry(const ros::Time& stamp, const ros::WallTime& now) {
  auto inserted = entries_.emplace(stamp, Entry{});
  if (inserted.second) inserted.first->second.arrival = now;
  return inserted.first->second;
}

bool FramePairing::complete(const Frame& frame) const {
  return frame.image && frame.classes && (!need_edges_ || frame.edges);
}

std::vector<FramePairing::Frame> FramePairing::addImage(const sensor_msgs::ImageConstPtr& image,
                                                        const sensor_msgs::CameraInfoConstPtr& info,
                                                        const ros::WallTime& now) {
  Frame& frame = entry(image->header.stamp, now).frame;
  frame.image = image;
  frame.info = info;
  return release(now);
}

std::vector<FramePairing::Frame> FramePairing::addClasses(const sensor_msgs::ImageConstPtr& classes, const ros::WallTime& now) {
  entry(classes->header.stamp, now).frame.classes = classes;
  return release(now);
}

std::vector<FramePairing::Frame> FramePairing::addEdges(const sensor_msgs::ImageConstPtr& edges, const ros::WallTime& now) {
  entry(edges->header.stamp, now).frame.edges = edges;
  return release(now);
}

std::vector<FramePairing::Frame> FramePairing::expire(const ros::WallTime& now) { return release(now); }

std::vector<FramePairing::Frame> FramePairing::release(const ros::WallTime& now) {
  // Everything up to the newest complete stamp leaves now.
  ros::Time newest_complete;
  bool any_complete = false;
  for (const auto& [stamp, e] : entries_)
    if (complete(e.frame)) {
      newest_complete = stamp;
      any_complete = true;
    }
  std::vector<Frame> ready;
  for (auto it = entries_.begin(); it != entries_.end();) {
    const bool expired = (now - it->second.arrival).toSec() > wait_;
    const bool overflow = entries_.size() > max_pending_;
    if (!(expired || overflow || (any_complete && it->first <= newest_complete))) break;
    Frame& frame = it->second.frame;
    frame.complete = complete(frame);
    if (frame.image) ready.push_back(std::move(frame));  // lone maps are dropped
    it = entries_.erase(it);
  }
  return ready;
}

std::size_t FramePairing::clear() {
  std::size_t images = 0;
  for (const auto& stamped : entries_) images += stamped.second.frame.image ? 1 : 0;
  entries_.clear();
  return images;
}

}  // namespace semantic_edge_vo
