// rostest: the fused intake pairs class maps by stamp, waits for late ones, falls back to Canny on
// missing ones, refuses bad class maps by name and keeps running; compressed images are taken; the
// semantic_edges intake reads the bitmask form; a rectifying fused intake undistorts a
// barrel-distorted camera's image and class map into its P camera; the Segmenter publishes ENet class probabilities (skipped without the model).
#include <filesystem>
#include <functional>
#include <mutex>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Float32.h>

#include "semantic_edge_vo/SemanticEdgeFrame.h"

namespace semantic_edge_vo {
namespace {

constexpr int kWidth = 320, kHeight = 240, kClasses = 19, kRoad = 0, kCar = 13, kBoundary = 150;
const std::string kModel = std::string(SEVO_SHARED_DIR) + "/models/enet_cityscapes/model-best.opencv.net";
const std::string kColorFrame = std::string(SEVO_SHARED_DIR) + "/data/kitti_odometry/color_frames/kitti06-12-color.png";

/// Dark road left of column kBoundary, bright car right of it.
cv::Mat boundaryImage() {
  cv::Mat gray(kHeight, kWidth, CV_8U, cv::Scalar(60));
  gray.colRange(kBoundary, kWidth).setTo(190);
  return gray;
}

sensor_msgs::Image imageMsg(const cv::Mat& mat, const std::string& encoding, const ros::Time& stamp) {
  sensor_msgs::Image msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = "camera_optical_frame";
  msg.width = static_cast<std::uint32_t>(mat.cols);
  msg.height = static_cast<std::uint32_t>(mat.rows);
  msg.encoding = encoding;
  msg.step = static_cast<std::uint32_t>(mat.cols * mat.elemSize());
  msg.data.assign(mat.data, mat.data + mat.total() * mat.elemSize());
  return msg;
}

sensor_msgs::CameraInfo infoMsg(const ros::Time& stamp) {
  sensor_msgs::CameraInfo info;
  info.header.stamp = stamp;
  info.header.frame_id = "camera_optical_frame";
  info.width = kWidth;
  info.height = kHeight;
  info.K = {300, 0, 160, 0, 300, 120, 0, 0, 1};
  info.P = {300, 0, 160, 0, 0, 300, 120, 0, 0, 0, 1, 0};
  return info;
}

/// Road 0.9 left of `boundary`, car 0.8 right of it, the rest spread thinly.
cv::Mat probabilities(int classes = kClasses, int boundary = kBoundary) {
  cv::Mat p(kHeight, kWidth, CV_32FC(classes));
  p.reshape(1).setTo(0.1 / (classes - 1));  // Scalar fills take at most 4 channels
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) p.ptr<float>(y)[x * classes + (x < boundary ? kRoad : kCar)] = x < boundary ? 0.9f : 0.8f;
  return p;
}

class SemanticIntake : public ::testing::Test {
 protected:
  void SetUp() override {
    image_publisher_ = node_.advertise<sensor_msgs::Image>("/camera/image_rect", 10);
    info_publisher_ = node_.advertise<sensor_msgs::CameraInfo>("/camera/camera_info", 10);
    class_publisher_ = node_.advertise<sensor_msgs::Image>("/class_probabilities", 10);
    subscribers_.push_back(node_.subscribe<SemanticEdgeFrame>("/edge_frame", 20, [this](const SemanticEdgeFrameConstPtr& f) {
      std::lock_guard<std::mutex> lock(mutex_);
      frames_[f->header.stamp] = f;
    }));
    subscribers_.push_back(node_.subscribe<rosgraph_msgs::Log>("/rosout", 100, [this](const rosgraph_msgs::LogConstPtr& log) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (log->level >= rosgraph_msgs::Log::WARN) logs_.push_back(log->msg);
    }));
    spinner_.start();
    waitFor([&] { return image_publisher_.getNumSubscribers() > 0 && class_publisher_.getNumSubscribers() > 0; }, 20.0);
    ASSERT_GT(class_publisher_.getNumSubscribers(), 0u) << "EdgeIntake never subscribed to class_probabilities";
    ros::WallDuration(1.0).sleep();
    stamp_ = ros::Time::now();
  }

  // The callbacks use this fixture's members: no callback may run once they start to go.
  void TearDown() override {
    for (ros::Subscriber& subscriber : subscribers_) subscriber.shutdown();
    spinner_.stop();
  }

  /// Keeps the latest frame published on `topic` in `*frame` (guarded by mutex_).
  ros::Subscriber latestFrame(const std::string& topic, SemanticEdgeFrameConstPtr* frame) {
    return node_.subscribe<SemanticEdgeFrame>(topic, 5, [this, frame](const SemanticEdgeFrameConstPtr& f) {
      std::lock_guard<std::mutex> lock(mutex_);
      *frame = f;
    });
  }

