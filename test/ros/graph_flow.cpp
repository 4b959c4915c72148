// rostest: messages flow through every stage at the input rate, zero-copy, with correct frames and
// stamps; the running graph saves its trajectory and map; every nodelet reports on /diagnostics.
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "semantic_edge_vo/KeyframeMap.h"
#include "semantic_edge_vo/MessageTrace.h"
#include "semantic_edge_vo/SaveFiles.h"
#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/TrackingStatus.h"

namespace semantic_edge_vo {
namespace {

/// Stamps seen per topic, and the last message of a few topics, collected over a window.
class Recorder {
 public:
  template <typename M>
  void listen(ros::NodeHandle& node, const std::string& topic) {
    subscribers_.push_back(node.subscribe<M>(topic, 50, [this, topic](const boost::shared_ptr<const M>& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      stamps_[topic].insert(m->header.stamp);
      last_header_[topic] = m->header;
    }));
  }
  std::set<ros::Time> stamps(const std::string& topic) {
    std::lock_guard<std::mutex> lock(mutex_);
    return stamps_[topic];
  }
  std_msgs::Header lastHeader(const std::string& topic) {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_header_[topic];
  }

 private:
  std::mutex mutex_;
  std::vector<ros::Subscriber> subscribers_;
  std::map<std::string, std::set<ros::Time>> stamps_;
  std::map<std::string, std_msgs::Header> last_header_;
};

double rateOf(const std::set<ros::Time>& stamps) {
  if (stamps.size() < 2) return 0.0;
  return (stamps.size() - 1) / (*stamps.rbegin() - *stamps.begin()).toSec();
}

TEST(GraphFlow, EveryStageAtInputRateZeroCopyWithStampedTf) {
  ros::NodeHandle node;
  Recorder recorder;
  recorder.listen<sensor_msgs::Image>(node, "/camera/image_rect");
  recorder.listen<SemanticEdgeFrame>(node, "/edge_frame");
  recorder.listen<NearestNeighborField>(node, "/nn_field");
  recorder.listen<nav_msgs::Odometry>(node, "/odometry");
  recorder.listen<TrackingStatus>(node, "/tracking_status");
  recorder.listen<TrackedFrame>(node, "/tracked_frame");
  recorder.listen<KeyframeMap>(node, "/keyframe_map");
  recorder.listen<nav_msgs::Path>(node, "/path");
  recorder.listen<sensor_msgs::PointCloud2>(node, "/semantic_edge_map");

  std::mutex trace_mutex;
  std::vector<MessageTrace> traces;
  ros::Subscriber trace_subscriber = node.subscribe<MessageTrace>("/message_trace", 1000, [&](const MessageTraceConstPtr& t) {
    std::lock_guard<std::mutex> lock(trace_mutex);
    traces.push_back(*t);
  });
  std::mutex status_mutex;
  std::map<ros::Time, std::uint8_t> states;
  ros::Subscriber status_subscriber = node.subscribe<TrackingStatus>("/tracking_status", 100, [&](const TrackingStatusConstPtr& s) {
    std::lock_guard<std::mutex> lock(status_mutex);
    states[s->header.stamp] = s->state;
  });
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics;  // the latest of each nodelet
  ros::Subscriber diagnostics_subscriber =
      node.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 100, [&](const diagnostic_msgs::DiagnosticArrayConstPtr& a) {
        std::lock_guard<std::mutex> lock(status_mutex);
        for (const auto& status : a->status) diagnostics[status.name] = status;
      });
  tf2_ros::Buffer tf_buffer(ros::Duration(60.0));
  tf2_ros::TransformListener tf_listener(tf_buffer);
  sensor_msgs::PointCloud2ConstPtr cloud;
  ros::Subscriber cloud_subscriber = node.subscribe<sensor_msgs::PointCloud2>(
      "/semantic_edge_map", 1, [&](const sensor_msgs::PointCloud2ConstPtr& c) { cloud = c; });

  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Wait for the first odometry (graph up), then record a window.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while (recorder.stamps("/odometry").empty() && ros::WallTime::now() < deadline) ros::WallDuration(0.1).sleep();
  ASSERT_FALSE(recorder.stamps("/odometry").empty()) << "no odometry within 20 s: the graph did not come up";
  ros::WallDuration(8.0).sleep();

