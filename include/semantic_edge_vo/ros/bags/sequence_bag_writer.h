#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>
#include <std_msgs/Header.h>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {

/// One frame on the topics every sequence bag has (synthetic or KITTI).
struct BagFrame {
  std::uint32_t index = 0;
  double time = 0.0;      ///< s since frame 0: the stamp is the writer's base time + this
  cv::Mat image;          ///< CV_8UC1 (mono8) or CV_8UC3 (bgr8), rectified
  cv::Mat class_labels;   ///< empty, or CV_8UC1 / CV_8UC2 (class, confidence x 255)
  cv::Mat edge_bitmask;   ///< empty, or CV_8UC4 (class bits 0..23, strength x 255)
  std::optional<Eigen::Isometry3d> T_world_cam;  ///< ground truth, camera to world (m)
};

/// Writes sequence frames into a rosbag on conventional topics (docs/synthetic_sequences.md):
///   /camera/image_rect, /camera/camera_info                 sensor_msgs/Image mono8 or bgr8 + CameraInfo
///   /camera/semantics/class_labels                          Image 8UC1/8UC2 (class, confidence x 255): labels form
///   /camera/semantics/edge_bitmask                          Image 8UC4 (class bits 0..23, strength x 255): bitmask form
///   /ground_truth/pose                                      geometry_msgs/PoseStamped, camera to world
/// and, for synthetic frames only,
///   /camera/color/image_rect/compressed, /camera/color/camera_info   PNG, bgr8
///   /camera/semantics/ground_truth_class                    Image mono8, Cityscapes train ids
/// (the class topics in EdgeIntake's class_format labels and bitmask). Stamps are the base time
/// (kBaseTime by default) + the frame time; chunks are LZ4-compressed (the label maps shrink a
/// hundredfold, playback is unchanged).
class SequenceBagWriter {
 public:
  static constexpr double kBaseTime = 1600000000.0;  ///< s (2020-09-13), default stamp of frame 0
  static constexpr const char* kCameraFrame = "camera_optical_frame";
  static constexpr const char* kWorldFrame = "world";

  /// Opens `path` for writing frames of the camera `info` (its frame_id is used); check error().
  SequenceBagWriter(const std::string& path, const sensor_msgs::CameraInfo& info, double base_time = kBaseTime);
  /// Synthetic sequences: cameraInfoOf(camera, kCameraFrame); `semantics` writes the class topics.
  SequenceBagWriter(const std::string& path, const PinholeCamera& camera, bool semantics);
  ~SequenceBagWriter();

  const std::string& error() const { return error_; }
  /// Writes one frame; false (see error()) when the bag failed.
  bool write(const BagFrame& frame);
  /// Writes one synthetic frame; `files` are its PNG files (synthetic::encodeFrame), the colour one
  /// reused for the compressed colour topic.
  bool write(const synthetic::SyntheticFrame& frame, const synthetic::EncodedFrame& files);
  void close();

 private:
  /// Writes the common topics and returns their header; throws on failure.
  std_msgs::Header writeCommon(const BagFrame& frame);
  /// Runs `write` unless the bag is closed or failed; a throw becomes error().
  bool guarded(const std::function<void()>& write);
  void writePng(const std::string& topic, const std_msgs::Header& header, std::vector<std::uint8_t> png,
                const std::string& encoding);

  rosbag::Bag bag_;
  sensor_msgs::CameraInfo info_;
  double base_time_;
  bool semantics_ = true;
  bool open_ = false;
  std::string error_;
};

}  // namespace semantic_edge_vo