  /// Plays a straight road/car boundary near the left border of a barrel-distorted raw image (and, with
  /// `with_classes`, its class map, in the same raw geometry) into the rectifying intake of `camera`,
  /// and checks that its frame describes the P camera and that the edges lie on the boundary's
  /// undistorted curve (with both classes when the class map came along).
  void expectRectifiedBoundary(const std::string& camera, bool with_classes) {
    ros::Publisher images = node_.advertise<sensor_msgs::Image>(camera + "/image", 5);
    ros::Publisher info = node_.advertise<sensor_msgs::CameraInfo>(camera + "/camera_info", 5);
    ros::Publisher classes = node_.advertise<sensor_msgs::Image>(camera + "/class_probabilities", 5);
    SemanticEdgeFrameConstPtr frame;
    const ros::Subscriber frames = latestFrame(camera + "/edge_frame", &frame);
    ASSERT_TRUE(waitFor([&] { return images.getNumSubscribers() > 0 && (!with_classes || classes.getNumSubscribers() > 0); }, 10.0));
    ros::WallDuration(0.5).sleep();
    constexpr int kRawColumn = 40;
    cv::Mat raw(kHeight, kWidth, CV_8U, cv::Scalar(60));
    raw.colRange(kRawColumn, kWidth).setTo(190);
    const ros::Time stamp = ros::Time::now();
    sensor_msgs::CameraInfo calibration = infoMsg(stamp);
    calibration.distortion_model = "plumb_bob";
    calibration.D = {-0.30, 0.10, 0.0, 0.0, 0.0};
    calibration.P = {280, 0, 165, 0, 0, 280, 118, 0, 0, 0, 1, 0};
    images.publish(imageMsg(raw, "mono8", stamp));
    info.publish(calibration);
    if (with_classes) classes.publish(imageMsg(probabilities(kClasses, kRawColumn), "32FC19", stamp));
    ASSERT_TRUE(waitFor([&] { return frame != nullptr; })) << "no frame from the rectifying intake on " << camera;
    EXPECT_EQ(frame->intake_mode, with_classes ? "fused" : "canny");
    EXPECT_EQ(frame->camera_info.K[0], 280.0) << "the frame describes the rectified (P) camera";
    EXPECT_EQ(frame->camera_info.K[2], 165.0);
    for (double d : frame->camera_info.D) EXPECT_EQ(d, 0.0);

    // Where the raw boundary (between columns 39 and 40) lands in the P camera, row by row.
    std::vector<cv::Point2f> boundary, rectified;
    for (int y = 0; y < kHeight; ++y) boundary.emplace_back(kRawColumn - 0.5f, static_cast<float>(y));
    const cv::Matx33d K(calibration.K.data()), P(280, 0, 165, 0, 280, 118, 0, 0, 1);
    cv::undistortPoints(boundary, rectified, K, cv::Mat(calibration.D, true), cv::Matx33d::eye(), P);
    float low = 1e9f, high = -1e9f;
    for (const cv::Point2f& p : rectified)
      if (p.y >= 0 && p.y < kHeight) low = std::min(low, p.x), high = std::max(high, p.x);
    ASSERT_GT(high - low, 3.0f) << "the test distortion must bow the line";
    const std::uint32_t both = (1u << kRoad) | (1u << kCar);
    std::size_t near = 0, on_boundary = 0, with_both = 0;
    for (std::size_t i = 0; i < frame->edge_u.size(); ++i) {
      if (frame->edge_u[i] > high + 10.0f) continue;  // the rectified image's border, not the boundary
      ++on_boundary;
      with_both += frame->edge_class_mask[i] == both;
      float best = 1e9f;
      for (const cv::Point2f& p : rectified) best = std::min(best, std::hypot(p.x - frame->edge_u[i], p.y - frame->edge_v[i]));
      near += best < 1.0f;
    }
    EXPECT_GT(on_boundary, static_cast<std::size_t>(kHeight / 2));
    EXPECT_GT(near, on_boundary * 9 / 10) << "the edges must lie on the undistorted boundary";
    if (with_classes) EXPECT_GT(with_both, on_boundary * 9 / 10) << "the rectified class map must give the boundary both classes";
  }

