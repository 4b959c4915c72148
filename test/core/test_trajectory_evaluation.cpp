// The evaluator against known answers: synthetic cases, and the official ground truth of KITTI 00
// and 06 transformed by known similarities, noise, scale errors and motion perturbations.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/eval/evaluation_report.h"
#include "semantic_edge_vo/support/json_text.h"
#include "semantic_edge_vo/eval/trajectory_association.h"
#include "semantic_edge_vo/eval/trajectory_evaluator.h"
#include "semantic_edge_vo/common/trajectory_io.h"
#include "semantic_edge_vo/eval/trajectory_plot.h"

namespace semantic_edge_vo {
namespace {

namespace fs = std::filesystem;
using Poses = std::vector<Eigen::Isometry3d>;

constexpr double kDeg = M_PI / 180.0;

/// Official KITTI ground truth from ../shared; an empty trajectory when absent (the test skips).
Trajectory loadGroundTruth(const std::string& sequence) {
  const fs::path path = fs::path(SEVO_SHARED_DIR) / "data" / "kitti_odometry" / "poses_full" / (sequence + ".txt");
  Trajectory trajectory;
  if (fs::exists(path)) {
    EXPECT_EQ(readKittiPoses(path.string(), &trajectory), "");
  }
  return trajectory;
}
#define LOAD_GROUND_TRUTH_OR_SKIP(variable, sequence)                                                    \
  const Trajectory variable = loadGroundTruth(sequence);                                                 \
  if (variable.poses.empty()) {                                                                          \
    GTEST_SKIP() << "shared KITTI ground truth absent: " SEVO_SHARED_DIR "/data/kitti_odometry/poses_full/" \
                 << sequence << ".txt";                                                                  \
  }                                                                                                      \
  static_assert(true, "")

Eigen::Matrix3d rotationAbout(const Eigen::Vector3d& axis, double radians) {
  return Eigen::AngleAxisd(radians, axis.normalized()).toRotationMatrix();
}

/// The similarity applied to whole poses: the world moves, the camera frames keep their shape.
Poses transformed(const Poses& poses, const SimilarityTransform& s) {
  Poses result;
  for (const auto& pose : poses) {
    Eigen::Isometry3d moved = pose;
    moved.linear() = s.rotation * pose.linear();
    moved.translation() = s * pose.translation();
    result.push_back(moved);
  }
  return result;
}

/// Independent N(0, sigma^2) noise on each coordinate of each camera position.
Poses withPositionNoise(const Poses& poses, double sigma, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  Poses result = poses;
  for (auto& pose : result) pose.translation() += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  return result;
}

/// Chains the ground-truth motions after `perturb` changed each of them. The motions are made
/// exactly orthonormal first (KITTI rotations are orthonormal to about 1e-7 only, and a chain of
/// 1100 of them would otherwise drift from SO(3) by about 1e-4).
template <typename Perturb>
Poses chainedMotions(const Poses& gt, Perturb perturb) {
  Poses result = {Eigen::Isometry3d::Identity()};
  for (std::size_t i = 0; i + 1 < gt.size(); ++i) {
    Eigen::Isometry3d motion = gt[i].inverse() * gt[i + 1];
    motion.linear() = Eigen::Quaterniond(motion.linear()).normalized().toRotationMatrix();
    result.push_back(result.back() * perturb(motion));
  }
  return result;
}

SimilarityTransform exampleSimilarity() {
  SimilarityTransform s;
  s.scale = 2.5;
  s.rotation = rotationAbout({0.3, 1.0, -0.2}, 40 * kDeg);
  s.translation = {100.0, -20.0, 35.0};
  return s;
}

PosePairs pairsOf(const Poses& gt, const Poses& est) { return {gt, est, {}}; }

TrajectoryEvaluation evaluate(const Poses& gt, const Poses& est) {
  TrajectoryEvaluation evaluation;
  EXPECT_EQ(evaluateTrajectory(pairsOf(gt, est), TrajectoryEvaluationOptions(), {}, &evaluation), "");
  return evaluation;
}

/// Straight drive along z with `step` metres between frames.
Poses straightLine(int n, double step) {
  Poses poses;
  for (int i = 0; i < n; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation().z() = step * i;
    poses.push_back(pose);
  }
  return poses;
}

// --- building blocks ---------------------------------------------------------------------------

TEST(TrajectoryEvaluation, UmeyamaRecoversAKnownSimilarity) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-50.0, 50.0);
  std::vector<Eigen::Vector3d> source, target;
  const SimilarityTransform truth = exampleSimilarity();
  for (int i = 0; i < 30; ++i) {
    source.emplace_back(unit(rng), unit(rng), unit(rng));
    target.push_back(truth * source.back());
  }
  SimilarityTransform found;
  ASSERT_EQ(alignUmeyama(source, target, true, &found), "");
  EXPECT_NEAR(found.scale, truth.scale, 1e-12);
  EXPECT_TRUE(found.rotation.isApprox(truth.rotation, 1e-12));
  EXPECT_TRUE(found.translation.isApprox(truth.translation, 1e-12));
  ASSERT_EQ(alignUmeyama(source, target, false, &found), "");
  EXPECT_NEAR(found.scale, 1.0, 1e-12);

