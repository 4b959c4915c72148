
#include <gtest/gtest.h>

#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"
#include "semantic_edge_vo/frontend/tracker.h"

namespace semantic_edge_vo {
namespace {

/// A keyframe from a synthetic frame, its points at their exact depth.
std::shared_ptr<Keyframe> exactKeyframe(const std::shared_ptr<const OdometryFrame>& frame,
                                        const synthetic::SyntheticFrame& truth) {
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->frame = frame;
  keyframe->T_world_cam = truth.T_world_cam;
  for (MapPoint point : frame->candidates) {
    const int x = static_cast<int>(point.u + 0.5f), y = static_cast<int>(point.v + 0.5f);
    const float depth = truth.depth.at<float>(y, x);
    if (!(depth > 0.5f) || truth.dynamic.at<std::uint8_t>(y, x)) continue;
    point.inverse_depth = 1.0 / depth;
    point.inverse_depth_variance = std::pow(0.01 * point.inverse_depth, 2);  // exact
    point.observations = 1;
    keyframe->points.push_back(point);
  }
  return keyframe;
}

double angleDeg(const Eigen::Isometry3d& T) { return Eigen::AngleAxisd(T.linear()).angle() * 180.0 / M_PI; }

/// The simulated network's per-class edges in EdgeIntake's bitmask form.
ClassEvidence semanticEdges(const synthetic::SyntheticFrame& frame) {
  ClassEvidence evidence;
  evidence.form = ClassEvidenceForm::kBitmask;
  evidence.values = synthetic::packEdgeBitmask(frame.semantics);
  evidence.classes = ClassTable::cityscapes().size();
  return evidence;
}

enum class Residuals { kPhotometric, kCannyEdges, kSemanticEdges };

class TrackerOnSyntheticCity : public ::testing::TestWithParam<Residuals> {};

TEST_P(TrackerOnSyntheticCity, RecoversTheTrueMotionFromExactDepth) {
  const bool use_field = GetParam() != Residuals::kPhotometric;
  const bool semantic = GetParam() == Residuals::kSemanticEdges;
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 3));
  FrameBuilderOptions options;
  options.use_field = use_field;
  options.intake.mode = semantic ? IntakeMode::kSemanticEdges : IntakeMode::kCanny;
  const FrameBuilder builder(options, sequence.camera(), ClassTable::cityscapes().names());
  ExtractionError error;
  const synthetic::SyntheticFrame truth_kf = sequence.frame(10);
  const auto keyframe_frame = builder.build(10, 1.0, truth_kf.gray, semanticEdges(truth_kf), &error);
  ASSERT_FALSE(error) << error.reason;
  Tracker tracker(TrackerOptions{});
  tracker.setKeyframe(exactKeyframe(keyframe_frame, truth_kf));

