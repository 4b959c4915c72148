// Trajectory files: KITTI poses, TUM trajectories and KITTI times.txt, against the format
// conventions of the KITTI devkit, TUM RGB-D and evo (file_interface.read_kitti_poses_file /
// read_tum_trajectory_file), and against each other on the official ground truth of KITTI 00.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "semantic_edge_vo/backend/trajectory_record.h"
#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace {

namespace fs = std::filesystem;

const fs::path kPoses = fs::path(SEVO_SHARED_DIR) / "data" / "kitti_odometry" / "poses_full";

class TrajectoryIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sevo_trajectory_io_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Writes `text` into a file of the test's directory and returns its path.
  std::string file(const std::string& name, const std::string& text) const {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
};

Trajectory randomTrajectory(int n, bool stamped, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Trajectory trajectory;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(unit(rng), unit(rng), unit(rng), unit(rng)).normalized().toRotationMatrix();
    pose.translation() = 500.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    trajectory.poses.push_back(pose);
    if (stamped) trajectory.stamps.push_back(1.6e9 + 0.1 * i + 1e-4 * unit(rng));
  }
  return trajectory;
}

void expectSamePoses(const Trajectory& a, const Trajectory& b, double tolerance) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    ASSERT_LT((a.poses[i].matrix() - b.poses[i].matrix()).cwiseAbs().maxCoeff(), tolerance) << "pose " << i;
}

