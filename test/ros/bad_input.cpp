// rostest: each kind of bad input is refused with a named error on /rosout, and the good frames
// that follow still flow through every stage to tracking. A stream whose stamps start over far
// earlier (a bag played again) is not refused: the graph starts over; a new image size starts the
// odometry over; a 30 s gap is no error. The watchdog reports a silent camera on /diagnostics, and
// a burst at five times the camera's rate is bounded, every frame answered or counted as dropped.
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <set>

#include <diagnostic_msgs/DiagnosticArray.h>
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

Frame goodFrame(const ros::Time& stamp, int index, int width = kWidth, int height = kHeight) {
  Frame frame;
  frame.image.header.stamp = stamp;
  frame.image.header.frame_id = "camera_optical_frame";
  frame.image.width = width;
  frame.image.height = height;
  frame.image.encoding = "mono8";
  frame.image.step = width;
  const cv::Mat pattern = renderTestPattern(index, width, height);
  frame.image.data.assign(pattern.data, pattern.data + pattern.total());
  frame.info.header = frame.image.header;
  frame.info.width = width;
  frame.info.height = height;
  const double cx = width / 2.0, cy = height / 2.0;
  frame.info.K = {300, 0, cx, 0, 300, cy, 0, 0, 1};
  frame.info.P = {300, 0, cx, 0, 0, 300, cy, 0, 0, 0, 1, 0};
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
    diagnostics_subscriber_ =
        node_.subscribe<diagnostic_msgs::DiagnosticArray>("/diagnostics", 100, [this](const diagnostic_msgs::DiagnosticArrayConstPtr& a) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& status : a->status) diagnostics_[status.name] = status;
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

  // The callbacks use this fixture's members: no callback may run once they start to go.
  void TearDown() override {
    log_subscriber_.shutdown();
    status_subscriber_.shutdown();
    diagnostics_subscriber_.shutdown();
    spinner_.stop();
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

  /// The latest diagnostics of a nodelet, after the next publication (they come once a second).
  diagnostic_msgs::DiagnosticStatus freshDiagnostics(const std::string& name) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      diagnostics_.erase(name);
    }
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(3.0);
    while (ros::WallTime::now() < deadline) {
      ros::WallDuration(0.05).sleep();
      std::lock_guard<std::mutex> lock(mutex_);
      if (diagnostics_.count(name)) return diagnostics_[name];
    }
    return diagnostic_msgs::DiagnosticStatus();
  }
  static long valueOf(const diagnostic_msgs::DiagnosticStatus& status, const std::string& key) {
    for (const auto& pair : status.values)
      if (pair.key == key) return std::stol(pair.value);
    return -1;
  }

  ros::NodeHandle node_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher image_publisher_, info_publisher_;
  ros::Subscriber log_subscriber_, status_subscriber_, diagnostics_subscriber_;
  std::map<std::string, diagnostic_msgs::DiagnosticStatus> diagnostics_;
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
      {"invalid_camera_info", [](Frame* f) { f->info.K[0] = f->info.P[0] = std::nan(""); }},
      {"invalid_camera_info", [](Frame* f) { f->info.K[4] = f->info.P[5] = -300.0; }},
      // Stamped 100 ms from its image: no camera_info within camera_info_tolerance.
      {"no_camera_info", [](Frame* f) { f->info.header.stamp += ros::Duration(0.1); }},
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

TEST_F(BadInput, CameraInfoStampedALittleApartIsPairedWithItsImage) {
  ASSERT_TRUE(goodFrameFlows());
  EXPECT_TRUE(goodFrameFlows([](Frame* f) { f->info.header.stamp += ros::Duration(0.002); }))
      << "a camera_info 2 ms after its image is within camera_info_tolerance";
}

TEST_F(BadInput, AChangeOfImageSizeStartsTheOdometryOver) {
  ASSERT_TRUE(goodFrameFlows());
  const ros::Time stamp = nextStamp();
  publish(goodFrame(stamp, ++index_, kWidth + 64, kHeight + 48));
  EXPECT_TRUE(warningLogged("tracking_nodelet", "the image size changed")) << "the tracking must start over on a new size";
  EXPECT_TRUE(goodFrameFlows()) << "frames of the first size must flow again";
}

TEST_F(BadInput, AThirtySecondGapInTheStampsIsNotAnError) {
  ASSERT_TRUE(goodFrameFlows());
  stamp_ += ros::Duration(30.0);
  EXPECT_TRUE(goodFrameFlows()) << "a frame 30 s after the previous one must flow";
  EXPECT_TRUE(goodFrameFlows());
}

TEST_F(BadInput, TheWatchdogReportsWhenImagesStop) {
  ASSERT_TRUE(goodFrameFlows());
  ros::WallDuration(2.5).sleep();  // bad_input.test: edge_intake/image_timeout 1 s
  const diagnostic_msgs::DiagnosticStatus silent = freshDiagnostics("/edge_intake");
  EXPECT_EQ(silent.level, diagnostic_msgs::DiagnosticStatus::ERROR) << silent.message;
  EXPECT_NE(silent.message.find("no image on /camera/image_rect"), std::string::npos) << silent.message;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    bool logged = false;
    for (const std::string& message : errors_) logged |= message.find("watchdog: no image") != std::string::npos;
    EXPECT_TRUE(logged) << "the watchdog must also log an error";
  }
  ASSERT_TRUE(goodFrameFlows());
  const diagnostic_msgs::DiagnosticStatus again = freshDiagnostics("/edge_intake");
  EXPECT_LT(again.level, diagnostic_msgs::DiagnosticStatus::ERROR) << again.message;
}

TEST_F(BadInput, FiveTimesTheCameraRateIsBoundedAndEveryFrameAccountedFor) {
  ASSERT_TRUE(goodFrameFlows());
  const auto accounted = [this] {
    long total = 0;
    for (const std::string name : {"/edge_intake", "/tracking"}) {
      const diagnostic_msgs::DiagnosticStatus status = freshDiagnostics(name);
      const long lost = valueOf(status, "inputs lost in queues (total)"), dropped = valueOf(status, "inputs dropped (total)");
      std::printf("bad_input: %s: %ld lost in queues, %ld dropped in all\n", name.c_str(), lost, dropped);
      total += lost + dropped;
    }
    return total;
  };
  const long before = accounted();
  stamp_ += ros::Duration(1000.0);  // stamps no earlier test used (one went 30 s back)
  const int kBurst = 100;
  std::set<ros::Time> burst;
  for (int i = 0; i < kBurst; ++i) {  // 50 Hz for 2 s: five times a 10 Hz camera
    const Frame frame = goodFrame(nextStamp(), ++index_);
    burst.insert(frame.image.header.stamp);
    image_publisher_.publish(frame.image);
    info_publisher_.publish(frame.info);
    ros::WallDuration(0.02).sleep();
  }
  ros::WallDuration(2.0).sleep();
  const long lost = accounted() - before;
  long answered = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const ros::Time& stamp : burst) answered += status_stamps_.count(stamp);
  }
  std::printf("bad_input: a burst of %d frames at 50 Hz: %ld answered, %ld counted as lost or dropped\n", kBurst, answered, lost);
  EXPECT_EQ(answered + lost, kBurst) << "every frame is answered or counted in the diagnostics";
  EXPECT_TRUE(goodFrameFlows()) << "the graph must keep running after the burst";
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bad_input_test");
  return RUN_ALL_TESTS();
}
