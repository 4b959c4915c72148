#include "semantic_edge_vo/ros/sequence_bag_writer.h"

#include <stdexcept>

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <sensor_msgs/CompressedImage.h>

#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"

namespace semantic_edge_vo {

sensor_msgs::CameraInfo cameraInfoOf(const PinholeCamera& camera, const std::string& frame_id) {
  sensor_msgs::CameraInfo info;
  info.header.frame_id = frame_id;
  info.width = static_cast<std::uint32_t>(camera.width);
  info.height = static_cast<std::uint32_t>(camera.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {camera.fx, 0.0, camera.cx, 0.0, 0.0, camera.fy, camera.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

SequenceBagWriter::SequenceBagWriter(const std::string& path, const PinholeCamera& camera, bool semantics)
    : info_(cameraInfoOf(camera, kCameraFrame)), semantics_(semantics) {
  try {
    bag_.open(path, rosbag::bagmode::Write);
    bag_.setCompression(rosbag::compression::LZ4);
    open_ = true;
  } catch (const rosbag::BagException& e) {
    error_ = "cannot open the bag " + path + ": " + e.what();
  }
}

SequenceBagWriter::~SequenceBagWriter() { close(); }

void SequenceBagWriter::close() {
  if (open_) bag_.close();
  open_ = false;
}

void SequenceBagWriter::writePng(const std::string& topic, const ros::Time& stamp, std::vector<std::uint8_t> png,
                                 const std::string& encoding) {
  sensor_msgs::CompressedImage message;
  message.header.stamp = stamp;
  message.header.frame_id = kCameraFrame;
  message.format = encoding + "; png compressed ";
  message.data = std::move(png);
  bag_.write(topic, stamp, message);
}

bool SequenceBagWriter::write(const synthetic::SyntheticFrame& frame, const synthetic::EncodedFrame& files) {
  if (!open_ || !error_.empty()) return false;
  auto encoded = [&](const char* folder) {
    const std::vector<std::uint8_t>* bytes = files.find(folder);
    if (!bytes) throw std::runtime_error(std::string("no encoded ") + folder + " image");
    return *bytes;
  };
  try {
    const ros::Time stamp(kBaseTime + frame.time);
    std_msgs::Header header;
    header.stamp = stamp;
    header.frame_id = kCameraFrame;
    header.seq = static_cast<std::uint32_t>(frame.index);
    info_.header = header;
    bag_.write("/camera/image_rect", stamp, cv_bridge::CvImage(header, "mono8", frame.gray).toImageMsg());
    bag_.write("/camera/camera_info", stamp, info_);
    writePng("/camera/color/image_rect/compressed", stamp, encoded("image_2"), "bgr8");
    bag_.write("/camera/color/camera_info", stamp, info_);
    // Raw images in the forms EdgeIntake reads (the bag's LZ4 chunks keep them small on disk).
    if (semantics_) {
      bag_.write("/camera/semantics/class_labels", stamp,
                 cv_bridge::CvImage(header, "8UC2", synthetic::classLabels(frame.semantics)).toImageMsg());
      bag_.write("/camera/semantics/edge_bitmask", stamp,
                 cv_bridge::CvImage(header, "8UC4", synthetic::packEdgeBitmask(frame.semantics)).toImageMsg());
    }
    bag_.write("/camera/semantics/ground_truth_class", stamp, cv_bridge::CvImage(header, "mono8", frame.class_id).toImageMsg());
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = stamp;
    pose.header.frame_id = kWorldFrame;
    pose.pose = toPoseMsg(frame.T_world_cam);
    bag_.write("/ground_truth/pose", stamp, pose);
  } catch (const std::exception& e) {
    error_ = std::string("cannot write to the bag: ") + e.what();
    return false;
  }
  return true;
}

}  // namespace semantic_edge_vo
