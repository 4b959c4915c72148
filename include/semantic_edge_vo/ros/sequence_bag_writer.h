#pragma once
#include <string>

#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

#include "semantic_edge_vo/camera.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {

/// Writes synthetic frames into a rosbag on conventional topics (docs/synthetic_sequences.md):
///   /camera/image_rect, /camera/camera_info                 sensor_msgs/Image mono8 + CameraInfo
///   /camera/color/image_rect/compressed, /camera/color/camera_info   PNG, bgr8
///   /camera/semantics/ground_truth_class                    Image mono8, Cityscapes train ids
///   /camera/semantics/class_labels                          Image 8UC2 (class, confidence x 255): labels form
///   /camera/semantics/edge_bitmask                          Image 8UC4 (class bits 0..23, strength x 255): bitmask form
///   /ground_truth/pose                                      geometry_msgs/PoseStamped, camera to world
/// (the class topics in EdgeIntake's class_format labels and bitmask). Stamps are kBaseTime + the
/// frame time; chunks are LZ4-compressed (the label maps shrink a hundredfold, playback is unchanged).
class SequenceBagWriter {
 public:
  static constexpr double kBaseTime = 1600000000.0;  ///< s (2020-09-13), stamp of frame 0
  static constexpr const char* kCameraFrame = "camera_optical_frame";
  static constexpr const char* kWorldFrame = "world";

  /// Opens `path` for writing; check error().
  SequenceBagWriter(const std::string& path, const PinholeCamera& camera, bool semantics);
  ~SequenceBagWriter();

  const std::string& error() const { return error_; }
  /// Writes one frame; `files` are its PNG files (synthetic::encodeFrame), the colour one reused
  /// for the compressed colour topic.
  bool write(const synthetic::SyntheticFrame& frame, const synthetic::EncodedFrame& files);
  void close();

 private:
  void writePng(const std::string& topic, const ros::Time& stamp, std::vector<std::uint8_t> png,
                const std::string& encoding);

  rosbag::Bag bag_;
  sensor_msgs::CameraInfo info_;
  bool semantics_;
  bool open_ = false;
  std::string error_;
};

/// A complete CameraInfo of a rectified pinhole camera (K, P, R identity, D zero, plumb_bob).
sensor_msgs::CameraInfo cameraInfoOf(const PinholeCamera& camera, const std::string& frame_id);

}  // namespace semantic_edge_vo