  // 1. Every stage runs at the input rate and processes every input frame of the window.
  const std::set<ros::Time> inputs = recorder.stamps("/camera/image_rect");
  const double input_rate = rateOf(inputs);
  EXPECT_NEAR(input_rate, 10.0, 1.5);
  const ros::Time first_output = *recorder.stamps("/odometry").begin();
  // Frames of the last 3 s may still be in flight (tracking queues hold 2 s); earlier ones must be there.
  const ros::Time settled = *inputs.rbegin() - ros::Duration(3.0);
  // Outputs first, statuses second: a pose seen in the outputs has its status (published before it)
  // in the snapshot, whatever the tracking latency.
  const std::vector<std::string> topics = {"/edge_frame", "/nn_field", "/tracking_status", "/odometry", "/tracked_frame"};
  std::map<std::string, std::set<ros::Time>> outputs_of;
  for (const std::string& topic : topics) outputs_of[topic] = recorder.stamps(topic);
  std::map<ros::Time, std::uint8_t> final_states;
  {
    std::lock_guard<std::mutex> lock(status_mutex);
    final_states = states;
  }
  for (const std::string& topic : topics) {
    const std::set<ros::Time>& outputs = outputs_of[topic];
    EXPECT_NEAR(rateOf(outputs), input_rate, 0.15 * input_rate) << topic;
    // Every stage answers every frame; poses go out exactly for the frames whose status trusts them.
    const bool poses_only = topic == "/odometry" || topic == "/tracked_frame";
    int missing = 0, untrusted_published = 0;
    std::ostringstream which;
    for (const ros::Time& stamp : inputs) {
      if (stamp < first_output + ros::Duration(0.5) || stamp >= settled) continue;  // connection races at start
      const auto state = final_states.find(stamp);
      if (poses_only && state == final_states.end()) continue;  // no status yet: the status check reports it
      const bool expected =
          !poses_only || state->second == TrackingStatus::TRACKING || state->second == TrackingStatus::RECOVERED;
      if (expected && !outputs.count(stamp)) {
        ++missing;
        which << " " << (stamp - first_output).toSec() << " s after the first pose";
      }
      untrusted_published += !expected && outputs.count(stamp);
    }
    EXPECT_EQ(missing, 0) << topic << " lost input frames:" << which.str();
    EXPECT_EQ(untrusted_published, 0) << topic << " published poses its status did not trust";
  }
  EXPECT_FALSE(recorder.stamps("/keyframe_map").empty());
  // The odometry tracks the drive.
  int tracking = 0, other = 0;
  {
    std::lock_guard<std::mutex> lock(status_mutex);
    for (const auto& entry : states) (entry.second == TrackingStatus::TRACKING ? tracking : other) += 1;
  }
  EXPECT_GT(tracking, 40);
  EXPECT_GE(tracking, 4 * other) << "most frames must be tracked (initialisation and a rare loss aside)";
  EXPECT_FALSE(recorder.stamps("/path").empty());

  // 2. Zero-copy: every receive of a (topic, stamp) saw an address published with it (a new
  // keyframe's mapping outcome is published twice with its frame's stamp: provisional, then settled).
  std::map<std::pair<std::string, ros::Time>, std::set<std::uint64_t>> published;
  std::map<std::string, int> receives_checked;  // topic + receiver -> count
  {
    std::lock_guard<std::mutex> lock(trace_mutex);
    for (const MessageTrace& t : traces)
      if (t.event == "publish") published[{t.topic, t.header.stamp}].insert(t.address);
    for (const MessageTrace& t : traces) {
      if (t.event != "receive") continue;
      auto it = published.find({t.topic, t.header.stamp});
      if (it == published.end()) continue;  // published before the trace subscription
      EXPECT_EQ(it->second.count(t.address), 1u) << t.nodelet << " received a copy on " << t.topic;
      ++receives_checked[t.topic + " by " + t.nodelet];
    }
  }
  for (const std::string expected : {"/edge_frame by /nearest_neighbor_field", "/edge_frame by /tracking",
                                     "/nn_field by /tracking", "/tracked_frame by /mapping", "/mapping_request by /mapping",
                                     "/mapping_outcome by /tracking"})
    EXPECT_GT(receives_checked[expected], 0) << "no traced receive: " << expected;