  bool waitFor(const std::function<bool()>& condition, double seconds = 5.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (condition()) return true;
      }
      ros::WallDuration(0.05).sleep();
    }
    return false;
  }
  SemanticEdgeFrameConstPtr frameAt(const ros::Time& stamp, double seconds = 5.0) {
    SemanticEdgeFrameConstPtr frame;
    waitFor([&] { return frames_.count(stamp) && (frame = frames_[stamp]); }, seconds);
    return frame;
  }
  bool logged(const std::string& a, const std::string& b) {
    return waitFor([&] {
      for (const std::string& m : logs_)
        if (m.find(a) != std::string::npos && m.find(b) != std::string::npos) return true;
      return false;
    });
  }
  /// Image and camera_info at a new stamp, then the class map (if any) after `delay` s.
  ros::Time send(const sensor_msgs::Image* classes, double delay = 0.0) {
    const ros::Time stamp = stamp_ += ros::Duration(0.1);
    image_publisher_.publish(imageMsg(boundaryImage(), "mono8", stamp));
    info_publisher_.publish(infoMsg(stamp));
    if (classes) {
      ros::WallDuration(delay).sleep();
      sensor_msgs::Image msg = *classes;
      msg.header.stamp = stamp;
      class_publisher_.publish(msg);
    }
    return stamp;
  }

  ros::NodeHandle node_;
  ros::AsyncSpinner spinner_{2};
  ros::Publisher image_publisher_, info_publisher_, class_publisher_;
  std::vector<ros::Subscriber> subscribers_;
  std::mutex mutex_;
  std::map<ros::Time, SemanticEdgeFrameConstPtr> frames_;
  std::vector<std::string> logs_;
  ros::Time stamp_;
};

TEST_F(SemanticIntake, FusedPairingFallbackAndBadClassMaps) {
  const sensor_msgs::Image good = imageMsg(probabilities(), "32FC19", ros::Time());
  for (double delay : {0.0, 0.15}) {  // on time, and late within class_wait
    const SemanticEdgeFrameConstPtr frame = frameAt(send(&good, delay));
    ASSERT_TRUE(frame) << "no fused frame (class map " << delay << " s late)";
    EXPECT_EQ(frame->intake_mode, "fused");
    ASSERT_EQ(frame->class_names.size(), static_cast<std::size_t>(kClasses));
    EXPECT_EQ(frame->class_names[kCar], "car");
    std::size_t both = 0;
    for (std::uint32_t mask : frame->edge_class_mask) both += mask == ((1u << kRoad) | (1u << kCar));
    EXPECT_GT(both, static_cast<std::size_t>(kHeight / 2)) << "boundary edges must carry road and car";
  }
  // No class map: after class_wait, Canny edges of no class (tracking matches them as ANNF does).
  const SemanticEdgeFrameConstPtr fallback = frameAt(send(nullptr));
  ASSERT_TRUE(fallback) << "no fallback frame";
  EXPECT_EQ(fallback->intake_mode, "canny");
  EXPECT_EQ(fallback->class_map_age, -1.0f);
  ASSERT_FALSE(fallback->edge_class_mask.empty());
  EXPECT_EQ(fallback->edge_class_mask[0], 0u);
  EXPECT_TRUE(logged("no class map", "Canny"));

  struct Case {
    std::string reason;
    sensor_msgs::Image classes;
  };
  cv::Mat nan_map = probabilities(), negative_map = probabilities();
  nan_map.ptr<float>(5)[7] = std::nanf("");
  negative_map.ptr<float>(100)[300] = -0.5f;
  cv::Mat small;
  cv::resize(probabilities(), small, cv::Size(kWidth / 2, kHeight / 2), 0, 0, cv::INTER_NEAREST);
  std::vector<Case> cases = {{"channel_count_mismatch", imageMsg(probabilities(18), "32FC18", ros::Time())},
                             {"size_mismatch", imageMsg(small, "32FC19", ros::Time())},
                             {"invalid_probability", imageMsg(nan_map, "32FC19", ros::Time())},
                             {"invalid_probability", imageMsg(negative_map, "32FC19", ros::Time())},
                             {"unsupported_encoding", imageMsg(probabilities(), "32FC19", ros::Time())}};
  cases.back().classes.encoding = "64FC19";
  for (const Case& c : cases) {
    const ros::Time stamp = send(&c.classes);
    EXPECT_TRUE(logged("dropped class map: " + c.reason, "")) << "no named error for " << c.reason;
    EXPECT_FALSE(frameAt(stamp, 0.5)) << "a frame with a bad class map must be dropped (" << c.reason << ")";
    EXPECT_TRUE(frameAt(send(&good))) << "good frames stopped flowing after " << c.reason;
  }
  // 8-bit probabilities are taken as well.
  cv::Mat bytes;
  probabilities().convertTo(bytes, CV_8U, 255.0);
  const sensor_msgs::Image good8 = imageMsg(bytes, "8UC19", ros::Time());
  const SemanticEdgeFrameConstPtr frame8 = frameAt(send(&good8));
  ASSERT_TRUE(frame8);
  EXPECT_EQ(frame8->intake_mode, "fused");
}