  EXPECT_NE(alignUmeyama({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}, true, &found).find("at least 3"),
            std::string::npos);
  EXPECT_NE(alignUmeyama(source, {}, true, &found).find("30 and 0"), std::string::npos);
  const std::vector<Eigen::Vector3d> still(5, Eigen::Vector3d(1, 2, 3));
  EXPECT_NE(alignUmeyama(still, still, true, &found).find("not all equal"), std::string::npos);
}

TEST(TrajectoryEvaluation, ErrorStatistics) {
  const ErrorStatistics even = errorStatistics({3.0, 4.0});
  EXPECT_EQ(even.count, 2u);
  EXPECT_DOUBLE_EQ(even.rmse, std::sqrt(12.5));
  EXPECT_DOUBLE_EQ(even.mean, 3.5);
  EXPECT_DOUBLE_EQ(even.median, 3.5);
  EXPECT_DOUBLE_EQ(even.max, 4.0);
  EXPECT_DOUBLE_EQ(errorStatistics({5.0, 1.0, 2.0}).median, 2.0);
  EXPECT_EQ(errorStatistics({}).count, 0u);
}

TEST(TrajectoryEvaluation, RotationAngle) {
  for (double degrees : {0.0, 1e-4, 1.0, 90.0, 179.0})
    EXPECT_NEAR(rotationAngle(rotationAbout({1, 2, 3}, degrees * kDeg)), degrees * kDeg, 1e-12) << degrees;
}

TEST(TrajectoryEvaluation, StraightLineReference) {
  // On a constant-speed line the reference is exact; frame numbers, not pair order, set the speed.
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 4}};
  EXPECT_LT(straightLineErrors(line, {0, 1, 3, 4}).rmse, 1e-12);
  EXPECT_GT(straightLineErrors(line, {0, 1, 2, 3}).rmse, 0.1);
  // A symmetric weave of +-0.5 m about the line: the closest line is the axis itself.
  const std::vector<Eigen::Vector3d> weave = {{0.5, 0, 0}, {-0.5, 0, 1}, {-0.5, 0, 2}, {0.5, 0, 3}};
  const ErrorStatistics s = straightLineErrors(weave, {0, 1, 2, 3});
  EXPECT_EQ(s.count, 4u);
  EXPECT_NEAR(s.rmse, 0.5, 1e-12);
  EXPECT_EQ(straightLineErrors(weave, {2, 2, 2, 2}).count, 0u);  // no speed to fit
}

