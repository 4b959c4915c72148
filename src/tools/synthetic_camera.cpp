// A camera driver that drives through a synthetic world live: publishes the frames of a synthetic
// sequence (core renderer) as image (mono8) + camera_info, the simulated semantic network's edges
// (bitmask form, /camera/semantics/edge_bitmask) and the ground-truth pose, at a fixed rate.
//   rosrun semantic_edge_vo synthetic_camera _scene:=city _seed:=1 _rate:=10 _frames:=0 _scale:=0.5
// Topics (relative): image, camera_info, semantics/edge_bitmask, ground_truth/pose. Parameters:
// ~scene (city|village|highway), ~seed, ~rate (Hz), ~frames (0: forever), ~scale (image size relative
// to KITTI's 1241x376), ~semantics (publish the bitmask), ~frame_id, ~start_delay (s).
#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <image_transport/image_transport.h>
#include <ros/ros.h>

#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

using namespace semantic_edge_vo;

int main(int argc, char** argv) {
  ros::init(argc, argv, "synthetic_camera");
  ros::NodeHandle node, private_node("~");
  const std::string scene_name = private_node.param<std::string>("scene", "city");
  const int seed = private_node.param("seed", 1), frames = private_node.param("frames", 0);
  const double rate = private_node.param("rate", 10.0), scale = private_node.param("scale", 0.5);
  const bool semantics = private_node.param("semantics", true);
  const std::string frame_id = private_node.param<std::string>("frame_id", "camera_optical_frame");
  synthetic::SceneType scene;
  if (!synthetic::parseSceneType(scene_name, &scene) || rate <= 0.0 || !(scale > 0.1 && scale <= 1.0)) {
    ROS_ERROR("synthetic_camera: need scene city|village|highway, rate > 0 and 0.1 < scale <= 1");
    return 1;
  }
  synthetic::SyntheticSequenceOptions options = synthetic::SyntheticSequenceOptions::forScene(scene, static_cast<std::uint64_t>(seed));
  options.camera = kittiCamera().scaled(scale);
  options.semantics = semantics;
  synthetic::SyntheticSequence sequence(options);
  sensor_msgs::CameraInfo info = cameraInfoOf(options.camera, frame_id);

  image_transport::ImageTransport transport(node);
  image_transport::CameraPublisher camera_publisher = transport.advertiseCamera("image", 5);
  ros::Publisher bitmask_publisher = node.advertise<sensor_msgs::Image>("semantics/edge_bitmask", 5);
  ros::Publisher truth_publisher = node.advertise<geometry_msgs::PoseStamped>("ground_truth/pose", 5);
  ros::Duration(private_node.param("start_delay", 1.0)).sleep();

  ros::Rate loop(rate);
  for (int i = 0; ros::ok() && (frames == 0 || i < frames); ++i) {
    const synthetic::SyntheticFrame frame = sequence.frame(i);
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = frame_id;
    info.header = header;
    camera_publisher.publish(*cv_bridge::CvImage(header, "mono8", frame.gray).toImageMsg(), info);
    if (semantics) bitmask_publisher.publish(cv_bridge::CvImage(header, "8UC4", synthetic::packEdgeBitmask(frame.semantics)).toImageMsg());
    geometry_msgs::PoseStamped truth;
    truth.header.stamp = header.stamp;
    truth.header.frame_id = "world";
    truth.pose = toPoseMsg(frame.T_world_cam);
    truth_publisher.publish(truth);
    ros::spinOnce();
    loop.sleep();
  }
  return 0;
}
