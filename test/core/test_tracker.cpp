#include <algorithm>

#include <gtest/gtest.h>

#include "semantic_edge_vo/odometry_frame.h"
#include "semantic_edge_vo/class_table.h"
#include "semantic_edge_vo/point_sampler.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"
#include "semantic_edge_vo/tracker.h"
#include "truck_scene.h"

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
  // The keyframe leaves out what truly moves (ground truth, below); parked cars stay, as in the
  // canny and photometric cases, so that the three residual kinds see the same scene.
  options.sampler.movable_classes = "";
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

/// Keyframe points of the truck scene, enough of them on the truck that it drags the pose. Edges:
/// the frame's sampled points. Photometric: a grid three times denser on the truck (class truck)
/// than on the ground and the wall (class road).
std::vector<MapPoint> truckScenePoints(Residuals residuals, const OdometryFrame& frame, const testing_scenes::TruckView& view) {
  if (residuals != Residuals::kPhotometric) return frame.candidates;
  const auto on_truck = [&](int u, int v) { return view.on_truck.at<std::uint8_t>(v, u) != 0; };
  std::vector<MapPoint> points;
  const std::vector<std::string> names = ClassTable::cityscapes().names();
  const std::uint32_t truck = classMaskOf(names, "truck"), road = classMaskOf(names, "road");
  for (int v = 24; v < view.gray.rows - 24; v += 4)
    for (int u = 24; u < view.gray.cols - 24; u += 4) {
      if (!on_truck(u, v) && (u % 12 != 0 || v % 12 != 0)) continue;
      MapPoint point;
      point.u = static_cast<float>(u);
      point.v = static_cast<float>(v);
      point.class_mask = on_truck(u, v) ? truck : road;
      point.normal = Eigen::Vector2f::UnitX();
      points.push_back(point);
    }
  return points;
}

/// A keyframe of `points` at the view's exact depths.
std::shared_ptr<Keyframe> truckSceneKeyframe(const std::shared_ptr<const OdometryFrame>& frame, const testing_scenes::TruckView& view,
                                             std::vector<MapPoint> points) {
  auto keyframe = std::make_shared<Keyframe>();
  keyframe->frame = frame;
  for (MapPoint& point : points) {
    point.inverse_depth = 1.0 / view.depth.at<float>(static_cast<int>(point.v + 0.5f), static_cast<int>(point.u + 0.5f));
    point.inverse_depth_variance = std::pow(0.01 * point.inverse_depth, 2);
    point.observations = 1;
  }
  keyframe->points = std::move(points);
  return keyframe;
}

/// The view's classes as a label image: truck where the truck is seen, road elsewhere.
ClassEvidence truckSceneLabels(const testing_scenes::TruckView& view) {
  const std::vector<std::string> names = ClassTable::cityscapes().names();
  const auto index = [&](const char* name) { return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin()); };
  ClassEvidence labels;
  labels.form = ClassEvidenceForm::kLabels;
  labels.values = cv::Mat(view.gray.size(), CV_8UC1, cv::Scalar(index("road")));
  labels.values.setTo(index("truck"), view.on_truck);
  labels.classes = static_cast<int>(names.size());
  return labels;
}

/// The camera drives 0.5 m past the truck: the keyframe points' motion into the frame.
const Eigen::Vector3d kTruckSceneMotion(0.0, 0.0, -0.5);
/// One frame at the speed the car drove at before, as the odometry guesses it.
const Eigen::Isometry3d kDrivingGuess(Eigen::Translation3d(0.9 * kTruckSceneMotion));

/// Tracker options with the movable-class check on.
TrackerOptions checkingMovable() {
  TrackerOptions options;
  options.movable_classes = "car,truck,bus";
  return options;
}