TEST(TrajectoryEvaluation, AssociatesByIndexAndByStamps) {
  Trajectory gt, est;
  gt.poses = straightLine(10, 1.0);
  est.poses = straightLine(6, 2.0);
  EXPECT_EQ(associateByIndex(gt, est).gt.size(), 6u);

  for (int i = 0; i < 10; ++i) gt.stamps.push_back(0.1 * i);
  est.stamps = {0.003, 0.104, 0.25, 0.301, 0.598, 0.9};  // 0.25 is 0.05 s from both neighbours
  PosePairs pairs;
  ASSERT_EQ(associateByStamps(gt, est, 0.01, &pairs), "");
  EXPECT_EQ(pairs.gt_index, (std::vector<std::size_t>{0, 1, 3, 6, 9}));
  ASSERT_EQ(pairs.est.size(), 5u);
  EXPECT_DOUBLE_EQ(pairs.est[2].translation().z(), 6.0);  // the estimate pose stamped 0.301

  const PosePairs later = fromGroundTruthFrame(pairs, 3);
  EXPECT_EQ(later.gt_index, (std::vector<std::size_t>{3, 6, 9}));
  ASSERT_EQ(later.est.size(), 3u);
  EXPECT_DOUBLE_EQ(later.est[0].translation().z(), 6.0);
  EXPECT_DOUBLE_EQ(later.gt[0].translation().z(), 3.0);
  EXPECT_TRUE(fromGroundTruthFrame(pairs, 10).gt.empty());

  for (double& stamp : est.stamps) stamp += 100.0;
  EXPECT_NE(associateByStamps(gt, est, 0.01, &pairs).find("no estimate stamp lies within"), std::string::npos);
  est.stamps.clear();
  EXPECT_NE(associateByStamps(gt, est, 0.01, &pairs).find("needs a stamp"), std::string::npos);
}

TEST(TrajectoryEvaluation, PaperSegmentsAbsorbAPiecewiseSimilarity) {
  // 10 discarded + 3 full segments + 60 poses: the short remainder joins the third segment. Each
  // segment moved by its own similarity is fitted exactly; one global similarity cannot fit it.
  Poses gt;
  for (int i = 0; i < 670; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(30.0 * std::sin(0.01 * i), 0.1 * std::sin(0.05 * i), 1.0 * i);
    gt.push_back(pose);
  }
  Poses est = gt;
  for (int k = 0; k < 3; ++k) {
    SimilarityTransform s = exampleSimilarity();
    s.scale = 0.5 + k;
    s.rotation = rotationAbout({0, 1, 0}, 20.0 * k * kDeg);
    const auto first = static_cast<std::size_t>(10 + 200 * k), last = k == 2 ? gt.size() : first + 200;
    const Poses moved = transformed(Poses(gt.begin() + first, gt.begin() + last), s);
    std::copy(moved.begin(), moved.end(), est.begin() + first);
  }
  const TrajectoryEvaluation e = evaluate(gt, est);
  ASSERT_EQ(e.paper_ate_unavailable, "");
  ASSERT_EQ(e.paper_ate.segments.size(), 3u);
  EXPECT_EQ(e.paper_ate.segments[2].first, 410u);
  EXPECT_EQ(e.paper_ate.segments[2].count, 260u);
  EXPECT_EQ(e.paper_ate.error_m.count, 660u);
  EXPECT_NEAR(e.paper_ate.segments[1].scale, 1.0 / 1.5, 1e-9);
  EXPECT_LT(e.paper_ate.error_m.rmse, 1e-9);
  EXPECT_GT(e.sim3_ate.error_m.rmse, 10.0);
}

TEST(TrajectoryEvaluation, PaperProtocolAsStatedTakesEachSegmentsScaleButKeepsItsDrift) {
  // The truth's motion at a scale of its own in each 200-frame segment: chained with the segments'
  // scales it is the truth again. A heading that turns away by 2 degrees per segment stays in it.
  Poses gt;
  for (int i = 0; i < 610; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(30.0 * std::sin(0.01 * i), 0.0, 1.0 * i);
    gt.push_back(pose);
  }
  const auto scaleOf = [](std::size_t i) { return i < 210 ? 0.5 : i < 410 ? 2.0 : 1.5; };
  const auto chain = [&gt, &scaleOf](double turn_deg_per_segment) {
    Poses est = gt;
    for (std::size_t i = 1; i < gt.size(); ++i) {
      const double turn = turn_deg_per_segment * kDeg * static_cast<double>(i) / 200.0;
      est[i].translation() = est[i - 1].translation() +
                             scaleOf(i) * (rotationAbout({0, 1, 0}, turn) * (gt[i].translation() - gt[i - 1].translation()));
    }
    return est;
  };
  const TrajectoryEvaluation exact = evaluate(gt, chain(0.0));
  ASSERT_EQ(exact.paper_ate_unavailable, "");
  EXPECT_LT(exact.paper_chained_ate.error_m.rmse, 1e-6);
  EXPECT_EQ(exact.paper_chained_ate.error_m.count, 600u);
  const TrajectoryEvaluation turning = evaluate(gt, chain(2.0));
  EXPECT_GT(turning.paper_chained_ate.error_m.rmse, 3.0 * turning.paper_ate.error_m.rmse) << "per-segment alignment hides drift";
}

