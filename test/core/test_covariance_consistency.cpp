// Tracked motions with their covariances: the file run_sequence writes, and the NEES that
// evaluate_trajectory computes from it against ground truth.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "semantic_edge_vo/common/tracked_motions.h"
#include "semantic_edge_vo/eval/covariance_consistency.h"

namespace semantic_edge_vo {
namespace {

namespace fs = std::filesystem;

/// A car-like drive: 1 m a frame along z, turning 0.5 degrees a frame.
PosePairs drive(std::size_t frames) {
  PosePairs pairs;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < frames; ++i) {
    pairs.gt.push_back(pose);
    pairs.est.push_back(pose);
    pose = pose * se3Exp((Vector6d() << 0.0, 0.0, 1.0, 0.0, 0.0087, 0.0).finished());
  }
  return pairs;
}

/// A covariance shaped like the tracker's: translation sigmas of centimetres, rotation of a
/// tenth of a degree, correlated.
Matrix6d trackerLikeCovariance() {
  Matrix6d A = Matrix6d::Identity();
  A.diagonal() << 0.02, 0.01, 0.05, 0.001, 0.002, 0.0005;
  A(0, 4) = 0.004;
  A(2, 1) = 0.01;
  return A * A.transpose();
}

/// Each frame tracked against the frame `gap` before it, its error drawn from `drawn`, its
/// covariance recorded as `recorded`.
std::vector<TrackedMotion> motionsWithErrors(const PosePairs& pairs, const Matrix6d& drawn, const Matrix6d& recorded,
                                             double translation_unit, bool in_metres) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  const Eigen::LLT<Matrix6d> llt(drawn);
  std::vector<TrackedMotion> motions;
  for (std::size_t f = 3; f < pairs.gt.size(); ++f) {
    TrackedMotion motion;
    motion.frame = f;
    motion.keyframe_frame = f - 3;
    motion.in_metres = in_metres;
    Vector6d noise;
    for (int i = 0; i < 6; ++i) noise(i) = normal(random);
    const Eigen::Isometry3d T_true = pairs.gt[f].inverse() * pairs.gt[f - 3];
    motion.T_cam_kf = se3Exp(llt.matrixL() * noise) * T_true;
    motion.T_cam_kf.translation() /= translation_unit;
    motion.covariance = recorded;
    motion.covariance.topRows<3>() /= translation_unit;
    motion.covariance.leftCols<3>() /= translation_unit;
    motions.push_back(motion);
  }
  return motions;
}

/// The consistency of `frames - 3` motions whose errors are drawn from the tracker-like covariance
/// and whose recorded covariance is it divided by `shrink`, in units of `translation_unit` metres.
CovarianceConsistency consistencyOf(std::size_t frames, double shrink, double translation_unit, bool in_metres) {
  const PosePairs pairs = drive(frames);
  const Matrix6d covariance = trackerLikeCovariance();
  CovarianceConsistency c;
  EXPECT_EQ(covarianceConsistency(pairs, motionsWithErrors(pairs, covariance, covariance / shrink, translation_unit, in_metres),
                                  in_metres ? 1.0 : translation_unit, &c),
            "");
  return c;
}

TEST(CovarianceConsistency, ErrorsDrawnFromTheCovarianceGiveChiSquareNees) {
  const CovarianceConsistency c = consistencyOf(3003, 1.0, 1.0, true);
  EXPECT_TRUE(c.in_metres);
  EXPECT_EQ(c.pose.count, 3000u);
  // Means of 3000 chi-square draws: standard deviations 0.045 (3 dof) and 0.063 (6 dof).
  EXPECT_NEAR(c.pose.mean, 6.0, 0.3);
  EXPECT_NEAR(c.rotation.mean, 3.0, 0.2);
  EXPECT_NEAR(c.translation.mean, 3.0, 0.2);
  EXPECT_NEAR(c.pose.median, c.pose.expected_median, 0.3);
  EXPECT_NEAR(c.pose.above_95, 0.05, 0.015);
}

TEST(CovarianceConsistency, ACovarianceTooSmallShowsAsLargeNees) {
  const CovarianceConsistency c = consistencyOf(1003, 16.0, 1.0, true);
  EXPECT_NEAR(c.pose.mean, 96.0, 10.0);  // errors 4 sigmas of the recorded covariance: NEES 16 times
  EXPECT_GT(c.pose.above_95, 0.9);
}

TEST(CovarianceConsistency, MonocularUnitsAreTakenToMetresByTheSim3Scale) {
  // The estimate in units of 2.5 m: its translations and their sigmas 2.5 times smaller.
  const CovarianceConsistency c = consistencyOf(1003, 1.0, 2.5, false);
  EXPECT_FALSE(c.in_metres);
  EXPECT_DOUBLE_EQ(c.translation_scale, 2.5);
  EXPECT_NEAR(c.translation.mean, 3.0, 0.35);
  EXPECT_NEAR(c.pose.mean, 6.0, 0.5);
}

TEST(CovarianceConsistency, MotionsOutsideTheGroundTruthAreSkippedAndNoneIsAnError) {
  const PosePairs pairs = drive(20);
  std::vector<TrackedMotion> motions = motionsWithErrors(pairs, trackerLikeCovariance(), trackerLikeCovariance(), 1.0, true);
  motions.back().frame = 40;
  CovarianceConsistency c;
  ASSERT_EQ(covarianceConsistency(pairs, motions, 1.0, &c), "");
  EXPECT_EQ(c.skipped, 1u);
  EXPECT_EQ(c.pose.count, motions.size() - 1);
  for (TrackedMotion& motion : motions) motion.frame = 100;
  EXPECT_NE(covarianceConsistency(pairs, motions, 1.0, &c), "");
}

TEST(TrackedMotions, WrittenMotionsReadBackAndBadLinesAreNamed) {
  const fs::path dir = fs::temp_directory_path() / ("sevo_tracked_motions_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const PosePairs pairs = drive(8);
  const std::vector<TrackedMotion> written = motionsWithErrors(pairs, trackerLikeCovariance(), trackerLikeCovariance(), 1.0, true);
  const std::string path = (dir / "tracked_motions.txt").string();
  ASSERT_EQ(writeTrackedMotions(path, written), "");
  std::vector<TrackedMotion> read;
  ASSERT_EQ(readTrackedMotions(path, &read), "");
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].frame, written[i].frame);
    EXPECT_EQ(read[i].keyframe_frame, written[i].keyframe_frame);
    EXPECT_TRUE(read[i].in_metres);
    EXPECT_TRUE(read[i].T_cam_kf.isApprox(written[i].T_cam_kf, 1e-7));
    EXPECT_TRUE(read[i].covariance.isApprox(written[i].covariance, 1e-7));
  }
  const std::string bad = (dir / "bad.txt").string();
  std::ofstream(bad) << "# header\n3 0 1 1 2 3\n";
  EXPECT_NE(readTrackedMotions(bad, &read).find("bad.txt:2:"), std::string::npos);
  EXPECT_EQ(read.size(), written.size());  // unchanged
  ASSERT_EQ(writeTrackedMotions(path, {}), "");  // a run without a trusted tracked frame
  ASSERT_EQ(readTrackedMotions(path, &read), "");
  EXPECT_TRUE(read.empty());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace semantic_edge_vo
