#include "semantic_edge_vo/ros/bags/kitti_bag_conversion.h"

#include <filesystem>
#include <vector>

#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/sequences/semantic_map_files.h"
#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace fs = std::filesystem;
namespace {

/// The first missing frame file of `folder` among frames 0..count-1, or "".
std::string missingFrame(const std::string& folder, std::size_t count) {
  if (!fs::is_directory(folder)) return folder + ": no such folder";
  for (std::size_t i = 0; i < count; ++i)
    if (const std::string path = kittiFramePath(folder, i); !fs::exists(path))
      return path + ": no such file (times.txt has " + std::to_string(count) + " frames)";
  return "";
}

/// "" when the image read from `path` has the size `expected` (that of `what`).
std::string checkSize(const std::string& path, const cv::Size& found, const cv::Size& expected, const char* what) {
  if (found == expected) return "";
  return path + ": " + std::to_string(found.width) + "x" + std::to_string(found.height) + ", " + what + " is " +
         std::to_string(expected.width) + "x" + std::to_string(expected.height);
}

/// Reads frame `i`'s image and semantic maps into `frame`.
std::string readFrame(const KittiBagOptions& options, const KittiSequence& sequence, std::size_t i, BagFrame* frame) {
  frame->index = static_cast<std::uint32_t>(i);
  frame->time = sequence.times[i];
  std::string error = readKittiImage(sequence.imagePath(i), sequence.camera, &frame->image);
  if (error.empty() && !options.class_labels.empty()) {
    const std::string path = kittiFramePath(options.class_labels, i);
    error = readClassLabelsPng(path, &frame->class_labels);
    if (error.empty()) error = checkSize(path, frame->class_labels.size(), frame->image.size(), "the camera image");
  }
  if (error.empty() && !options.edge_bitmask.empty()) {
    const std::string path = kittiFramePath(options.edge_bitmask, i);
    error = readEdgeBitmaskPng(path, &frame->edge_bitmask);
    if (error.empty()) error = checkSize(path, frame->edge_bitmask.size(), frame->image.size(), "the camera image");
  }
  return error;
}

/// Every input file exists and the text files parse; the ground truth has one pose per frame.
std::string openInputs(const KittiBagOptions& options, KittiSequence* sequence, Trajectory* ground_truth) {
  std::string error = openKittiSequence(options.sequence, options.camera, sequence);
  if (!error.empty()) return error;
  const std::size_t frames = sequence->size();
  const std::string images = (fs::path(sequence->directory) / ("image_" + std::to_string(sequence->camera))).string();
  for (const std::string& folder : {images, options.class_labels, options.edge_bitmask})
    if (!folder.empty())
      if (error = missingFrame(folder, frames); !error.empty()) return error;
  if (!options.poses.empty()) {
    if (error = readKittiPoses(options.poses, ground_truth); !error.empty()) return error;
    if (ground_truth->size() != frames)
      return options.poses + ": " + std::to_string(ground_truth->size()) + " poses, but times.txt has " +
             std::to_string(frames) + " frames";
  }
  return "";
}

}  // namespace

sensor_msgs::CameraInfo kittiCameraInfo(const KittiSequence& sequence, int width, int height,
                                        const std::string& frame_id) {
  sensor_msgs::CameraInfo info = cameraInfoOf(sequence.pinhole(width, height), frame_id);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) info.P[static_cast<std::size_t>(4 * r + c)] = sequence.projection(r, c);
  return info;
}

std::string writeKittiBag(const KittiBagOptions& options,
                          const std::function<void(std::size_t done, std::size_t total)>& progress) {
  KittiSequence sequence;
  Trajectory ground_truth;
  std::string error = openInputs(options, &sequence, &ground_truth);
  if (!error.empty()) return error;
  const Eigen::Isometry3d T_cam0_cam = sequence.T_cam0_cam();

  BagFrame frame;  // frame 0 first: its size completes the CameraInfo
  if (error = readFrame(options, sequence, 0, &frame); !error.empty()) return error;
  const cv::Size size = frame.image.size();
  if (const std::string invalid = sequence.pinhole(size.width, size.height).validate(); !invalid.empty())
    return (fs::path(options.sequence) / "calib.txt").string() + ": " + invalid;
  {
    SequenceBagWriter bag(options.output,
                          kittiCameraInfo(sequence, size.width, size.height, SequenceBagWriter::kCameraFrame),
                          options.start_time);
    error = bag.error();
    if (error.empty() && progress) progress(0, sequence.size());
    for (std::size_t i = 0; error.empty() && i < sequence.size(); ++i) {
      if (i > 0 && !(error = readFrame(options, sequence, i, &frame)).empty()) break;
      if (error = checkSize(sequence.imagePath(i), frame.image.size(), size, "frame 0"); !error.empty()) break;
      if (!ground_truth.poses.empty()) frame.T_world_cam = ground_truth.poses[i] * T_cam0_cam;
      if (!bag.write(frame)) error = bag.error();
      else if (progress) progress(i + 1, sequence.size());
    }
  }
  if (!error.empty()) {
    std::error_code ignored;
    fs::remove(options.output, ignored);
  }
  return error;
}

}  // namespace semantic_edge_vo