TEST(TrajectoryEvaluation, ShortSequencesSayWhatIsNotAvailable) {
  const Poses gt = straightLine(12, 1.0);  // 11 m
  const TrajectoryEvaluation e = evaluate(gt, gt);
  EXPECT_EQ(e.paper_ate_unavailable, "after discarding 10 poses, needs at least 13 pose pairs, has 12");
  EXPECT_NE(e.drift_unavailable.find("11 m long, shorter than the shortest KITTI segment (100 m)"), std::string::npos);
  EXPECT_EQ(e.rpe_unavailable, "");
  const std::string markdown = evaluationMarkdown({}, e, TrajectoryEvaluationOptions());
  EXPECT_NE(markdown.find("Not available: the ground truth is 11 m long"), std::string::npos);
  TrajectoryEvaluation unused;
  EXPECT_NE(evaluateTrajectory(pairsOf(straightLine(2, 1.0), straightLine(2, 1.0)), {}, {}, &unused).find("at least 3"),
            std::string::npos);
}

TEST(TrajectoryEvaluation, OptionsAreValidated) {
  TrajectoryEvaluationOptions options;
  EXPECT_EQ(options.validate(), "");
  options.paper_ate.segment_frames = 2;
  EXPECT_NE(options.validate().find("segment_frames"), std::string::npos);
  options = {};
  options.kitti_drift.segment_lengths_m.clear();
  EXPECT_NE(options.validate().find("segment_lengths_m"), std::string::npos);
  options = {};
  options.rpe_delta_frames = 0;
  EXPECT_NE(options.validate().find("rpe_delta_frames"), std::string::npos);
}

// --- KITTI 00 and 06 with known transforms -------------------------------------------------------

TEST(TrajectoryEvaluation, IdenticalTrajectoriesGiveZero) {
  LOAD_GROUND_TRUTH_OR_SKIP(gt, "00");
  const TrajectoryEvaluation e = evaluate(gt.poses, gt.poses);
  EXPECT_EQ(e.pairs, 4541u);
  EXPECT_NEAR(e.gt_length_m, 3724.19, 0.01);
  EXPECT_LT(e.paper_ate.error_m.rmse, 1e-9);
  EXPECT_LT(e.sim3_ate.error_m.rmse, 1e-9);
  EXPECT_LT(e.se3_ate.error_m.rmse, 1e-9);
  EXPECT_LT(e.rpe.translation_m.max, 1e-9);
  EXPECT_LT(e.rpe.rotation_deg.max, 1e-9);
  ASSERT_EQ(e.drift_unavailable, "");
  EXPECT_EQ(e.drift_as_given.lengths.size(), 8u);
  EXPECT_LT(e.drift_as_given.translation_percent, 1e-9);
  EXPECT_LT(e.drift_as_given.rotation_deg_per_100m, 1e-9);
  EXPECT_LT(e.frame_to_frame.mean_rotation_error_deg, 1e-9);
  EXPECT_LT(e.frame_to_frame.mean_direction_error_deg, 1e-9);
}

TEST(TrajectoryEvaluation, SimilarityOfGroundTruthIsAbsorbedBySim3NotBySe3) {
  LOAD_GROUND_TRUTH_OR_SKIP(gt, "00");
  const SimilarityTransform s = exampleSimilarity();
  const TrajectoryEvaluation e = evaluate(gt.poses, transformed(gt.poses, s));
  EXPECT_LT(e.sim3_ate.error_m.rmse, 1e-6);
  EXPECT_NEAR(e.sim3_ate.alignment.scale, 1.0 / s.scale, 1e-9);
  EXPECT_TRUE(e.sim3_ate.alignment.rotation.isApprox(s.rotation.transpose(), 1e-9));
  EXPECT_LT(e.paper_ate.error_m.rmse, 1e-6);
  // Without scale the estimate, 2.5 times too large, cannot be fitted: hundreds of metres.
  EXPECT_GT(e.se3_ate.error_m.rmse, 100.0);
  EXPECT_LT(e.rpe.translation_m.rmse, 1e-6);  // estimated motions shrunk by the Sim(3) scale
  EXPECT_LT(e.drift_sim3_scale.translation_percent, 1e-6);
  EXPECT_LT(e.frame_to_frame.mean_rotation_error_deg, 1e-6);
  EXPECT_LT(e.frame_to_frame.mean_direction_error_deg, 1e-6);
}