  // 3. tf odom -> base_link at each image stamp, frames per REP-105, camera frame from the image.
  int tf_checked = 0;
  for (const ros::Time& stamp : recorder.stamps("/odometry")) {
    if (stamp < first_output + ros::Duration(0.5)) continue;
    geometry_msgs::TransformStamped transform;
    ASSERT_NO_THROW(transform = tf_buffer.lookupTransform("odom", "base_link", stamp)) << stamp;
    EXPECT_EQ(transform.header.stamp, stamp);
    ++tf_checked;
  }
  EXPECT_GT(tf_checked, 30);
  const std_msgs::Header odometry_header = recorder.lastHeader("/odometry");
  EXPECT_EQ(odometry_header.frame_id, "odom");
  EXPECT_EQ(recorder.lastHeader("/tracking_status").frame_id, "camera_optical_frame");
  EXPECT_EQ(recorder.lastHeader("/edge_frame").frame_id, "camera_optical_frame");
  EXPECT_TRUE(tf_buffer.canTransform("base_link", "camera_optical_frame", ros::Time(0)));

  ASSERT_TRUE(cloud);
  EXPECT_EQ(cloud->header.frame_id, "odom");
  std::vector<std::string> fields;
  for (const auto& f : cloud->fields) fields.push_back(f.name);
  EXPECT_EQ(fields, (std::vector<std::string>{"x", "y", "z", "label", "rgb"}));
  EXPECT_GT(cloud->width * cloud->height, 0u);

  // 4. The running graph saves its trajectory (every frame, flagged) and its map.
  const std::string saved = ::testing::TempDir() + "/graph_flow_saved";
  SaveFiles save;
  save.request.directory = saved;
  ASSERT_TRUE(ros::service::call("/tracking/save_trajectory", save));
  EXPECT_TRUE(save.response.success) << save.response.message;
  EXPECT_EQ(save.response.files.size(), 3u);
  const auto data_lines = [](const std::string& path) {
    std::ifstream in(path);
    int count = 0;
    for (std::string line; std::getline(in, line);) count += !line.empty() && line[0] != '#';
    return count;
  };
  const int poses = data_lines(saved + "/poses_kitti.txt");
  EXPECT_GT(poses, 40);
  EXPECT_EQ(data_lines(saved + "/poses_flags.txt"), poses);
  EXPECT_EQ(data_lines(saved + "/poses_tum.txt"), poses);
  SaveFiles save_map;
  save_map.request.directory = saved;
  ASSERT_TRUE(ros::service::call("/mapping/save_map", save_map));
  EXPECT_TRUE(save_map.response.success) << save_map.response.message;
  std::ifstream ply(saved + "/semantic_edge_map.ply");
  std::string line;
  while (std::getline(ply, line) && line.rfind("element vertex", 0) != 0) {}
  EXPECT_GT(std::stoi(line.substr(std::string("element vertex ").size())), 0) << "the saved map has no point";

  // 5. Every nodelet reports its health on /diagnostics: inputs at the camera's rate, none lost.
  std::lock_guard<std::mutex> lock(status_mutex);
  for (const std::string name : {"/edge_intake", "/nearest_neighbor_field", "/tracking", "/mapping"}) {
    ASSERT_TRUE(diagnostics.count(name)) << "no diagnostics from " << name;
    const diagnostic_msgs::DiagnosticStatus& status = diagnostics[name];
    std::map<std::string, std::string> values;
    for (const auto& pair : status.values) values[pair.key] = pair.value;
    EXPECT_LE(status.level, diagnostic_msgs::DiagnosticStatus::WARN) << name << ": " << status.message;
    EXPECT_NEAR(std::stod(values["input rate (Hz)"]), 10.0, 3.0) << name;
    EXPECT_EQ(values["inputs lost in queues (total)"], "0") << name;
    EXPECT_TRUE(values.count("processing time median (ms)")) << name;
    if (name == "/tracking") {
      EXPECT_EQ(values["tracking state"], "tracking");
      EXPECT_EQ(values["scale state"], "arbitrary");
    }
  }
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "graph_flow_test");
  return RUN_ALL_TESTS();
}
