// kitti_to_bag's conversion: the shared KITTI 06 frames become a complete bag, which reads back as
// the same folder (run_sequence --bag); a small colour sequence with semantics; malformed or
// missing inputs are refused by name.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <geometry_msgs/PoseStamped.h>
#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/bags/bag_sequence.h"
#include "semantic_edge_vo/ros/bags/kitti_bag_conversion.h"
#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace {
namespace fs = std::filesystem;

const fs::path kKitti = fs::path(SEVO_SHARED_DIR) / "data" / "kitti_odometry";

/// A fresh temporary folder, removed at the end of the test.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("sevo_kitti_to_bag_" + std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TemporaryFolder() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

/// Messages of `topic` in `bag`, in bag order.
template <typename Message>
std::vector<typename Message::ConstPtr> readTopic(const std::string& bag_path, const std::string& topic) {
  rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
  std::vector<typename Message::ConstPtr> messages;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery(topic)))
    if (auto message = m.instantiate<Message>()) messages.push_back(message);
  return messages;
}

/// A 3-frame 16x8 sequence: colour camera 2 with a baseline in P2, class labels and edge bitmasks.
void makeSmallSequence(const fs::path& root) {
  for (const char* folder : {"image_2", "labels", "bitmask"}) fs::create_directories(root / folder);
  writeText(root / "calib.txt",
            "P0: 10 0 8 0 0 10 4 0 0 0 1 0\n"
            "P2: 10 0 8 5 0 10 4 0 0 0 1 0\n");
  writeText(root / "times.txt", "0.0\n0.1\n0.2\n");
  writeText(root / "poses.txt",
            "1 0 0 0 0 1 0 0 0 0 1 0\n"
            "1 0 0 0 0 1 0 0 0 0 1 1\n"
            "1 0 0 0 0 1 0 0 0 0 1 2\n");
  for (int i = 0; i < 3; ++i) {
    const std::string name = kittiFramePath("", static_cast<std::size_t>(i));
    cv::imwrite((root / "image_2" / name).string(), cv::Mat(8, 16, CV_8UC3, cv::Scalar(10, 20, 30 + i)));
    cv::imwrite((root / "labels" / name).string(), cv::Mat(8, 16, CV_8UC4, cv::Scalar(7, 200, 3, 40)));
    cv::imwrite((root / "bitmask" / name).string(), cv::Mat(8, 16, CV_8UC4, cv::Scalar(1, 2, 4, 255)));
  }
}

TEST(KittiToBag, SharedKitti06BecomesACompleteBag) {
  const fs::path sequence = kKitti / "sequences" / "06";
  const fs::path poses = kKitti / "poses" / "06.txt";
  if (!fs::exists(sequence / "calib.txt") || !fs::exists(poses))
    GTEST_SKIP() << "shared KITTI 06 absent (" << sequence << "): ../shared is not beside the repository";
  TemporaryFolder folder;
  KittiBagOptions options;
  options.sequence = sequence.string();
  options.output = (folder.path() / "06.bag").string();
  options.poses = poses.string();
  std::size_t last_progress = 0;
  ASSERT_EQ(writeKittiBag(options, [&](std::size_t done, std::size_t) { last_progress = done; }), "");
  EXPECT_EQ(last_progress, 51u);

  std::vector<double> times;
  ASSERT_EQ(readTimes((sequence / "times.txt").string(), &times), "");
  Trajectory truth;
  ASSERT_EQ(readKittiPoses(poses.string(), &truth), "");
  Eigen::Matrix<double, 3, 4> P0;
  ASSERT_EQ(readKittiProjection((sequence / "calib.txt").string(), 0, &P0), "");

  const auto images = readTopic<sensor_msgs::Image>(options.output, "/camera/image_rect");
  const auto infos = readTopic<sensor_msgs::CameraInfo>(options.output, "/camera/camera_info");
  const auto truths = readTopic<geometry_msgs::PoseStamped>(options.output, "/ground_truth/pose");
  ASSERT_EQ(images.size(), 51u);
  ASSERT_EQ(infos.size(), 51u);
  ASSERT_EQ(truths.size(), 51u);
  const cv::Mat frame0 = cv::imread((sequence / "image_0" / "000000.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(images[0]->encoding, "mono8");
  EXPECT_EQ(images[0]->header.frame_id, "camera_optical_frame");
  ASSERT_EQ(images[0]->width, 1226u);
  ASSERT_EQ(images[0]->height, 370u);
  EXPECT_EQ(std::memcmp(images[0]->data.data(), frame0.data, frame0.total()), 0) << "frame 0's pixels";
  for (std::size_t i = 0; i < 51; ++i) {
    const double stamp = SequenceBagWriter::kBaseTime + times[i];
    EXPECT_NEAR(images[i]->header.stamp.toSec(), stamp, 1e-6) << i;
    EXPECT_EQ(infos[i]->header.stamp, images[i]->header.stamp) << i;
    EXPECT_EQ(truths[i]->header.stamp, images[i]->header.stamp) << i;
    // KITTI's rotation blocks are orthonormal to about 1e-6 only; the message holds a unit quaternion.
    const Eigen::Isometry3d pose = fromPoseMsg(truths[i]->pose);
    EXPECT_TRUE(pose.translation().isApprox(truth.poses[i].translation(), 1e-12)) << i;
    EXPECT_LT((pose.linear() - truth.poses[i].linear()).cwiseAbs().maxCoeff(), 1e-5) << i;
  }
  const sensor_msgs::CameraInfo& info = *infos[0];
  EXPECT_EQ(info.width, 1226u);
  EXPECT_EQ(info.height, 370u);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  EXPECT_EQ(info.D, std::vector<double>(5, 0.0));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) EXPECT_EQ(info.P[static_cast<std::size_t>(4 * r + c)], P0(r, c)) << r << c;
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(info.K[static_cast<std::size_t>(3 * r + c)], P0(r, c)) << r << c;
      EXPECT_EQ(info.R[static_cast<std::size_t>(3 * r + c)], r == c ? 1.0 : 0.0) << r << c;
    }
  }
  EXPECT_DOUBLE_EQ(info.K[0], 707.0912);
}

