// A camera driver for smoke tests and the demo: publishes the core's moving test pattern as
// image (mono8) + camera_info through image_transport at a fixed rate.
//   rosrun semantic_edge_vo test_pattern_camera _rate:=10 _frames:=0 _width:=640 _height:=360
// Topics (relative): image, camera_info. Parameters: ~rate (Hz), ~frames (0: forever), ~width,
// ~height (px), ~frame_id, ~seed, ~start_delay (s, lets subscribers connect).
#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include "semantic_edge_vo/test_pattern.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "test_pattern_camera");
  ros::NodeHandle node, private_node("~");
  const double rate = private_node.param("rate", 10.0);
  const int frames = private_node.param("frames", 0);
  const int width = private_node.param("width", 640);
  const int height = private_node.param("height", 360);
  const int seed = private_node.param("seed", 1);
  const std::string frame_id = private_node.param<std::string>("frame_id", "camera_optical_frame");
  const double start_delay = private_node.param("start_delay", 1.0);
  if (rate <= 0.0 || width < 32 || height < 32) {
    ROS_ERROR("test_pattern_camera: need rate > 0 and an image of at least 32x32 pixels");
    return 1;
  }
  image_transport::ImageTransport transport(node);
  image_transport::CameraPublisher publisher = transport.advertiseCamera("image", 5);
  ros::Duration(start_delay).sleep();

  sensor_msgs::CameraInfo info;
  info.header.frame_id = frame_id;
  info.width = static_cast<std::uint32_t>(width);
  info.height = static_cast<std::uint32_t>(height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  const double f = 0.58 * width, cx = (width - 1) / 2.0, cy = (height - 1) / 2.0;
  info.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {f, 0, cx, 0, 0, f, cy, 0, 0, 0, 1, 0};

  ros::Rate loop(rate);
  for (int i = 0; ros::ok() && (frames == 0 || i < frames); ++i) {
    cv_bridge::CvImage image;
    image.header.stamp = ros::Time::now();
    image.header.frame_id = frame_id;
    image.encoding = "mono8";
    image.image = semantic_edge_vo::renderTestPattern(i, width, height, static_cast<std::uint32_t>(seed));
    info.header.stamp = image.header.stamp;
    publisher.publish(*image.toImageMsg(), info);
    ros::spinOnce();
    loop.sleep();
  }
  return 0;
}