/// Tracks the camera's 0.5 m forward past the truck, its rear 5 m behind the keyframe's camera;
/// the truck drives `truck_step` meanwhile. Photometric residuals only, or with SNNF edge residuals
/// (fused edges: Canny's x the view's labels). Returns the result and its translation error, m.
std::pair<TrackingResult, double> trackPastTruck(Residuals residuals, double truck_step, const TrackerOptions& options,
                                                 const std::vector<Eigen::Isometry3d>& guesses) {
  const PinholeCamera camera = kittiCamera();
  const cv::Mat texture = testing_scenes::noiseTexture();
  FrameBuilderOptions frame_options;
  frame_options.use_field = residuals != Residuals::kPhotometric;
  frame_options.intake.mode = frame_options.use_field ? IntakeMode::kFused : IntakeMode::kCanny;
  frame_options.sampler.movable_classes = "";  // the keyframe keeps the truck: the tracker's check is tested
  const FrameBuilder builder(frame_options, camera, ClassTable::cityscapes().names());
  const testing_scenes::TruckView keyframe_view = testing_scenes::renderTruckScene(camera, texture, 0.0, -5.0);
  const testing_scenes::TruckView frame_view = testing_scenes::renderTruckScene(camera, texture, 0.5, -5.0 + truck_step);
  const auto evidence = [&](const testing_scenes::TruckView& view) {
    return frame_options.use_field ? truckSceneLabels(view) : ClassEvidence();
  };
  ExtractionError error;
  Tracker tracker(options);
  tracker.setClassNames(ClassTable::cityscapes().names());
  const auto keyframe_frame = builder.build(0, 0.0, keyframe_view.gray, evidence(keyframe_view), &error);
  EXPECT_FALSE(error) << error.reason;
  tracker.setKeyframe(truckSceneKeyframe(keyframe_frame, keyframe_view, truckScenePoints(residuals, *keyframe_frame, keyframe_view)));
  const auto frame = builder.build(1, 0.1, frame_view.gray, evidence(frame_view), &error);
  EXPECT_FALSE(error) << error.reason;
  const TrackingResult result = tracker.track(*frame->pyramid, frame->fieldOrNull(), guesses, 0.9);
  if (frame_options.use_field) {
    EXPECT_GT(result.edge_residuals, 0);
  }
  return {result, (result.T_cam_kf.translation() - kTruckSceneMotion).norm()};
}

class TrackerPastTruck : public ::testing::TestWithParam<Residuals> {};

TEST_P(TrackerPastTruck, ATruckAlongsideAtOurSpeedDoesNotDragThePose) {
  // Every point tracked: the truck, standing still in the image, holds the pose at "no motion".
  TrackerOptions no_check;
  no_check.movable_classes = "";
  // The guesses are the odometry's once the truck has dragged the last frames to a stop: no motion
  // first, then one frame of the speed the car drove at.
  const std::vector<Eigen::Isometry3d> dragged_guesses = {Eigen::Isometry3d::Identity(), kDrivingGuess};
  const auto [dragged, dragged_error] = trackPastTruck(GetParam(), 0.5, no_check, dragged_guesses);
  EXPECT_GT(dragged_error, 0.3);
  EXPECT_FALSE(dragged.without_movable);
  EXPECT_EQ(dragged.reference_inlier_ratio, dragged.inlierRatio());
  // The truck's points agree with that pose far better than the road's and the wall's: tracked
  // again without them, the pose follows the static structure.
  const auto [checked, checked_error] = trackPastTruck(GetParam(), 0.5, checkingMovable(), dragged_guesses);
  EXPECT_TRUE(checked.ok);
  EXPECT_TRUE(checked.without_movable);
  EXPECT_LT(checked_error, 0.05);
  // The next frame is tracked with the truck again first: its reference is the inlier ratio with
  // the truck's points at this pose (photometric 0.87, edges 0.81), not the static structure's
  // alone (0.81, 0.84).
  EXPECT_NE(checked.reference_inlier_ratio, checked.inlierRatio());
}

TEST_P(TrackerPastTruck, AParkedTruckIsTrackedWithTheRest) {
  // From the constant velocity of a car that tracked well.
  const auto [result, error] = trackPastTruck(GetParam(), 0.0, checkingMovable(), {kDrivingGuess});
  EXPECT_TRUE(result.ok);
  EXPECT_FALSE(result.without_movable);
  EXPECT_LT(error, 0.05);
  // The truck, close by, agrees better than the far wall (photometric: an inlier ratio 0.17
  // higher). Checked even so, it agrees with the pose tracked without it as well as with its own:
  // it stands.
  TrackerOptions eager = checkingMovable();
  eager.movable_disagreement = 0.05;
  const auto [checked, checked_error] = trackPastTruck(GetParam(), 0.0, eager, {kDrivingGuess});
  EXPECT_GT(checked.iterations, result.iterations);  // tracked again
  EXPECT_FALSE(checked.without_movable);
  EXPECT_LT(checked_error, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Residuals, TrackerPastTruck, ::testing::Values(Residuals::kPhotometric, Residuals::kSemanticEdges),
                         [](const auto& info) { return std::string(info.param == Residuals::kPhotometric ? "photometric" : "snnf_edges"); });

}  // namespace
}  // namespace semantic_edge_vo