TEST(TrajectoryEvaluation, PositionNoiseGivesSigmaTimesSqrt3) {
  // est = S(gt + n), n ~ N(0, sigma^2 I3) per pose. Aligned back, each residual is the noise minus
  // what the fit absorbs: E[|n|^2] = 3 sigma^2, and a fit of 7 parameters to 3N coordinates leaves
  // E[RMSE^2] = sigma^2 (3N - 7) / N, so RMSE = sigma sqrt(3) sqrt(1 - 7 / 3N) (N = 200 for the
  // paper's segments: 0.6 % below sigma sqrt(3)). The sample RMSE of 3N = 13623 squares has a
  // relative standard deviation of about 1 / sqrt(2 * 3N) = 0.6 %: 2 % is over three of them.
  // RPE: the difference of two independent noises, sigma sqrt(6).
  LOAD_GROUND_TRUTH_OR_SKIP(gt, "00");
  const double sigma = 0.2;
  const TrajectoryEvaluation e = evaluate(gt.poses, transformed(withPositionNoise(gt.poses, sigma, 11), exampleSimilarity()));
  const double n = static_cast<double>(gt.size());
  EXPECT_NEAR(e.sim3_ate.error_m.rmse, sigma * std::sqrt(3.0) * std::sqrt(1.0 - 7.0 / (3.0 * n)), 0.02 * sigma * std::sqrt(3.0));
  EXPECT_NEAR(e.paper_ate.error_m.rmse, sigma * std::sqrt(3.0) * std::sqrt(1.0 - 7.0 / 600.0), 0.02 * sigma * std::sqrt(3.0));
  EXPECT_NEAR(e.rpe.translation_m.rmse, sigma * std::sqrt(6.0), 0.03 * sigma * std::sqrt(6.0));
  EXPECT_LT(e.rpe.rotation_deg.rmse, 1e-6);
  EXPECT_NEAR(e.sim3_ate.alignment.scale, 1.0 / 2.5, 1e-4);
}

Poses scaledTranslations(Poses poses, double scale) {
  for (auto& pose : poses) pose.translation() *= scale;
  return poses;
}

TEST(TrajectoryEvaluation, ConstantScaleErrorGivesKittiDriftOfScaleMinusOne) {
  // Every estimated translation s times too long: the devkit's error of a segment is
  // |(s - 1) t_gt| / L, t_gt the segment's displacement and L the nominal length. On a straight road
  // with 1 m between frames the segment ends at the first frame beyond L, L + 1 m away: exactly
  // |s - 1| (L + 1) / L.
  const double s = 1.05;
  const Poses gt = straightLine(1000, 1.0);
  KittiDriftResult drift;
  ASSERT_EQ(kittiDrift(gt, scaledTranslations(gt, s), 1.0, KittiDriftOptions(), &drift), "");
  ASSERT_EQ(drift.lengths.size(), 8u);
  for (const KittiDriftLength& length : drift.lengths) {
    EXPECT_NEAR(length.translation_percent, (s - 1.0) * 100.0 * (length.length_m + 1.0) / length.length_m, 1e-9);
    EXPECT_EQ(length.count, (998 - static_cast<std::size_t>(length.length_m)) / 10 + 1) << length.length_m;
    EXPECT_LT(length.rotation_deg_per_100m, 1e-9);
  }
  // With the Sim(3) scale applied first (monocular), a constant scale error is no drift at all.
  const TrajectoryEvaluation e = evaluate(gt, scaledTranslations(gt, s));
  EXPECT_NEAR(e.drift_as_given.translation_percent, drift.translation_percent, 1e-12);
  EXPECT_LT(e.drift_sim3_scale.translation_percent, 1e-9);
  // The scale as it is, whole path and end.
  EXPECT_NEAR(e.path_scale, s, 1e-9);
  EXPECT_NEAR(e.end_scale, s, 1e-9);
}