TEST_F(SemanticIntake, CompressedImagesAreDecoded) {
  ros::Publisher compressed = node_.advertise<sensor_msgs::CompressedImage>("/cam2/image/compressed", 5);
  ros::Publisher info = node_.advertise<sensor_msgs::CameraInfo>("/cam2/camera_info", 5);
  SemanticEdgeFrameConstPtr frame;
  const ros::Subscriber frames = latestFrame("/cam2/edge_frame", &frame);
  ASSERT_TRUE(waitFor([&] { return compressed.getNumSubscribers() > 0 && info.getNumSubscribers() > 0; }, 10.0));
  ros::WallDuration(0.5).sleep();
  sensor_msgs::CompressedImage msg;
  msg.header.stamp = ros::Time::now();
  msg.format = "mono8; png compressed";
  cv::imencode(".png", boundaryImage(), msg.data);
  compressed.publish(msg);
  info.publish(infoMsg(msg.header.stamp));
  ASSERT_TRUE(waitFor([&] { return frame != nullptr; })) << "no frame from the compressed intake";
  EXPECT_EQ(frame->image.width, static_cast<std::uint32_t>(kWidth));
  EXPECT_GT(frame->edge_u.size(), static_cast<std::size_t>(kHeight / 2));
}

TEST_F(SemanticIntake, SemanticEdgesFromTheBitmaskForm) {
  ros::Publisher images = node_.advertise<sensor_msgs::Image>("/cam3/image", 5);
  ros::Publisher info = node_.advertise<sensor_msgs::CameraInfo>("/cam3/camera_info", 5);
  ros::Publisher bitmasks = node_.advertise<sensor_msgs::Image>("/cam3/class_edge_probabilities", 5);
  SemanticEdgeFrameConstPtr frame;
  const ros::Subscriber frames = latestFrame("/cam3/edge_frame", &frame);
  ASSERT_TRUE(waitFor([&] { return images.getNumSubscribers() > 0 && bitmasks.getNumSubscribers() > 0; }, 10.0));
  ros::WallDuration(0.5).sleep();
  // Road and car bits on a 3-pixel band at the boundary, edge strength peaking on it.
  const std::uint32_t bits = (1u << kRoad) | (1u << kCar);
  cv::Mat bitmask(kHeight, kWidth, CV_8UC4, cv::Scalar::all(0));
  for (int x = kBoundary - 1; x <= kBoundary + 1; ++x)
    bitmask.colRange(x, x + 1).setTo(cv::Scalar(bits & 0xff, (bits >> 8) & 0xff, (bits >> 16) & 0xff, x == kBoundary ? 230 : 120));
  const ros::Time stamp = ros::Time::now();
  images.publish(imageMsg(boundaryImage(), "mono8", stamp));
  info.publish(infoMsg(stamp));
  bitmasks.publish(imageMsg(bitmask, "8UC4", stamp));
  ASSERT_TRUE(waitFor([&] { return frame != nullptr; })) << "no frame from the bitmask intake";
  EXPECT_EQ(frame->intake_mode, "semantic_edges");
  std::size_t both = 0;
  for (std::size_t i = 0; i < frame->edge_u.size(); ++i) {
    EXPECT_NEAR(frame->edge_u[i], kBoundary, 1.0);
    both += frame->edge_class_mask[i] == bits;
  }
  EXPECT_GT(both, static_cast<std::size_t>(kHeight / 2)) << "boundary edges must carry road and car";
}

TEST_F(SemanticIntake, ARectifyingFusedIntakeUndistortsImageAndClassesIntoThePCamera) { expectRectifiedBoundary("/cam4", true); }

TEST_F(SemanticIntake, ARectifyingCannyIntakeUndistortsTheImageIntoThePCamera) { expectRectifiedBoundary("/cam5", false); }

