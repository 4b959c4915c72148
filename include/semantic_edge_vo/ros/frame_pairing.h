#pragma once
#include <map>
#include <vector>

#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

namespace semantic_edge_vo {

/// Pairs each image with the class map (and, when needed, the edge map) of the same stamp. An image
/// waits at most `wait` (wall time) for its maps, maps wait as long for their image; frames leave in
/// stamp order, so a complete frame also releases the older images still waiting (incomplete).
/// Not thread-safe: the caller serializes.
class FramePairing {
 public:
  struct Frame {
    sensor_msgs::ImageConstPtr image;
    sensor_msgs::CameraInfoConstPtr info;
    sensor_msgs::ImageConstPtr classes;  ///< null when it did not arrive in time
    sensor_msgs::ImageConstPtr edges;    ///< null when not needed or not arrived
    bool complete = false;               ///< every needed map is there
  };

  /// @param[in] need_edges whether frames also wait for an edge map
  /// @param[in] wait how long an input waits for its partners, s
  /// @param[in] max_pending stamps held at most; beyond, the oldest leaves incomplete
  FramePairing(bool need_edges, double wait, std::size_t max_pending)
      : need_edges_(need_edges), wait_(wait), max_pending_(max_pending) {}

  /// Each returns the frames that are ready (complete, or released incomplete), oldest first.
  std::vector<Frame> addImage(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info,
                              const ros::WallTime& now);
  std::vector<Frame> addClasses(const sensor_msgs::ImageConstPtr& classes, const ros::WallTime& now);
  std::vector<Frame> addEdges(const sensor_msgs::ImageConstPtr& edges, const ros::WallTime& now);
  /// Frames whose image waited longer than `wait`, released incomplete; expired lone maps are dropped.
  std::vector<Frame> expire(const ros::WallTime& now);

  /// Drops every waiting input (its stream started over); returns how many images were waiting.
  std::size_t clear();

  std::size_t pending() const { return entries_.size(); }

 private:
  struct Entry {
    Frame frame;
    ros::WallTime arrival;  // of the first input with this stamp
  };
  Entry& entry(const ros::Time& stamp, const ros::WallTime& now);
  bool complete(const Frame& frame) const;
  std::vector<Frame> release(const ros::WallTime& now);

  bool need_edges_;
  double wait_;
  std::size_t max_pending_;
  std::map<ros::Time, Entry> entries_;
};

}  // namespace semantic_edge_vo