TEST(TrajectoryEvaluation, TheScaleAtTheEndIsTheLastPosesTravel) {
  // Metres for 900 frames, then 10 % short: the whole path's scale is a mix, the end's the last.
  const Poses gt = straightLine(1000, 1.0);
  Poses est = gt;
  for (std::size_t i = 901; i < est.size(); ++i)
    est[i].translation() = est[i - 1].translation() + 0.9 * (gt[i].translation() - gt[i - 1].translation());
  const TrajectoryEvaluation e = evaluate(gt, est);
  EXPECT_NEAR(e.end_scale, 0.9, 1e-9);
  EXPECT_GT(e.path_scale, 0.98);
}

TEST(TrajectoryEvaluation, TheScaleAlongThePathShowsWhereItDrifts) {
  // 1 m a frame for 100 m; the estimate travels 1 m a frame too, but 0.8 m a frame from 40 to 60 m.
  const Poses gt = straightLine(101, 1.0);
  Poses est = gt;
  for (std::size_t i = 1; i < est.size(); ++i) {
    const double step = i > 40 && i <= 60 ? 0.8 : 1.0;
    est[i].translation() = est[i - 1].translation() + Eigen::Vector3d(0.0, 0.0, step);
  }
  const ScaleAlongPath along = scaleAlongPath(positionsOf(gt), positionsOf(est), 20.0, 10);
  const std::vector<ScaleStretch>& stretches = along.stretches;
  ASSERT_EQ(stretches.size(), 5u);
  const double expected[] = {1.0, 1.0, 0.8, 1.0, 1.0};
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    EXPECT_EQ(stretches[k].first, 20 * k);
    EXPECT_EQ(stretches[k].last, 20 * (k + 1));
    EXPECT_NEAR(stretches[k].from_m, 20.0 * k, 1e-9);
    EXPECT_NEAR(stretches[k].scale, expected[k], 1e-9) << "stretch " << k;
  }
  EXPECT_EQ(along.lowest, 2u);
  EXPECT_EQ(along.highest, 0u);
  EXPECT_NEAR(along.largest_change, 0.25, 1e-9);
  // A tail shorter than half a stretch joins the one before it: 0-20, 20-40, 40-65 m.
  const Poses short_gt(gt.begin(), gt.begin() + 66), short_est(est.begin(), est.begin() + 66);
  const std::vector<ScaleStretch> joined = scaleAlongPath(positionsOf(short_gt), positionsOf(short_est), 20.0, 10).stretches;
  ASSERT_EQ(joined.size(), 3u);
  EXPECT_EQ(joined.back().first, 40u);
  EXPECT_EQ(joined.back().last, 65u);
  EXPECT_NEAR(joined.back().scale, (20 * 0.8 + 5.0) / 25.0, 1e-9);
  // A standing car: no stretch.
  EXPECT_TRUE(scaleAlongPath(positionsOf(straightLine(30, 0.0)), positionsOf(straightLine(30, 0.0)), 20.0, 10).stretches.empty());
  // In the reports: the lowest stretch over the whole path's scale, and where it is.
  const TrajectoryEvaluation e = evaluate(gt, est);
  EXPECT_NEAR(e.path_scale, 0.96, 1e-9);
  const std::string markdown = evaluationMarkdown(EvaluationSources(), e, TrajectoryEvaluationOptions());
  EXPECT_NE(markdown.find("| 5 | 0.8333 | 40-60 m | 1.042 | 0-20 m | 25 |"), std::string::npos) << markdown;
  const std::string json = evaluationJson(EvaluationSources(), e, TrajectoryEvaluationOptions());
  EXPECT_NE(json.find("\"lowest_relative\": 0.8333333333"), std::string::npos);
}