TEST_F(TrajectoryIo, KittiLineIsRowMajorCameraToWorld) {
  // 90 degrees about z, camera at (1, 2, 3): rows [R | t], as the devkit and evo read them.
  Trajectory trajectory;
  ASSERT_EQ(readKittiPoses(file("a.txt", "# comment\n\n0 -1 0 1 1 0 0 2 0 0 1 3\n"), &trajectory), "");
  ASSERT_EQ(trajectory.size(), 1u);
  EXPECT_FALSE(trajectory.hasStamps());
  const Eigen::Isometry3d& T_world_cam = trajectory.poses[0];
  EXPECT_TRUE(T_world_cam.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((T_world_cam.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((T_world_cam * Eigen::Vector3d::Zero()).isApprox(Eigen::Vector3d(1, 2, 3)));  // camera centre
}

TEST_F(TrajectoryIo, TumLineIsStampPositionAndXyzwQuaternion) {
  // evo reads `timestamp x y z q_x q_y q_z q_w` and rolls the quaternion to w-first.
  Trajectory trajectory;
  ASSERT_EQ(readTumTrajectory(file("a.tum", "# timestamp tx ty tz qx qy qz qw\n"
                                            "1.5 1 2 3 0 0 0.70710678 0.70710678\n"
                                            "2.5\t1 2 3   0 0 0 1\n"),
                              &trajectory),
            "");
  ASSERT_EQ(trajectory.size(), 2u);
  ASSERT_EQ(trajectory.stamps, (std::vector<double>{1.5, 2.5}));
  EXPECT_TRUE(trajectory.poses[0].translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE((trajectory.poses[0].linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-8));
  EXPECT_TRUE(trajectory.poses[1].linear().isIdentity());

  // The same pose in KITTI form reads the same.
  Trajectory kitti;
  ASSERT_EQ(readKittiPoses(file("a.txt", "0 -1 0 1 1 0 0 2 0 0 1 3\n"), &kitti), "");
  EXPECT_TRUE(kitti.poses[0].isApprox(trajectory.poses[0], 1e-8));
}

TEST_F(TrajectoryIo, KittiWriteReadRoundTrip) {
  const Trajectory written = randomTrajectory(50, false, 1);
  const std::string path = (dir_ / "poses.txt").string();
  ASSERT_EQ(writeKittiPoses(path, written), "");
  Trajectory read;
  ASSERT_EQ(readKittiPoses(path, &read), "");
  expectSamePoses(written, read, 1e-6);  // 10 significant digits of up to 500 m
}

TEST_F(TrajectoryIo, TumWriteReadRoundTripKeepsEpochStamps) {
  const Trajectory written = randomTrajectory(50, true, 2);
  const std::string path = (dir_ / "trajectory.tum").string();
  ASSERT_EQ(writeTumTrajectory(path, written), "");
  Trajectory read;
  ASSERT_EQ(readTumTrajectory(path, &read), "");
  expectSamePoses(written, read, 1e-6);
  for (std::size_t i = 0; i < read.size(); ++i) EXPECT_NEAR(read.stamps[i], written.stamps[i], 1e-6);

  Trajectory unstamped = written;
  unstamped.stamps.clear();
  EXPECT_NE(writeTumTrajectory(path, unstamped).find("one time stamp per pose"), std::string::npos);
}

TEST_F(TrajectoryIo, TimesWriteReadRoundTrip) {
  const std::vector<double> stamps = {0.0, 0.103736, 1.6e9 + 0.123456789};
  const std::string path = (dir_ / "times.txt").string();
  ASSERT_EQ(writeTimes(path, stamps), "");
  std::vector<double> read;
  ASSERT_EQ(readTimes(path, &read), "");
  ASSERT_EQ(read.size(), stamps.size());
  for (std::size_t i = 0; i < read.size(); ++i) EXPECT_NEAR(read[i], stamps[i], 1e-6);
}

TEST_F(TrajectoryIo, ARecordWritesItsPosesAndFlagsEveryPoseNotTrusted) {
  TrajectoryRecord record;
  const Trajectory poses = randomTrajectory(3, true, 5);
  for (int i = 0; i < 3; ++i) {
    FramePose pose;
    pose.index = i;
    pose.T_world_cam = poses.poses[static_cast<std::size_t>(i)];
    pose.trusted = i != 1;
    pose.state = i == 1 ? OdometryState::kLost : OdometryState::kTracking;
    record.add(pose, poses.stamps[static_cast<std::size_t>(i)]);
  }
  std::vector<std::string> files;
  ASSERT_EQ(record.write(dir_.string(), &files), "");
  ASSERT_EQ(files.size(), 3u);
  Trajectory kitti, tum;
  ASSERT_EQ(readKittiPoses((dir_ / "poses_kitti.txt").string(), &kitti), "");
  ASSERT_EQ(readTumTrajectory((dir_ / "poses_tum.txt").string(), &tum), "");
  EXPECT_EQ(kitti.size(), 3u);
  EXPECT_EQ(tum.size(), 3u);
  std::ifstream flags(dir_ / "poses_flags.txt");
  std::vector<std::string> lines;
  for (std::string line; std::getline(flags, line);)
    if (!line.empty() && line[0] != '#') lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << "one flag line per pose";
  EXPECT_EQ(lines[1].substr(lines[1].size() - 7), " 0 lost") << lines[1];
  EXPECT_EQ(lines[2].substr(lines[2].size() - 11), " 1 tracking") << lines[2];
}

TEST_F(TrajectoryIo, ReadsKeyframesFromATimingTableOrAList) {
  std::vector<std::size_t> keyframes;
  ASSERT_EQ(readKeyframeFrames(file("timing.txt", "# frame tracking_ms trusted state keyframe guess\n"
                                                  "0 1.5 1 tracking 1 0\n1 2.0 1 tracking 0 0\n2 2.5 0 untrusted 0 0\n"
                                                  "3 1.0 1 tracking 1 2\n"),
                               &keyframes),
            "");
  EXPECT_EQ(keyframes, (std::vector<std::size_t>{0, 3}));
  ASSERT_EQ(readKeyframeFrames(file("list.txt", "4\n9\n\n12\n"), &keyframes), "");
  EXPECT_EQ(keyframes, (std::vector<std::size_t>{4, 9, 12}));
  EXPECT_NE(readKeyframeFrames(file("bad.txt", "4\n2\n"), &keyframes).find("bad.txt:2:"), std::string::npos);
  EXPECT_NE(readKeyframeFrames(file("word.txt", "four\n"), &keyframes).find("word.txt:1:"), std::string::npos);
}

TEST_F(TrajectoryIo, DetectsTheFormatFromTheColumns) {
  TrajectoryFormat format = TrajectoryFormat::kTum;
  ASSERT_EQ(detectTrajectoryFormat(file("k.txt", "# c\n1 0 0 0 0 1 0 0 0 0 1 0\n"), &format), "");
  EXPECT_EQ(format, TrajectoryFormat::kKitti);
  ASSERT_EQ(detectTrajectoryFormat(file("t.txt", "0 0 0 0 0 0 0 1\n"), &format), "");
  EXPECT_EQ(format, TrajectoryFormat::kTum);
  EXPECT_NE(detectTrajectoryFormat(file("x.txt", "1 2 3\n"), &format).find("x.txt:1:"), std::string::npos);
  EXPECT_TRUE(parseTrajectoryFormat("tum", &format));
  EXPECT_FALSE(parseTrajectoryFormat("euroc", &format));
}

TEST_F(TrajectoryIo, RejectsBadFilesNamingFileAndLine) {
  Trajectory trajectory;
  const std::string identity = "1 0 0 0 0 1 0 0 0 0 1 0\n";
  const std::string short_line = file("short.txt", identity + "1 0 0 0 0 1 0 0 0 0 1\n");
  EXPECT_EQ(readKittiPoses(short_line, &trajectory), short_line + ":2: expected 12 numbers, found 11");
  EXPECT_TRUE(trajectory.poses.empty()) << "output must stay unchanged on failure";
  EXPECT_NE(readKittiPoses(file("word.txt", "1 0 0 x 0 1 0 0 0 0 1 0\n"), &trajectory).find("word.txt:1: 'x'"),
            std::string::npos);
  EXPECT_NE(readKittiPoses(file("nan.txt", "1 0 0 nan 0 1 0 0 0 0 1 0\n"), &trajectory).find("not a finite"),
            std::string::npos);
  EXPECT_NE(readKittiPoses(file("scaled.txt", "2 0 0 0 0 2 0 0 0 0 2 0\n"), &trajectory).find("not a rotation"),
            std::string::npos);
  EXPECT_NE(readKittiPoses(file("mirror.txt", "-1 0 0 0 0 1 0 0 0 0 1 0\n"), &trajectory).find("not a rotation"),
            std::string::npos);
  EXPECT_NE(readKittiPoses(file("empty.txt", "# nothing\n"), &trajectory).find("no data lines"), std::string::npos);
  EXPECT_NE(readKittiPoses((dir_ / "absent.txt").string(), &trajectory).find("cannot open"), std::string::npos);
  EXPECT_NE(readTumTrajectory(file("order.tum", "2 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n"), &trajectory)
                .find("order.tum:2: time stamp 1 does not increase"),
            std::string::npos);
  EXPECT_NE(readTumTrajectory(file("q.tum", "1 0 0 0 0 0 0 2\n"), &trajectory).find("q.tum:1: quaternion norm"),
            std::string::npos);
  std::vector<double> stamps;
  EXPECT_NE(readTimes(file("times.txt", "0\n0.1\n0.1\n"), &stamps).find("times.txt:3:"), std::string::npos);
  EXPECT_TRUE(trajectory.poses.empty() && stamps.empty());
}

TEST_F(TrajectoryIo, KittiAndTumReadersAgreeOnKitti00GroundTruth) {
  const fs::path poses = kPoses / "00.txt", times = kPoses / "00_times.txt";
  if (!fs::exists(poses) || !fs::exists(times)) GTEST_SKIP() << "shared KITTI ground truth absent: " << poses;
  Trajectory kitti;
  ASSERT_EQ(readKittiPoses(poses.string(), &kitti), "");
  ASSERT_EQ(readTimes(times.string(), &kitti.stamps), "");
  ASSERT_EQ(kitti.size(), 4541u);
  ASSERT_EQ(kitti.stamps.size(), 4541u);
  EXPECT_EQ(kitti.stamps.front(), 0.0);
  EXPECT_TRUE(kitti.poses.front().isApprox(Eigen::Isometry3d::Identity(), 1e-6));  // frame 0 is the world

  // KITTI -> TUM -> read: the same poses (the TUM quaternion re-orthonormalises rotations that the
  // ground truth keeps to about 1e-7) and the same stamps.
  const std::string tum = (dir_ / "00.tum").string();
  ASSERT_EQ(writeTumTrajectory(tum, kitti), "");
  Trajectory from_tum;
  ASSERT_EQ(readTumTrajectory(tum, &from_tum), "");
  expectSamePoses(kitti, from_tum, 1e-6);
  for (std::size_t i = 0; i < kitti.size(); ++i) ASSERT_NEAR(from_tum.stamps[i], kitti.stamps[i], 1e-9);

  // Written back as KITTI, the file reads the same as the original.
  const std::string again = (dir_ / "00.txt").string();
  ASSERT_EQ(writeKittiPoses(again, kitti), "");
  Trajectory reread;
  ASSERT_EQ(readKittiPoses(again, &reread), "");
  expectSamePoses(kitti, reread, 1e-9);
}

TEST_F(TrajectoryIo, ShortKitti06PosesAreTheStartOfTheFullOnes) {
  const fs::path full = kPoses / "06.txt", start = kPoses.parent_path() / "poses" / "06.txt";
  if (!fs::exists(full) || !fs::exists(start)) GTEST_SKIP() << "shared KITTI 06 ground truth absent: " << full;
  Trajectory all, first;
  ASSERT_EQ(readKittiPoses(full.string(), &all), "");
  ASSERT_EQ(readKittiPoses(start.string(), &first), "");
  ASSERT_EQ(all.size(), 1101u);
  ASSERT_EQ(first.size(), 51u);
  all.poses.resize(first.size());
  expectSamePoses(all, first, 1e-12);
}

}  // namespace
}  // namespace semantic_edge_vo
