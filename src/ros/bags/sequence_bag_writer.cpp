#include "semantic_edge_vo/ros/bags/sequence_bag_writer.h"

#include <functional>
#include <stdexcept>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CompressedImage.h>

#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"

namespace semantic_edge_vo {
namespace {

const char* imageEncoding(const cv::Mat& image) {
  if (image.type() == CV_8UC1) return "mono8";
  if (image.type() == CV_8UC3) return "bgr8";
  throw std::runtime_error("the camera image must be CV_8UC1 or CV_8UC3");
}

}  // namespace

SequenceBagWriter::SequenceBagWriter(const std::string& path, const sensor_msgs::CameraInfo& info, double base_time)
    : info_(info), base_time_(base_time) {
  try {
    bag_.open(path, rosbag::bagmode::Write);
    bag_.setCompression(rosbag::compression::LZ4);
    open_ = true;
  } catch (const rosbag::BagException& e) {
    error_ = "cannot open the bag " + path + ": " + e.what();
  }
}

SequenceBagWriter::SequenceBagWriter(const std::string& path, const PinholeCamera& camera, bool semantics)
    : SequenceBagWriter(path, cameraInfoOf(camera, kCameraFrame)) {
  semantics_ = semantics;
}

SequenceBagWriter::~SequenceBagWriter() { close(); }

void SequenceBagWriter::close() {
  if (open_) bag_.close();
  open_ = false;
}

void SequenceBagWriter::writePng(const std::string& topic, const std_msgs::Header& header,
                                 std::vector<std::uint8_t> png, const std::string& encoding) {
  sensor_msgs::CompressedImage message;
  message.header = header;
  message.format = encoding + "; png compressed ";
  message.data = std::move(png);
  bag_.write(topic, header.stamp, message);
}

std_msgs::Header SequenceBagWriter::writeCommon(const BagFrame& frame) {
  std_msgs::Header header;
  header.stamp = ros::Time(base_time_ + frame.time);
  header.frame_id = info_.header.frame_id;
  header.seq = frame.index;
  info_.header = header;
  bag_.write("/camera/image_rect", header.stamp,
             cv_bridge::CvImage(header, imageEncoding(frame.image), frame.image).toImageMsg());
  bag_.write("/camera/camera_info", header.stamp, info_);
  // Raw images in the forms EdgeIntake reads (the bag's LZ4 chunks keep them small on disk).
  if (!frame.class_labels.empty())
    bag_.write("/camera/semantics/class_labels", header.stamp,
               cv_bridge::CvImage(header, frame.class_labels.channels() == 1 ? "8UC1" : "8UC2", frame.class_labels)
                   .toImageMsg());
  if (!frame.edge_bitmask.empty())
    bag_.write("/camera/semantics/edge_bitmask", header.stamp,
               cv_bridge::CvImage(header, "8UC4", frame.edge_bitmask).toImageMsg());
  if (frame.T_world_cam) {
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = header.stamp;
    pose.header.frame_id = kWorldFrame;
    pose.pose = toPoseMsg(*frame.T_world_cam);
    bag_.write("/ground_truth/pose", header.stamp, pose);
  }
  return header;
}

bool SequenceBagWriter::guarded(const std::function<void()>& write) {
  if (!open_ || !error_.empty()) return false;
  try {
    write();
  } catch (const std::exception& e) {
    error_ = std::string("cannot write to the bag: ") + e.what();
    return false;
  }
  return true;
}

bool SequenceBagWriter::write(const BagFrame& frame) {
  return guarded([&] { writeCommon(frame); });
}

bool SequenceBagWriter::write(const synthetic::SyntheticFrame& frame, const synthetic::EncodedFrame& files) {
  return guarded([&] {
    const std::vector<std::uint8_t>* color = files.find("image_2");
    if (!color) throw std::runtime_error("no encoded image_2 image");
    BagFrame common;
    common.index = static_cast<std::uint32_t>(frame.index);
    common.time = frame.time;
    common.image = frame.gray;
    if (semantics_) {
      common.class_labels = synthetic::classLabels(frame.semantics);
      common.edge_bitmask = synthetic::packEdgeBitmask(frame.semantics);
    }
    common.T_world_cam = frame.T_world_cam;
    const std_msgs::Header header = writeCommon(common);
    writePng("/camera/color/image_rect/compressed", header, *color, "bgr8");
    bag_.write("/camera/color/camera_info", header.stamp, info_);
    bag_.write("/camera/semantics/ground_truth_class", header.stamp,
               cv_bridge::CvImage(header, "mono8", frame.class_id).toImageMsg());
  });
}

}  // namespace semantic_edge_vo