TEST(TrajectoryEvaluation, ConstantScaleErrorOnKitti00And06) {
  // On real roads the displacement of a segment is shorter than its path where the road turns, so
  // |s - 1| * 100 % (plus a frame's step) is an upper bound, nearly reached by the 100 m segments
  // and less and less by the longer ones, which turn round the blocks of 00 and the loop of 06.
  const double s = 1.05;
  for (const char* sequence : {"00", "06"}) {
    LOAD_GROUND_TRUTH_OR_SKIP(gt, sequence);
    KittiDriftResult drift;
    ASSERT_EQ(kittiDrift(gt.poses, scaledTranslations(gt.poses, s), 1.0, KittiDriftOptions(), &drift), "");
    ASSERT_EQ(drift.lengths.size(), 8u) << sequence;
    EXPECT_GT(drift.lengths.front().translation_percent, 0.88 * (s - 1.0) * 100.0) << sequence;
    for (const KittiDriftLength& length : drift.lengths)
      EXPECT_LT(length.translation_percent, 1.02 * (s - 1.0) * 100.0) << sequence << ", " << length.length_m << " m";
  }
}

TEST(TrajectoryEvaluation, KittiRotationDriftOfAConstantYawError) {
  // A yaw error of 0.01 degrees on every motion accumulates linearly: the error over a segment of
  // k frames is 0.01 k degrees, k being the frames needed for L metres of path.
  LOAD_GROUND_TRUTH_OR_SKIP(gt, "06");
  const double yaw = 0.01 * kDeg;
  const Poses est = chainedMotions(gt.poses, [&](Eigen::Isometry3d motion) {
    motion.linear() = motion.linear() * rotationAbout(Eigen::Vector3d::UnitY(), yaw);
    return motion;
  });
  const TrajectoryEvaluation e = evaluate(gt.poses, est);
  const double frames_per_100m = 100.0 * static_cast<double>(gt.size() - 1) / e.gt_length_m;
  EXPECT_NEAR(e.drift_as_given.rotation_deg_per_100m, 0.01 * frames_per_100m, 0.01 * frames_per_100m * 0.03);
  EXPECT_NEAR(e.frame_to_frame.mean_rotation_error_deg, 0.01, 1e-5);  // 1e-5: the ground truth's 1e-7 rad
  EXPECT_LT(e.frame_to_frame.mean_direction_error_deg, 1e-9);  // the motions' translations are untouched
}

TEST(TrajectoryEvaluation, KeyframeScaleChangeOfAnEstimateThatShrinks) {
  // 1 m a frame, keyframes every 3 frames; from frame 12 on the estimate travels 0.6 m a frame.
  const Poses gt = straightLine(30, 1.0);
  Poses est = gt;
  for (int i = 13; i < 30; ++i) est[static_cast<std::size_t>(i)].translation().z() = 12.0 + 0.6 * (i - 12);
  const std::vector<std::size_t> keyframes = {0, 3, 6, 9, 12, 15, 18, 21, 24, 27};
  KeyframeScaleChanges changes;
  ASSERT_EQ(keyframeScaleChanges(positionsOf(gt), positionsOf(est), keyframes, 0.2, &changes), "");
  EXPECT_EQ(changes.intervals, 9u);
  EXPECT_NEAR(changes.largest_change, 1.0 / 0.6 - 1.0, 1e-9);
  EXPECT_EQ(changes.at_pair, 12u) << "the interval 9-12 at scale 1, then 12-15 at 0.6";
  // Through evaluateTrajectory, with the keyframes given as frame numbers.
  TrajectoryEvaluation evaluation;
  ASSERT_EQ(evaluateTrajectory(pairsOf(gt, est), TrajectoryEvaluationOptions(), EstimateRecords{keyframes, {}}, &evaluation), "");
  EXPECT_EQ(evaluation.keyframe_scale_unavailable, "");
  EXPECT_NEAR(evaluation.keyframe_scale.largest_change, 1.0 / 0.6 - 1.0, 1e-9);
  // A standing car has no scale: intervals without travel are left out.
  const Poses standing = straightLine(30, 0.0);
  EXPECT_NE(keyframeScaleChanges(positionsOf(standing), positionsOf(standing), keyframes, 0.2, &changes), "");
}