TEST_F(SemanticIntake, NewestClassMapsAreCarriedToTheFramesAfterTheirImage) {
  ros::Publisher images = node_.advertise<sensor_msgs::Image>("/cam6/image", 5);
  ros::Publisher info = node_.advertise<sensor_msgs::CameraInfo>("/cam6/camera_info", 5);
  ros::Publisher labels = node_.advertise<sensor_msgs::Image>("/cam6/class_labels", 5);
  std::map<ros::Time, SemanticEdgeFrameConstPtr> frames;
  const ros::Subscriber subscriber = node_.subscribe<SemanticEdgeFrame>("/cam6/edge_frame", 10, [&](const SemanticEdgeFrameConstPtr& f) {
    std::lock_guard<std::mutex> lock(mutex_);
    frames[f->header.stamp] = f;
  });
  ASSERT_TRUE(waitFor([&] { return images.getNumSubscribers() > 0 && labels.getNumSubscribers() > 0; }, 10.0));
  ros::WallDuration(0.5).sleep();
  cv::Mat label_map(kHeight, kWidth, CV_8UC2, cv::Scalar(kRoad, 230));
  label_map.colRange(kBoundary, kWidth).setTo(cv::Scalar(kCar, 200));
  const auto frameOf = [&](const ros::Time& stamp) {
    SemanticEdgeFrameConstPtr frame;
    waitFor([&] { return frames.count(stamp) && (frame = frames[stamp]); });
    return frame;
  };
  // The first image has no map yet: made at once, with Canny edges of no class.
  const ros::Time first = ros::Time::now();
  images.publish(imageMsg(boundaryImage(), "mono8", first));
  info.publish(infoMsg(first));
  const SemanticEdgeFrameConstPtr without = frameOf(first);
  ASSERT_TRUE(without) << "the first frame must not wait for its class map";
  EXPECT_EQ(without->class_map_age, -1.0f);
  EXPECT_EQ(without->intake_mode, "canny");
  // Its map comes late; the next images take it, carried, with its age.
  labels.publish(imageMsg(label_map, "8UC2", first));
  ros::WallDuration(0.3).sleep();
  const std::uint32_t both = (1u << kRoad) | (1u << kCar);
  for (int k = 1; k <= 2; ++k) {
    const ros::Time later = first + ros::Duration(0.1 * k);
    images.publish(imageMsg(boundaryImage(), "mono8", later));
    info.publish(infoMsg(later));
    const SemanticEdgeFrameConstPtr frame = frameOf(later);
    ASSERT_TRUE(frame) << "no frame " << k << " after the class map";
    EXPECT_EQ(frame->intake_mode, "fused");
    EXPECT_NEAR(frame->class_map_age, 0.1 * k, 1e-3);
    std::size_t with_both = 0;
    for (std::uint32_t mask : frame->edge_class_mask) with_both += mask == both;
    EXPECT_GT(with_both, static_cast<std::size_t>(kHeight / 2)) << "the carried map must give the boundary both classes";
  }
}

TEST_F(SemanticIntake, SegmenterPublishesEnetProbabilities) {
  if (!std::filesystem::exists(kModel) || !std::filesystem::exists(kColorFrame))
    GTEST_SKIP() << "ENet model or KITTI colour frame absent (" << kModel << ", " << kColorFrame << ")";
  ros::Publisher images = node_.advertise<sensor_msgs::Image>("/seg/image", 2);
  sensor_msgs::ImageConstPtr result;
  float ms = -1.0f;
  ros::Subscriber probabilities = node_.subscribe<sensor_msgs::Image>("/seg/class_probabilities", 2, [&](const sensor_msgs::ImageConstPtr& p) {
    std::lock_guard<std::mutex> lock(mutex_);
    result = p;
  });
  ros::Subscriber times = node_.subscribe<std_msgs::Float32>("/seg/segmentation_time", 2, [&](const std_msgs::Float32ConstPtr& t) {
    std::lock_guard<std::mutex> lock(mutex_);
    ms = t->data;
  });
  ASSERT_TRUE(waitFor([&] { return images.getNumSubscribers() > 0; }, 20.0)) << "the Segmenter never subscribed (model not loaded?)";
  ros::WallDuration(0.5).sleep();
  const cv::Mat colour = cv::imread(kColorFrame, cv::IMREAD_COLOR);
  const ros::Time stamp = ros::Time::now();
  images.publish(imageMsg(colour, "bgr8", stamp));
  ASSERT_TRUE(waitFor([&] { return result != nullptr && ms > 0.0f; }, 20.0)) << "no class probabilities";
  std::cout << "Segmenter (ENet 640x320) on " << colour.cols << "x" << colour.rows << ": " << ms << " ms\n";
  EXPECT_EQ(result->encoding, "32FC19");
  EXPECT_EQ(result->header.stamp, stamp);
  EXPECT_EQ(result->width, static_cast<std::uint32_t>(colour.cols));
  EXPECT_EQ(result->height, static_cast<std::uint32_t>(colour.rows));
}

}  // namespace
}  // namespace semantic_edge_vo

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "semantic_intake_test");
  return RUN_ALL_TESTS();
}