  for (int target_index : {11, 13}) {
    const synthetic::SyntheticFrame truth = sequence.frame(target_index);
    const auto frame = builder.build(target_index, 0.1 * target_index, truth.gray, semanticEdges(truth), &error);
    const Eigen::Isometry3d T_true = truth.T_world_cam.inverse() * truth_kf.T_world_cam;
    // Frame 11 from no motion; frame 13 (2.6 m away) from a constant-velocity-like prediction 30 % short.
    const Eigen::Isometry3d guess = target_index == 11 ? Eigen::Isometry3d::Identity() : se3Exp(0.7 * se3Log(T_true));
    const TrackingResult result = tracker.track(*frame->pyramid, frame->fieldOrNull(), {guess});
    const Eigen::Isometry3d T_error = result.T_cam_kf * T_true.inverse();
    EXPECT_TRUE(result.ok) << "frame " << target_index;
    EXPECT_LT(T_error.translation().norm(), 0.03) << "frame " << target_index << ", moved " << T_true.translation().norm() << " m";
    EXPECT_LT(angleDeg(T_error), 0.05) << "frame " << target_index;
    EXPECT_GT(result.points_in_view, 1000);
    if (use_field) {
      EXPECT_GT(result.edge_inliers, 500);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Residuals, TrackerOnSyntheticCity,
                         ::testing::Values(Residuals::kPhotometric, Residuals::kCannyEdges, Residuals::kSemanticEdges),
                         [](const auto& info) {
                           return std::string(info.param == Residuals::kPhotometric ? "photometric"
                                              : info.param == Residuals::kCannyEdges ? "canny_edges" : "semantic_edges");
                         });

TEST(Tracker, TriesTheOtherGuessesWhenTheFirstTracksWorseThanThePreviousFrame) {
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 3));
  FrameBuilderOptions options;
  options.use_field = false;
  const FrameBuilder builder(options, sequence.camera(), ClassTable::cityscapes().names());
  ExtractionError error;
  const synthetic::SyntheticFrame truth_kf = sequence.frame(10), truth = sequence.frame(12);
  Tracker tracker(TrackerOptions{});
  tracker.setKeyframe(exactKeyframe(builder.build(10, 1.0, truth_kf.gray, ClassEvidence(), &error), truth_kf));
  const auto frame = builder.build(12, 1.2, truth.gray, ClassEvidence(), &error);
  const Eigen::Isometry3d T_true = truth.T_world_cam.inverse() * truth_kf.T_world_cam;
  // The first guess is 4 m off to the side; the second is close.
  Eigen::Isometry3d wrong = T_true;
  wrong.translation() += Eigen::Vector3d(4.0, 0.0, 0.0);
  const std::vector<Eigen::Isometry3d> guesses = {wrong, se3Exp(0.8 * se3Log(T_true))};

  // Against a previous frame that tracked well, the first guess falls short and the others are tried.
  const TrackingResult retried = tracker.track(*frame->pyramid, nullptr, guesses, 0.9);
  EXPECT_EQ(retried.guess, 1);
  EXPECT_LT((retried.T_cam_kf * T_true.inverse()).translation().norm(), 0.03);
  // Against a previous frame that tracked as badly, the first guess is kept.
  const TrackingResult kept = tracker.track(*frame->pyramid, nullptr, guesses, 0.0);
  EXPECT_EQ(kept.guess, 0);
}

TEST(Tracker, TheCovarianceGrowsWhenFewerPointsConstrainThePose) {
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 3));
  FrameBuilderOptions options;
  options.use_field = false;
  const FrameBuilder builder(options, sequence.camera(), ClassTable::cityscapes().names());
  ExtractionError error;
  const synthetic::SyntheticFrame truth_kf = sequence.frame(10), truth = sequence.frame(11);
  const auto full = exactKeyframe(builder.build(10, 1.0, truth_kf.gray, ClassEvidence(), &error), truth_kf);
  auto sparse = std::make_shared<Keyframe>(*full);
  sparse->points.clear();
  for (std::size_t i = 0; i < full->points.size(); i += 10) sparse->points.push_back(full->points[i]);
  const auto frame = builder.build(11, 1.1, truth.gray, ClassEvidence(), &error);
  const Eigen::Isometry3d T_true = truth.T_world_cam.inverse() * truth_kf.T_world_cam;
  const auto track = [&](const std::shared_ptr<Keyframe>& keyframe) {
    Tracker tracker(TrackerOptions{});
    tracker.setKeyframe(keyframe);
    return tracker.track(*frame->pyramid, nullptr, {se3Exp(0.9 * se3Log(T_true))});
  };
  const TrackingResult with_all = track(full), with_tenth = track(sparse);
  ASSERT_TRUE(with_all.ok && with_tenth.ok);
  // The rotation's block: the translation's also holds the travel's share, the same for both.
  const double all = with_all.covariance.bottomRightCorner<3, 3>().trace(), tenth = with_tenth.covariance.bottomRightCorner<3, 3>().trace();
  EXPECT_GT(all, 0.0);
  EXPECT_GT(tenth, 4.0 * all) << "a tenth of the points must leave the pose several times less certain";
  const double all_position = with_all.covariance.topLeftCorner<3, 3>().trace();
  const double tenth_position = with_tenth.covariance.topLeftCorner<3, 3>().trace();
  EXPECT_GT(tenth_position, all_position);
  EXPECT_TRUE(with_all.covariance.isApprox(with_all.covariance.transpose()));
}

}  // namespace
}  // namespace semantic_edge_vo