TEST(TrajectoryEvaluation, FrameToFrameDirectionErrorOfAKnownTilt) {
  // Each motion's translation turned by 2 degrees about an axis perpendicular to it, rotations
  // untouched: the direction error is 2 degrees, the rotation error 0.
  LOAD_GROUND_TRUTH_OR_SKIP(gt, "06");
  const Poses est = chainedMotions(gt.poses, [](Eigen::Isometry3d motion) {
    const Eigen::Vector3d t = motion.translation();
    const Eigen::Vector3d axis = t.cross(Eigen::Vector3d::UnitY());
    if (axis.norm() > 1e-9) motion.translation() = rotationAbout(axis, 2.0 * kDeg) * t;
    return motion;
  });
  FrameToFrameErrors errors;
  ASSERT_EQ(frameToFrameErrors(gt.poses, est, 0.05, &errors), "");
  EXPECT_EQ(errors.motions, gt.size() - 1);
  EXPECT_GT(errors.direction_motions, gt.size() - 20);
  EXPECT_NEAR(errors.mean_direction_error_deg, 2.0, 1e-9);
  EXPECT_LT(errors.mean_rotation_error_deg, 1e-5);
}

// --- report and plot -----------------------------------------------------------------------------

TEST(TrajectoryEvaluation, JsonStringsAreEscaped) {
  EXPECT_EQ(jsonString("a\"b\\c\nd\te\x01/é"), "\"a\\\"b\\\\c\\nd\\te\\u0001/é\"");
}

TEST(TrajectoryEvaluation, ReportsHoldTheFigures) {
  const Poses gt = straightLine(300, 1.2);
  Poses est = withPositionNoise(gt, 0.1, 5);
  const TrajectoryEvaluation e = evaluate(gt, est);
  EvaluationSources sources;
  sources.gt_path = "gt \"quoted\".txt";
  sources.est_path = "a|b.tum";
  const std::string json = evaluationJson(sources, e, TrajectoryEvaluationOptions());
  EXPECT_NE(json.find("\"path\": \"gt \\\"quoted\\\".txt\""), std::string::npos);
  EXPECT_NE(json.find("\"unavailable\": null"), std::string::npos);
  EXPECT_EQ(json.find("nan"), std::string::npos);
  EXPECT_EQ(std::count(json.begin(), json.end(), '{'), std::count(json.begin(), json.end(), '}'));
  EXPECT_EQ(std::count(json.begin(), json.end(), '['), std::count(json.begin(), json.end(), ']'));
  char rmse[32];
  std::snprintf(rmse, sizeof(rmse), "\"rmse\": %.10g", e.sim3_ate.error_m.rmse);
  EXPECT_NE(json.find(rmse), std::string::npos);
  const std::string markdown = evaluationMarkdown(sources, e, TrajectoryEvaluationOptions());
  EXPECT_NE(markdown.find("`a\\|b.tum`"), std::string::npos);
  EXPECT_NE(markdown.find("| paper: first 10 poses discarded, Sim(3) per 200 frames |"), std::string::npos);
  EXPECT_NE(markdown.find("## KITTI devkit drift"), std::string::npos);
  // The straight-line reference: the ground truth is a straight line at constant speed.
  EXPECT_EQ(e.straight_line_m.count, gt.size());
  EXPECT_LT(e.straight_line_m.rmse, 1e-9);
  EXPECT_NE(json.find("\"straight_line_reference\": {"), std::string::npos);
  EXPECT_NE(markdown.find("| reference: constant-speed straight line closest to the ground truth | "), std::string::npos);
}

TEST(TrajectoryEvaluation, TopDownPlotDrawsBothTrajectories) {
  TopDownPlotOptions options;
  ASSERT_EQ(options.validate(), "");
  const std::vector<Eigen::Vector3d> gt = positionsOf(straightLine(100, 1.0));
  std::vector<Eigen::Vector3d> est = gt;
  for (auto& p : est) p.x() += 5.0;
  const cv::Mat image = renderTopDownPlot(gt, est, options);
  ASSERT_EQ(image.type(), CV_8UC3);
  EXPECT_EQ(image.cols, options.width_px);
  EXPECT_EQ(image.rows, options.height_px);
  int orange = 0, dark = 0;
  for (int v = 0; v < image.rows; ++v)
    for (int u = 0; u < image.cols; ++u) {
      const cv::Vec3b pixel = image.at<cv::Vec3b>(v, u);
      orange += pixel[2] > 200 && pixel[0] < 60;
      dark += pixel[0] < 60 && pixel[1] < 60 && pixel[2] < 60;
    }
  EXPECT_GT(orange, 500);  // the estimate's line, start dot and legend sample
  EXPECT_GT(dark, 500);
  EXPECT_FALSE(renderTopDownPlot({}, {}, options).empty());
  options.width_px = 10;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