TEST(KittiToBag, ABagReadBackIsTheKittiFolderItCameFrom) {
  const fs::path sequence = kKitti / "sequences" / "06";
  if (!fs::exists(sequence / "calib.txt")) GTEST_SKIP() << "shared KITTI 06 absent (" << sequence << "): ../shared is not beside the repository";
  TemporaryFolder folder;
  KittiBagOptions options;
  options.sequence = sequence.string();
  options.output = (folder.path() / "06.bag").string();
  ASSERT_EQ(writeKittiBag(options, nullptr), "");
  BagSequenceOptions read;
  read.bag = options.output;
  read.topic = "/camera/image_rect";
  read.output = (folder.path() / "back").string();
  std::size_t frames = 0, skipped = 0;
  ASSERT_EQ(writeSequenceFromBag(read, nullptr, &frames, &skipped), "");
  EXPECT_EQ(frames, 51u);
  EXPECT_EQ(skipped, 0u);
  Eigen::Matrix<double, 3, 4> original, back;
  ASSERT_EQ(readKittiProjection((sequence / "calib.txt").string(), 0, &original), "");
  ASSERT_EQ(readKittiProjection(read.output + "/calib.txt", 0, &back), "");
  EXPECT_TRUE(back.leftCols<3>().isApprox(original.leftCols<3>(), 1e-9)) << back;
  std::vector<double> times, times_back;
  ASSERT_EQ(readTimes((sequence / "times.txt").string(), &times), "");
  ASSERT_EQ(readTimes(read.output + "/times.txt", &times_back), "");
  ASSERT_EQ(times_back.size(), times.size());
  EXPECT_NEAR(times_back[50] - times_back[0], times[50] - times[0], 1e-6);
  for (std::size_t frame : {0u, 50u}) {
    const cv::Mat a = cv::imread(kittiFramePath((sequence / "image_0").string(), frame), cv::IMREAD_UNCHANGED);
    const cv::Mat b = cv::imread(kittiFramePath(read.output + "/image_0", frame), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << "frame " << frame << "'s pixels";
  }
  read.topic = "/no/such/image";
  EXPECT_NE(writeSequenceFromBag(read, nullptr, &frames, &skipped).find("no valid sensor_msgs/CameraInfo on /no/such/camera_info"),
            std::string::npos);
}

TEST(KittiToBag, ColourCameraWithSemantics) {
  TemporaryFolder folder;
  makeSmallSequence(folder.path());
  KittiBagOptions options;
  options.sequence = folder.path().string();
  options.output = (folder.path() / "small.bag").string();
  options.camera = 2;
  options.poses = (folder.path() / "poses.txt").string();
  options.class_labels = (folder.path() / "labels").string();
  options.edge_bitmask = (folder.path() / "bitmask").string();
  options.start_time = 100.0;
  ASSERT_EQ(writeKittiBag(options, nullptr), "");

  const auto images = readTopic<sensor_msgs::Image>(options.output, "/camera/image_rect");
  const auto labels = readTopic<sensor_msgs::Image>(options.output, "/camera/semantics/class_labels");
  const auto bitmasks = readTopic<sensor_msgs::Image>(options.output, "/camera/semantics/edge_bitmask");
  const auto infos = readTopic<sensor_msgs::CameraInfo>(options.output, "/camera/camera_info");
  const auto truths = readTopic<geometry_msgs::PoseStamped>(options.output, "/ground_truth/pose");
  ASSERT_EQ(images.size(), 3u);
  ASSERT_EQ(labels.size(), 3u);
  ASSERT_EQ(bitmasks.size(), 3u);
  ASSERT_EQ(truths.size(), 3u);
  EXPECT_EQ(images[2]->encoding, "bgr8");
  EXPECT_EQ(images[2]->data[2], 32) << "red of frame 2";
  EXPECT_NEAR(images[1]->header.stamp.toSec(), 100.1, 1e-9);
  EXPECT_EQ(labels[0]->encoding, "8UC2");
  EXPECT_EQ(labels[0]->data[0], 7) << "class";
  EXPECT_EQ(labels[0]->data[1], 200) << "confidence";
  EXPECT_EQ(labels[0]->header.stamp, images[0]->header.stamp);
  EXPECT_EQ(bitmasks[0]->encoding, "8UC4");
  EXPECT_EQ(std::vector<std::uint8_t>(bitmasks[0]->data.begin(), bitmasks[0]->data.begin() + 4),
            (std::vector<std::uint8_t>{1, 2, 4, 255}));
  EXPECT_EQ(infos[0]->P[3], 5.0) << "P2 as given";
  EXPECT_EQ(infos[0]->K[2], 8.0);
  // Camera 2 sits 0.5 m left of camera 0 (P2's fourth column 5 = fx * 0.5): x = -0.5 in camera 0.
  const Eigen::Isometry3d T_world_cam2 = fromPoseMsg(truths[1]->pose);
  EXPECT_TRUE(T_world_cam2.translation().isApprox(Eigen::Vector3d(-0.5, 0.0, 1.0), 1e-12))
      << T_world_cam2.translation().transpose();
}

TEST(KittiToBag, MalformedCalibrationIsNamedWithItsLine) {
  TemporaryFolder folder;
  makeSmallSequence(folder.path());
  writeText(folder.path() / "calib.txt", "P0: 10 0 8 0 0 10 4 0 0 0 1\nP2: 10 0 8 5 0 10 4 0 0 0 1 x\n");
  KittiBagOptions options;
  options.sequence = folder.path().string();
  options.output = (folder.path() / "bad.bag").string();
  options.camera = 2;
  const std::string calib = (folder.path() / "calib.txt").string();
  EXPECT_EQ(writeKittiBag(options, nullptr), calib + ":2: P2: 'x' is not a finite number");
  options.camera = 0;
  EXPECT_EQ(writeKittiBag(options, nullptr), calib + ":1: P0: expected 12 numbers, found 11");
  writeText(folder.path() / "calib.txt", "P0: 10 0 8 0 0 10 4 0 0 0 1 0\n");
  options.camera = 2;
  EXPECT_EQ(writeKittiBag(options, nullptr), calib + ": no P2: row");
  EXPECT_FALSE(fs::exists(options.output)) << "no bag is left behind";
}

TEST(KittiToBag, MissingOrMalformedFramesAreNamed) {
  TemporaryFolder folder;
  makeSmallSequence(folder.path());
  KittiBagOptions options;
  options.sequence = folder.path().string();
  options.output = (folder.path() / "bad.bag").string();
  options.camera = 2;
  options.class_labels = (folder.path() / "labels").string();

  fs::remove(folder.path() / "labels" / "000002.png");
  EXPECT_EQ(writeKittiBag(options, nullptr),
            (folder.path() / "labels" / "000002.png").string() + ": no such file (times.txt has 3 frames)");
  cv::imwrite((folder.path() / "labels" / "000002.png").string(), cv::Mat(8, 16, CV_8UC3, cv::Scalar::all(1)));
  const std::string error = writeKittiBag(options, nullptr);
  EXPECT_EQ(error.rfind((folder.path() / "labels" / "000002.png").string() + ": expected 1 channel", 0), 0u) << error;
  EXPECT_FALSE(fs::exists(options.output)) << "the partial bag is removed";

  options.class_labels.clear();
  cv::imwrite((folder.path() / "image_2" / "000001.png").string(), cv::Mat(9, 16, CV_8UC3, cv::Scalar::all(1)));
  EXPECT_EQ(writeKittiBag(options, nullptr),
            (folder.path() / "image_2" / "000001.png").string() + ": 16x9, frame 0 is 16x8");

  options.poses = (folder.path() / "poses.txt").string();
  writeText(folder.path() / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n");
  EXPECT_EQ(writeKittiBag(options, nullptr), options.poses + ": 1 poses, but times.txt has 3 frames");
}

}  // namespace
}  // namespace semantic_edge_vo
