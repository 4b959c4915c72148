// rostest: each kind of bad input is refused with a named error on /rosout, and the good frames
// that follow still flow through every stage to tracking. A stream whose stamps start over far
// earlier (a bag played again) is not refused: the graph starts over.
#include <functional>
#include <mutex>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackingStatus.h"
#include "semantic_edge_vo/support/test_pattern.h"

namespace semantic_edge_vo {
namespace {

constexpr int kWidth = 320, kHeight = 240;

struct Frame {
  sensor_msgs::Image image;
  sensor_msgs::CameraInfo info;
};

Frame goodFrame(const ros::Time& stamp, int index) {
  Frame frame;
  frame.image.header.stamp = stamp;
  frame.image.header.frame_id = "camera_optical_frame";
  frame.image.width = kWidth;
  frame.image.height = kHeight;
  frame.image.encoding = "mono8";
  frame.image.step = kWidth;
  const cv::Mat pattern = renderTestPattern(index, kWidth, kHeight);
  frame.image.data.assign(pattern.data, pattern.data + pattern.total());
  frame.info.header = frame.image.header;
  frame.info.width = kWidth;
  frame.info.height = kHeight;
  frame.info.K = {300, 0, 160, 0, 300, 120, 0, 0, 1};
  frame.info.P = {300, 0, 160, 0, 0, 300, 120, 0, 0, 0, 1, 0};
  return frame;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    image_publisher_ = node_.advertise<sensor_msgs::Image>("/camera/image_rect", 10);
    info_publisher_ = node_.advertise<sensor_msgs::CameraInfo>("/camera/camera_info", 10);
    log_subscriber_ = node_.subscribe<rosgraph_msgs::Log>("/rosout", 100, [this](const rosgraph_msgs::LogConstPtr& log) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (log->level >= rosgraph_msgs::Log::ERROR) errors_.push_back(log->msg);
      else if (log->level == rosgraph_msgs::Log::WARN) warnings_.push_back(log->file + ": " + log->msg);
    });
    // Every processed frame gets a status (a 2D test pattern never initialises a monocular odometry,
    // so there is no pose to wait for).
    status_subscriber_ = node_.subscribe<TrackingStatus>("/tracking_status", 100, [this](const TrackingStatusConstPtr& s) {
      std::lock_guard<std::mutex> lock(mutex_);
      status_stamps_.insert(s->header.stamp);
    });
    spinner_.start();
    // Wait until the intake subscribes to both topics.
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
    while ((image_publisher_.getNumSubscribers() == 0 || info_publisher_.getNumSubscribers() == 0) &&
           ros::WallTime::now() < deadline)
      ros::WallDuration(0.1).sleep();
    ASSERT_GT(image_publisher_.getNumSubscribers(), 0u) << "EdgeIntake never subscribed";
    ros::WallDuration(1.0).sleep();
    if (stamp_.isZero()) stamp_ = ros::Time::now();  // the graph lives on from test to test: stamps too
  }

  void publish(const Frame& frame) {
    image_publisher_.publish(frame.image);
    info_publisher_.publish(frame.info);
    ros::WallDuration(0.15).sleep();
  }
  ros::Time nextStamp() { return stamp_ += ros::Duration(0.1); }

  /// Sends a good frame (its camera_info described otherwise by `describe`, when given) and waits
  /// for its tracking status.
  bool goodFrameFlows(const std::function<void(Frame*)>& describe = nullptr) {
    const ros::Time stamp = nextStamp();
    Frame frame = goodFrame(stamp, ++index_);
    if (describe) describe(&frame);
    publish(frame);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (status_stamps_.count(stamp)) return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

  /// Waits for an error log naming `reason`.
  bool errorLogged(const std::string& reason) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const std::string& message : errors_)
          if (message.find(reason) != std::string::npos && message.find("dropped") != std::string::npos) return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

  /// Waits for a warning logged from a source file whose name contains `source` (the nodelets share
  /// one manager node) with text containing `text`.
  bool warningLogged(const std::string& source, const std::string& text) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const std::string& message : warnings_)
          if (message.find(source) != std::string::npos && message.find(text) != std::string::npos) return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }

  ros::NodeHandle node_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher image_publisher_, info_publisher_;
  ros::Subscriber log_subscriber_, status_subscriber_;
  std::mutex mutex_;
  std::vector<std::string> errors_, warnings_;  ///< warnings as "source file: text"
  std::set<ros::Time> status_stamps_;
  static ros::Time stamp_;
  int index_ = 0;
};

ros::Time BadInput::stamp_;

TEST_F(BadInput, EachIsRefusedByNameAndGoodFramesStillFlow) {
  ASSERT_TRUE(goodFrameFlows()) << "a good frame must flow before the bad ones";

  struct Case {
    std::string reason;
    std::function<void(Frame*)> spoil;
  };
  const std::vector<Case> cases = {
      {"unsupported_encoding", [](Frame* f) { f->image.encoding = "32FC1"; }},
      {"size_mismatch", [](Frame* f) { f->info.width = kWidth / 2; }},
      {"invalid_camera_info", [](Frame* f) {
         f->info.K.fill(0.0);
         f->info.P.fill(0.0);
       }},
      {"empty_image", [](Frame* f) {
         f->image.width = f->image.height = f->image.step = 0;
         f->image.data.clear();
         f->info.width = f->info.height = 0;
       }},
      {"malformed_image", [](Frame* f) { f->image.data.resize(100); }},
  };
  for (const Case& c : cases) {
    Frame frame = goodFrame(nextStamp(), ++index_);
    c.spoil(&frame);
    publish(frame);
    EXPECT_TRUE(errorLogged(c.reason)) << "no named error for " << c.reason;
    EXPECT_TRUE(goodFrameFlows()) << "good frames stopped flowing after " << c.reason;
  }

  // Not bad: a camera that bins 2x2 calibrated at full resolution (REP-104) describes this image too.
  EXPECT_TRUE(goodFrameFlows([](Frame* f) {
    f->info.width = 2 * kWidth;
    f->info.height = 2 * kHeight;
    f->info.binning_x = f->info.binning_y = 2;
    f->info.K = {600, 0, 320, 0, 600, 240, 0, 0, 1};
    f->info.P = {600, 0, 320, 0, 0, 600, 240, 0, 0, 0, 1, 0};
  })) << "a binned camera's frame was refused";

  // Stamps going backwards: a frame older than the last accepted one.
  publish(goodFrame(stamp_ - ros::Duration(0.05), ++index_));
  EXPECT_TRUE(errorLogged("stamp_not_increasing"));
  EXPECT_TRUE(goodFrameFlows()) << "good frames stopped flowing after a backwards stamp";
}

TEST_F(BadInput, AStreamThatStartsOverEarlierStartsTheGraphOver) {
  ASSERT_TRUE(goodFrameFlows());
  // A bag played again: its stamps start over, far before the last frame's.
  stamp_ -= ros::Duration(30.0);
  EXPECT_TRUE(goodFrameFlows()) << "the frames of a second pass must flow, not be refused as out of order";
  EXPECT_TRUE(warningLogged("edge_intake_nodelet", "jumped back")) << "the intake must say that its input started over";
  EXPECT_TRUE(warningLogged("tracking_nodelet", "the odometry starts over")) << "the tracking must start over";
  EXPECT_TRUE(goodFrameFlows());
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bad_input_test");
  return RUN_ALL_TESTS();
}
