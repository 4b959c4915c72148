#include "semantic_edge_vo/ros/bags/bag_sequence.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/camera_common.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include "semantic_edge_vo/common/trajectory_io.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/rectifier.h"
#include "semantic_edge_vo/sequences/kitti_sequence.h"

namespace semantic_edge_vo {
namespace {

namespace fs = std::filesystem;

/// The image of a message as 8-bit grayscale; empty when it cannot be read.
cv::Mat grayOf(const rosbag::MessageInstance& message, std::string* error) {
  try {
    if (const auto image = message.instantiate<sensor_msgs::Image>()) return cv_bridge::toCvCopy(image, "mono8")->image;
    if (const auto compressed = message.instantiate<sensor_msgs::CompressedImage>()) {
      const cv::Mat decoded = cv::imdecode(compressed->data, cv::IMREAD_GRAYSCALE);
      if (decoded.empty()) *error = "a compressed image on " + message.getTopic() + " does not decode";
      return decoded;
    }
    *error = message.getTopic() + " carries " + message.getDataType() + ", not sensor_msgs/Image or CompressedImage";
  } catch (const cv_bridge::Exception& e) {
    *error = std::string("an image on ") + message.getTopic() + " cannot be converted to mono8: " + e.what();
  }
  return cv::Mat();
}

/// The topic's first camera_info that describes a valid camera.
std::string firstCameraInfo(rosbag::Bag& bag, const std::string& topic, sensor_msgs::CameraInfo* info) {
  for (const rosbag::MessageInstance& message : rosbag::View(bag, rosbag::TopicQuery(topic))) {
    const auto candidate = message.instantiate<sensor_msgs::CameraInfo>();
    if (candidate && cameraFromInfo(*candidate).validate().empty()) {
      *info = *candidate;
      return "";
    }
  }
  return "no valid sensor_msgs/CameraInfo on " + topic + " (the camera_info beside the image topic)";
}

std::string writeCalibration(const std::string& path, const PinholeCamera& camera) {
  std::ofstream out(path);
  char line[256];
  std::snprintf(line, sizeof(line), "P0: %.12e 0 %.12e 0 0 %.12e %.12e 0 0 0 1 0\n", camera.fx, camera.cx, camera.fy, camera.cy);
  out << line;
  out.flush();
  return out ? "" : "cannot write " + path;
}

}  // namespace

std::string writeSequenceFromBag(const BagSequenceOptions& options, const std::function<void(std::size_t, std::size_t)>& progress,
                                 std::size_t* frames, std::size_t* skipped) {
  *frames = *skipped = 0;
  rosbag::Bag bag;
  try {
    bag.open(options.bag, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    return options.bag + ": " + e.what();
  }
  const std::string info_topic = image_transport::getCameraInfoTopic(options.topic);
  sensor_msgs::CameraInfo info;
  if (std::string error = firstCameraInfo(bag, info_topic, &info); !error.empty()) return options.bag + ": " + error;
  Rectifier rectifier;
  if (options.rectify) {
    if (const std::string problem = rectifier.prepare(info); !problem.empty()) return "cannot rectify with " + info_topic + ": " + problem;
    info = rectifier.rectifiedInfo();
  }
  const PinholeCamera camera = cameraFromInfo(info);
  const fs::path root(options.output), images = root / "image_0";
  fs::create_directories(images);
  if (std::string error = writeCalibration((root / "calib.txt").string(), camera); !error.empty()) return error;

  rosbag::View view(bag, rosbag::TopicQuery(options.topic));
  const std::size_t total = view.size();
  if (total == 0) return options.bag + ": no message on " + options.topic;
  std::vector<double> stamps;
  for (const rosbag::MessageInstance& message : view) {
    std::string error;
    cv::Mat gray = grayOf(message, &error);
    if (!error.empty()) return options.bag + ": " + error;
    const auto image = message.instantiate<sensor_msgs::Image>();
    const auto compressed = image ? nullptr : message.instantiate<sensor_msgs::CompressedImage>();
    const double stamp = (image ? image->header.stamp : compressed->header.stamp).toSec();
    if (gray.cols != camera.width || gray.rows != camera.height)
      return options.bag + ": an image on " + options.topic + " is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
             ", its camera_info describes " + std::to_string(camera.width) + "x" + std::to_string(camera.height);
    if (!stamps.empty() && !(stamp > stamps.back())) {
      ++*skipped;
      continue;
    }
    if (options.rectify) {
      cv::Mat rectified;
      rectifier.rectify(gray, &rectified);
      gray = rectified;
    }
    const std::string path = kittiFramePath(images.string(), stamps.size());
    if (!cv::imwrite(path, gray)) return "cannot write " + path;
    stamps.push_back(stamp);
    if (progress) progress(stamps.size() + *skipped, total);
  }
  *frames = stamps.size();
  return writeTimes((root / "times.txt").string(), stamps);
}

}  // namespace semantic_edge_vo
