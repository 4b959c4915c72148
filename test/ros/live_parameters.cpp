// rostest: the live parameters (dynamic_reconfigure under each nodelet's ~live/) start from the
// config and change the running graph: a smaller edge budget samples fewer edges from the next
// frame, another field kind is built from the next frame and tracking starts a new map on it, a
// lower keyframe flow makes keyframes more often; the odometry keeps tracking throughout.
#include <map>
#include <mutex>
#include <set>

#include <dynamic_reconfigure/Reconfigure.h>
#include <gtest/gtest.h>
#include <ros/ros.h>

#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackingStatus.h"

namespace semantic_edge_vo {
namespace {

bool setLive(const std::string& nodelet, const dynamic_reconfigure::Config& values, dynamic_reconfigure::Config* now) {
  dynamic_reconfigure::Reconfigure call;
  call.request.config = values;
  if (!ros::service::call(nodelet + "/live/set_parameters", call)) return false;
  *now = call.response.config;
  return true;
}

dynamic_reconfigure::Config oneInt(const std::string& name, int value) {
  dynamic_reconfigure::Config config;
  dynamic_reconfigure::IntParameter parameter;
  parameter.name = name;
  parameter.value = value;
  config.ints.push_back(parameter);
  return config;
}

class LiveParameters : public ::testing::Test {
 protected:
  void SetUp() override {
    edge_subscriber_ = node_.subscribe<SemanticEdgeFrame>("/edge_frame", 20, [this](const SemanticEdgeFrameConstPtr& f) {
      std::lock_guard<std::mutex> lock(mutex_);
      sampled_edges_ = f->sampled_edges.size();
    });
    field_subscriber_ = node_.subscribe<NearestNeighborField>("/nn_field", 20, [this](const NearestNeighborFieldConstPtr& f) {
      std::lock_guard<std::mutex> lock(mutex_);
      field_kind_ = f->kind;
    });
    status_subscriber_ = node_.subscribe<TrackingStatus>("/tracking_status", 100, [this](const TrackingStatusConstPtr& s) {
      std::lock_guard<std::mutex> lock(mutex_);
      statuses_.push_back(*s);
    });
    spinner_.start();
  }

  // The callbacks use this fixture's members: no callback may run once they start to go.
  void TearDown() override {
    edge_subscriber_.shutdown();
    field_subscriber_.shutdown();
    status_subscriber_.shutdown();
    spinner_.stop();
  }

  /// The tracking statuses of the next `seconds`.
  std::vector<TrackingStatus> statusesFor(double seconds) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      statuses_.clear();
    }
    ros::WallDuration(seconds).sleep();
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_;
  }
  static int tracked(const std::vector<TrackingStatus>& statuses) {
    int count = 0;
    for (const TrackingStatus& s : statuses) count += s.state == TrackingStatus::TRACKING;
    return count;
  }
  static int keyframes(const std::vector<TrackingStatus>& statuses) {
    std::set<std::uint32_t> ids;
    for (const TrackingStatus& s : statuses)
      if (s.state == TrackingStatus::TRACKING) ids.insert(s.keyframe_id);
    return static_cast<int>(ids.size());
  }

  ros::NodeHandle node_;
  ros::AsyncSpinner spinner_{2};
  ros::Subscriber edge_subscriber_, field_subscriber_, status_subscriber_;
  std::mutex mutex_;
  std::size_t sampled_edges_ = 0;
  std::string field_kind_;
  std::vector<TrackingStatus> statuses_;
};

TEST_F(LiveParameters, StartFromTheConfigAndChangeTheRunningGraph) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (tracked(statusesFor(0.5)) == 0 && ros::WallTime::now() < deadline) {}
  const std::vector<TrackingStatus> before = statusesFor(6.0);
  ASSERT_GT(tracked(before), 40) << "the graph must track before the change";

  // The server starts from the config (shipped: 3000 edge points, keyframe flow 60 px).
  dynamic_reconfigure::Config now;
  ASSERT_TRUE(setLive("/edge_intake", oneInt("max_edge_points", 500), &now));
  ASSERT_EQ(now.ints.size(), 2u);
  std::map<std::string, int> ints;
  for (const auto& p : now.ints) ints[p.name] = p.value;
  EXPECT_EQ(ints["max_edge_points"], 500);
  EXPECT_EQ(ints["min_support_points"], 1000) << "untouched values stay the config's";
  ros::WallDuration(1.0).sleep();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_LE(sampled_edges_, 500u) << "the edge budget applies from the next frame";
    EXPECT_GT(sampled_edges_, 100u);
  }

  // Another field kind: built from the next frame; tracking starts a new map and tracks again.
  dynamic_reconfigure::Config kind;
  dynamic_reconfigure::StrParameter annf;
  annf.name = "kind";
  annf.value = "annf";
  kind.strs.push_back(annf);
  ASSERT_TRUE(setLive("/nearest_neighbor_field", kind, &now));
  ros::WallDuration(1.0).sleep();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    EXPECT_EQ(field_kind_, "annf");
  }

  // Keyframes more often with a lower keyframe flow; tracking goes on on the new map.
  dynamic_reconfigure::Config flow;
  dynamic_reconfigure::DoubleParameter low;
  low.name = "keyframe_flow";
  low.value = 15.0;
  flow.doubles.push_back(low);
  ASSERT_TRUE(setLive("/tracking", flow, &now));
  ros::WallDuration(3.0).sleep();  // the new map initialises
  const std::vector<TrackingStatus> after = statusesFor(6.0);
  std::printf("live_parameters: before: %d frames tracked on %d keyframes; after: %d on %d\n", tracked(before), keyframes(before),
              tracked(after), keyframes(after));
  EXPECT_GT(tracked(after), 40) << "the odometry must track on the new field kind";
  EXPECT_GT(keyframes(after), keyframes(before)) << "a lower keyframe flow makes more keyframes";
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "live_parameters_test");
  return RUN_ALL_TESTS();
}
