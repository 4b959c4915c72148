// The whole odometry on a short synthetic drive, with exact ground truth: it tracks from its first
// frames, and a frame it cannot track (the camera blinded for one or five frames) is reported lost,
// never trusted; the odometry goes on where it was (odom continuous), at about the scale it had,
// on the map it had when the view comes back. A restart asked for (the tracking nodelet's reset
// service) starts a new map there. A car that stops at a light and drives on is tracked all along,
// on the map it had, also when the first second of its start never reaches the odometry (dropped
// frames) or a van blocks the view while it stands. Frames dropped from the stream are counted from
// the stamps; a loss it never recovers from predicts on for 5 s, then stands. A view that changes
// for good (a truck alongside) makes a keyframe at once.
#include <algorithm>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"
#include "semantic_edge_vo/eval/trajectory_evaluation.h"

namespace semantic_edge_vo {
namespace {

constexpr int kFrames = 50;
constexpr int kEvent = 24;  ///< the frame blinded or restarted at: well after the first initialisation (about 5 frames)

struct DriveResult {
  std::map<int, FramePose> poses;  ///< by frame index, every frame once
  std::vector<Eigen::Isometry3d> truth;
  std::vector<double> speed;  ///< of the car, m/s
};

enum class Event {
  kBlindedFrame,
  kRestart,
  kStop,
  kStopThenFramesDropped,
  kStopWhileBlinded,
  kBlindedWhileDriving,
  kFramesDropped,
  kBlindedForGood,
  kRepeatedFrame,   ///< frame kEvent shows frame kEvent - 1 again (a driver that sent the same image twice)
  kFrameFromLater,  ///< frame kEvent shows frame kEvent + kLaterFrames (a frame out of order)
  kCoveredForGood,  ///< from frame kEvent on, the right kCoveredShare of every image is uniform gray (a truck alongside that stays)
};

constexpr int kStopFrames = 120;       ///< the drive with a stop: to the light (braking from about 15 m), 3 s there, and on
constexpr double kStopAt = 25.0;       ///< m along the route
constexpr double kStopDuration = 3.0;  ///< s
constexpr int kDroppedAtStart = 10;    ///< frames of the start after the stop that never arrive (1 s: 0.9 m)
constexpr int kBlindedFrames = 5;      ///< a van crossing in front: half a second without a view
constexpr int kBlindedIntoStop = 10;   ///< frames after the car came to rest that the van arrives
constexpr int kDroppedWhileDriving = 3;
constexpr double kCoveredShare = 0.5;
constexpr int kLaterFrames = 30;       ///< how far ahead the out-of-order frame is  ///< frames from kEvent on that never arrive: the next moved four frames' travel

/// Frames of the drive blinded from the first (-1 for none; the stop's first standing frame not
/// known yet) and how many.
struct Blinding {
  int first = -1, count = 0;
};
Blinding blindingOf(Event event, int first_standing) {
  switch (event) {
    case Event::kBlindedFrame: return {kEvent, 1};
    case Event::kBlindedWhileDriving: return {kEvent, kBlindedFrames};
    case Event::kStopWhileBlinded: return {first_standing < 0 ? -1 : first_standing + kBlindedIntoStop, kBlindedFrames};
    case Event::kBlindedForGood: return {kEvent, kStopFrames};
    default: return {};
  }
}

/// Runs the odometry over the city drive (Canny edges, SNNF); from frame kEvent one or more images
/// are replaced by a uniform gray one, or the odometry is restarted before it; or the car stops on
/// its way (and may be blinded while standing).
DriveResult drive(Event event, MappingMode mapping = MappingMode::kDeterministic) {
  synthetic::SyntheticSequenceOptions options = synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 1);
  const bool stop = event == Event::kStop || event == Event::kStopThenFramesDropped || event == Event::kStopWhileBlinded;
  if (stop) {
    options.world.ego.stop_at = kStopAt;
    options.world.ego.stop_duration = kStopDuration;
  }
  synthetic::SyntheticSequence sequence(options);
  const FrameBuilder builder(FrameBuilderOptions{}, sequence.camera(), ClassTable::cityscapes().names());
  OdometryOptions odometry_options;  // the defaults: the shipped config
  Odometry odometry(odometry_options, sequence.camera(), mapping);
  DriveResult run;
  // As in the tracking nodelet, the odometry numbers the frames it receives: dropped frames are seen
  // in the stamps only. drive_index maps its numbers back to the drive's frames.
  std::vector<int> drive_index;
  const auto keep = [&run, &drive_index](const std::vector<FramePose>& poses) {
    for (const FramePose& pose : poses) {
      const int i = drive_index.at(static_cast<std::size_t>(pose.index));
      EXPECT_EQ(run.poses.count(i), 0u) << "frame " << i << " got a second pose";
      run.poses[i] = pose;
    }
  };
  // Keyframes as the windows tell them (parallel mapping decides after the pose was returned).
  std::vector<int> keyframe_frames;
  const auto keepKeyframes = [&] {
    for (const auto& window : odometry.takeNewWindows()) keyframe_frames.push_back(drive_index.at(static_cast<std::size_t>(window->frame_index)));
  };
  const int frames = stop || event == Event::kBlindedForGood ? kStopFrames : kFrames;
  int last_standing = -1, first_standing = -1;
  for (int i = 0; i < frames; ++i) {
    synthetic::SyntheticFrame frame = sequence.frame(i);
    run.truth.push_back(frame.T_world_cam);
    run.speed.push_back(frame.speed);
    if (frame.speed == 0.0) last_standing = i;
    if (frame.speed == 0.0 && first_standing < 0) first_standing = i;
    const Blinding blinding = blindingOf(event, first_standing);
    if (blinding.first >= 0 && i >= blinding.first && i < blinding.first + blinding.count) frame.gray.setTo(128);
    if (i >= kEvent && event == Event::kCoveredForGood) {
      const int covered = static_cast<int>(kCoveredShare * frame.gray.cols);
      frame.gray(cv::Rect(frame.gray.cols - covered, 0, covered, frame.gray.rows)).setTo(128);
    }
    if (i == kEvent && event == Event::kRepeatedFrame) frame.gray = sequence.frame(i - 1).gray;
    if (i == kEvent && event == Event::kFrameFromLater) frame.gray = sequence.frame(i + kLaterFrames).gray;
    if (event == Event::kStopThenFramesDropped && last_standing >= 0 && i > last_standing && i <= last_standing + kDroppedAtStart)
      continue;
    if (event == Event::kFramesDropped && i >= kEvent && i < kEvent + kDroppedWhileDriving) continue;
    if (i == kEvent && event == Event::kRestart) odometry.restart();
    ExtractionError error;
    const auto odometry_frame = builder.build(static_cast<int>(drive_index.size()), frame.time, frame.gray, ClassEvidence{}, &error);
    drive_index.push_back(i);
    EXPECT_FALSE(error) << error.reason;
    keep(odometry.process(odometry_frame));
    keepKeyframes();
  }
  odometry.finishMapping();
  keepKeyframes();
  keep(odometry.flush());
  for (auto& [index, pose] : run.poses) {
    const bool made = std::find(keyframe_frames.begin(), keyframe_frames.end(), index) != keyframe_frames.end();
    if (mapping == MappingMode::kDeterministic) EXPECT_EQ(made, pose.keyframe) << "frame " << index << ": the windows and the poses agree";
    pose.keyframe = made;
  }
  return run;
}

/// The drive before the event, Sim(3)-aligned to the truth, fixes the map's scale and placement;
/// the same alignment must carry the poses after it (odom continuous, the scale carried over).
void expectContinuousAcross(const DriveResult& run, const char* what, int event = kEvent, double tolerance = 0.02) {
  const int frames = static_cast<int>(run.truth.size());
  std::vector<Eigen::Vector3d> estimate_before, truth_before;
  for (int i = 0; i < event; ++i) {
    estimate_before.push_back(run.poses.at(i).T_world_cam.translation());
    truth_before.push_back(run.truth[static_cast<std::size_t>(i)].translation());
  }
  SimilarityTransform alignment;
  ASSERT_EQ(alignUmeyama(estimate_before, truth_before, true, &alignment), "");
  double before_error = 0.0, after_error = 0.0, after_distance = 0.0;
  for (std::size_t i = 0; i < estimate_before.size(); ++i)
    before_error = std::max(before_error, (alignment * estimate_before[i] - truth_before[i]).norm());
  const Eigen::Vector3d event_position = run.truth[static_cast<std::size_t>(event)].translation();
  for (int i = event + 1; i < frames; ++i) {
    if (!run.poses.count(i)) continue;  // a dropped frame
    const Eigen::Vector3d truth = run.truth[static_cast<std::size_t>(i)].translation();
    after_error = std::max(after_error, (alignment * run.poses.at(i).T_world_cam.translation() - truth).norm());
    after_distance = std::max(after_distance, (truth - event_position).norm());
  }
  std::printf("odometry, %s at frame %d: largest position error %.3f m before it, %.3f m over the %.1f m after it\n", what,
              event, before_error, after_error, after_distance);
  EXPECT_LT(before_error, 0.1) << "the drive before the event is tracked to a few centimetres";
  // A new map at its own scale (the initialisation's median depth) or back at the origin would be
  // metres off; `tolerance` of the distance (2 % by default) allows a scale carried over to within
  // about as much (measured: 0.4 % after a blinded frame, 0.9 % after five).
  EXPECT_LT(after_error, tolerance * after_distance) << "odom must continue where it was, at the scale it had";
}

/// Parallel mapping tracks against keyframes that arrive a frame or two late, with fewer depth
/// measurements (measured on a lightly loaded machine: 0.8 % after a blinded frame, 1.0 % after a
/// repeated one or a restart, against 0.8, 0.4 and 1.2 % in deterministic mode; up to 2.1 % with a
/// busy loop on one of the two cores).
double continuityTolerance(MappingMode mapping) { return mapping == MappingMode::kParallel ? 0.04 : 0.02; }

/// Every frame but the blinded ones is trusted, those are lost; the first after them is tracked
/// again on the map it had.
void expectLostOnlyWhileBlinded(const DriveResult& run, int blinded_from, int blinded_frames) {
  for (const auto& [index, pose] : run.poses) {
    const bool blinded = index >= blinded_from && index < blinded_from + blinded_frames;
    EXPECT_EQ(pose.trusted, !blinded) << "frame " << index;
  }
  const FramePose& before = run.poses.at(blinded_from - 1);
  const FramePose& after = run.poses.at(blinded_from + blinded_frames);
  std::printf("odometry, blinded frames %d-%d: inlier ratio %.3f before, %.3f after, against keyframe %d / %d\n", blinded_from,
              blinded_from + blinded_frames - 1, before.tracking.inlierRatio(), after.tracking.inlierRatio(), before.keyframe_id,
              after.keyframe_id);
  EXPECT_TRUE(after.recovered) << "the first frame after the blinded ones";
  EXPECT_EQ(after.keyframe_id, before.keyframe_id) << "tracked on the map it had";
}

void expectLostOnlyAtTheBlindedFrame(MappingMode mapping) {
  const DriveResult run = drive(Event::kBlindedFrame, mapping);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames)) << "every frame gets a pose";
  EXPECT_EQ(run.poses.at(kEvent).state, OdometryState::kLost);
  expectLostOnlyWhileBlinded(run, kEvent, 1);
  expectContinuousAcross(run, "a blinded frame", kEvent, continuityTolerance(mapping));
}

TEST(Odometry, ABlindedFrameIsLostThenTrackingResumesWithOdomContinuous) { expectLostOnlyAtTheBlindedFrame(MappingMode::kDeterministic); }

/// The frame at kEvent shows another moment of the drive: it is not trusted and makes no keyframe;
/// the next frame is tracked on the map as before, odom continuous.
void expectTheWrongFrameIsNotTrusted(Event event, const char* what, MappingMode mapping = MappingMode::kDeterministic) {
  const DriveResult run = drive(event, mapping);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames)) << "every frame gets a pose";
  const FramePose& wrong = run.poses.at(kEvent);
  std::printf("odometry, %s: state %s, motion %.2f of the usual travel away from the prediction\n", what, toString(wrong.state),
              wrong.motion_deviation);
  EXPECT_FALSE(wrong.trusted);
  EXPECT_FALSE(wrong.keyframe);
  for (int i = 0; i < kFrames; ++i)
    if (i != kEvent) EXPECT_TRUE(run.poses.at(i).trusted) << "frame " << i;
  if (mapping == MappingMode::kDeterministic)  // (parallel mapping may hand tracking a new keyframe at any frame)
    EXPECT_EQ(run.poses.at(kEvent + 1).keyframe_id, run.poses.at(kEvent - 1).keyframe_id) << "tracked on against the keyframe before";
  expectContinuousAcross(run, what, kEvent, continuityTolerance(mapping));
}

TEST(Odometry, ARepeatedFrameIsNotTrustedAndMakesNoKeyframe) {
  expectTheWrongFrameIsNotTrusted(Event::kRepeatedFrame, "a frame repeated");
}

TEST(Odometry, AFrameThirtyFramesAheadIsNotTrustedAndMakesNoKeyframe) {
  expectTheWrongFrameIsNotTrusted(Event::kFrameFromLater, "a frame from 30 frames later");
}

void expectANewMapWhereTheOldOneWas(MappingMode mapping) {
  const DriveResult run = drive(Event::kRestart, mapping);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames)) << "every frame gets a pose";
  for (int i = 0; i < kFrames; ++i) EXPECT_TRUE(run.poses.at(i).trusted) << "frame " << i;
  EXPECT_TRUE(run.poses.at(kEvent).recovered) << "the frame after the restart starts the new map";
  EXPECT_TRUE(run.poses.at(kEvent).keyframe);
  expectContinuousAcross(run, "a restart", kEvent, continuityTolerance(mapping));
}

TEST(Odometry, ARestartStartsANewMapWhereTheOldOneWas) { expectANewMapWhereTheOldOneWas(MappingMode::kDeterministic); }

/// Frames of the car at rest (the camera still bounces a few millimetres).
std::vector<int> standingFrames(const DriveResult& run) {
  std::vector<int> standing;
  for (std::size_t i = 1; i < run.speed.size(); ++i)
    if (run.speed[i] == 0.0) standing.push_back(static_cast<int>(i));
  return standing;
}

TEST(Odometry, ACarStandingAtALightIsTrackedThroughOnTheMapItHad) {
  const DriveResult run = drive(Event::kStop);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kStopFrames)) << "every frame gets a pose";
  const std::vector<int> standing = standingFrames(run);
  ASSERT_GE(standing.size(), 25u) << "the drive must stand about 3 s at 10 Hz";
  ASSERT_LT(standing.back(), kStopFrames - 25) << "and drive on for a while after";
  for (int i = 0; i < kStopFrames; ++i) EXPECT_TRUE(run.poses.at(i).trusted) << "frame " << i;
  // Without parallax a new keyframe would measure no depth (every keyframe_max_interval frames);
  // the first frames at rest may still take the travel since the last keyframe, none after that.
  // Measured: one keyframe; with keyframe_min_parallax 0, three, frames 69-81 lost and the map
  // started again 19 m off.
  int standing_keyframes = 0;
  for (int i : standing) standing_keyframes += run.poses.at(i).keyframe ? 1 : 0;
  EXPECT_LE(standing_keyframes, 1) << "keyframes while standing";
  double drift = 0.0;  // of the estimate while standing, relative to the distance driven before
  for (int i : standing)
    drift = std::max(drift, (run.poses.at(i).T_world_cam.translation() - run.poses.at(standing.front() - 1).T_world_cam.translation()).norm());
  const double driven = run.poses.at(standing.front() - 1).T_world_cam.translation().norm();
  std::printf("odometry, a stop: frames %d-%d standing, the estimate moved %.4f of the %.3f map units driven before\n",
              standing.front(), standing.back(), drift, driven);
  EXPECT_LT(drift, 0.01 * driven) << "standing still must stay still";
  expectContinuousAcross(run, "a stop", standing.front());
}

TEST(Odometry, AStartWhoseFirstSecondIsDroppedIsTrackedFromTheMotionBeforeTheStop) {
  // Standing, every motion guess is "no motion"; 0.9 m later the fastest recent motion (before the
  // stop) is the guess that finds the frame.
  const DriveResult run = drive(Event::kStopThenFramesDropped);
  const std::vector<int> standing = standingFrames(run);
  ASSERT_FALSE(standing.empty());
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kStopFrames - kDroppedAtStart)) << "every frame that arrives gets a pose";
  for (const auto& [index, pose] : run.poses) EXPECT_TRUE(pose.trusted) << "frame " << index;
  const int first_after_gap = standing.back() + kDroppedAtStart + 1;
  std::printf("odometry, the first frame after the dropped start: guess %d won\n", run.poses.at(first_after_gap).tracking.guess);
  EXPECT_EQ(run.poses.at(first_after_gap).tracking.guess, 4) << "the driving travel (guess 4) must find it";
  // Measured over the 7.1 m after the stop: 0.72 m; without that guess 5.2 m (a new map). The frame
  // after the gap becomes a keyframe, triangulated against the standing one from a pose whose forward
  // travel is weakly observed: small changes of that pose move the map's scale after it by up to
  // about 17 % (0.15 m before the guesses counted the dropped frames from the stamps; run_sequence
  // on three seeds of this drive, fused SNNF, gave the same Sim(3) ATE before and after).
  expectContinuousAcross(run, "a stop, the start's first second dropped", standing.front(), 0.15);
}

TEST(Odometry, AVanCrossingInFrontOfTheCarStandingAtALightLeavesTheMapItHad) {
  // Standing, a new initialisation has no parallax until the car drives off, and nothing to take
  // the scale from: the view comes back, and with it the map it had.
  const DriveResult run = drive(Event::kStopWhileBlinded);
  const std::vector<int> standing = standingFrames(run);
  ASSERT_GE(standing.size(), 25u);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kStopFrames)) << "every frame gets a pose";
  expectLostOnlyWhileBlinded(run, standing.front() + kBlindedIntoStop, kBlindedFrames);
  // Measured: 0.116 and 0.150 m over the 7.1 m after the stop (1.6 and 2.1 %) with two versions of
  // the window that differ only in their rounding path (one Ceres block per residual, or per
  // observation); a new map at its own scale would be metres off.
  expectContinuousAcross(run, "a view blocked while standing", standing.front(), 0.03);
}

TEST(Odometry, HalfASecondBlindedWhileDrivingIsTrackedOnTheMapItHad) {
  const DriveResult run = drive(Event::kBlindedWhileDriving);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames)) << "every frame gets a pose";
  expectLostOnlyWhileBlinded(run, kEvent, kBlindedFrames);
  expectContinuousAcross(run, "half a second blinded");
}

TEST(Odometry, AViewThatChangesForGoodMakesAKeyframeWithinAFrame) {
  // The keyframe's points under the truck stop matching (a lower inlier ratio) while the flow, the
  // points in view and the interval say nothing (keyframe_min_inliers). Measured: the truck's first
  // frame becomes the keyframe (inlier ratio 0.85 before, 0.66 at it); without the rule, a frame
  // after it was not trusted and the keyframe came four frames later.
  const DriveResult run = drive(Event::kCoveredForGood);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames)) << "every frame gets a pose";
  for (int i = 0; i < kFrames; ++i) EXPECT_TRUE(run.poses.at(i).trusted) << "frame " << i;
  int first_keyframe = -1;
  for (int i = kEvent; i < kFrames && first_keyframe < 0; ++i)
    if (run.poses.at(i).keyframe) first_keyframe = i;
  std::printf("odometry, the right %.0f %% covered from frame %d on: inlier ratio %.2f before, %.2f at it; next keyframe at frame %d\n",
              100 * kCoveredShare, kEvent, run.poses.at(kEvent - 1).tracking.inlierRatio(), run.poses.at(kEvent).tracking.inlierRatio(),
              first_keyframe);
  EXPECT_GE(first_keyframe, kEvent);
  EXPECT_LE(first_keyframe, kEvent + 1) << "a keyframe from the changed view within a frame";
  expectContinuousAcross(run, "the view covered for good");
}

TEST(Odometry, FramesDroppedWhileDrivingAreCountedFromTheStamps) {
  // The frame after the gap moved four frame intervals: the constant-velocity guesses scale with
  // the stamps. Measured: 0.059 m over the 15.2 m after the gap; without, frame 27 (the first
  // after it) lost and a new map, 1.9 m.
  const DriveResult run = drive(Event::kFramesDropped);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kFrames - kDroppedWhileDriving)) << "every frame that arrives gets a pose";
  for (const auto& [index, pose] : run.poses) EXPECT_TRUE(pose.trusted) << "frame " << index;
  expectContinuousAcross(run, "three frames dropped");
}

TEST(Odometry, PredictionsWhileLostEndFiftyFramesAfterTheLastTrustedPose) {
  // A loss it never recovers from (the camera blinded for good): the untrusted predictions go on at
  // the velocity before it for 5 s, then stand (the car may have stopped; without the bound they
  // drove on for ever, and a new map would start wherever they had got to).
  constexpr int kDeadReckoning = 50;  // Odometry::kMaxDeadReckoning
  const DriveResult run = drive(Event::kBlindedForGood);
  ASSERT_EQ(run.poses.size(), static_cast<std::size_t>(kStopFrames)) << "every frame gets a pose";
  for (int i = kEvent; i < kStopFrames; ++i) EXPECT_FALSE(run.poses.at(i).trusted) << "frame " << i;
  const auto position = [&run](int i) { return run.poses.at(i).T_world_cam.translation(); };
  const int last_trusted = kEvent - 1, end = last_trusted + kDeadReckoning;
  const double step = (position(last_trusted) - position(last_trusted - 1)).norm();
  std::printf("odometry, blinded for good from frame %d: predicted %.3f map units on by frame %d (%.3f a frame), %.2g more after\n",
              kEvent, (position(end) - position(last_trusted)).norm(), end, step, (position(kStopFrames - 1) - position(end)).norm());
  EXPECT_NEAR((position(end) - position(last_trusted)).norm(), kDeadReckoning * step, 0.05 * kDeadReckoning * step)
      << "constant velocity up to the bound";
  for (int i = end + 1; i < kStopFrames; ++i) EXPECT_LT((position(i) - position(end)).norm(), 1e-9) << "frame " << i;
}

// The same with mapping on its own thread (the live default): tracking hands each trusted frame over
// and tracks against the newest keyframe mapping made, without waiting for it.
TEST(ParallelMapping, ABlindedFrameIsLostThenTrackingResumesWithOdomContinuous) {
  expectLostOnlyAtTheBlindedFrame(MappingMode::kParallel);
}

TEST(ParallelMapping, ARepeatedFrameIsNotTrustedAndMakesNoKeyframe) {
  expectTheWrongFrameIsNotTrusted(Event::kRepeatedFrame, "a frame repeated, parallel mapping", MappingMode::kParallel);
}

TEST(ParallelMapping, ARestartStartsANewMapWhereTheOldOneWas) { expectANewMapWhereTheOldOneWas(MappingMode::kParallel); }

TEST(ParallelMapping, TheFrameAfterOneThatAskedForAKeyframeIsTrackedAgainstIt) {
  // Frames come faster than mapping makes keyframes (no camera rate here): without waiting, the
  // frames after one whose flow asked for a keyframe would be tracked farther and farther from the
  // old keyframe.
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 1));
  const FrameBuilder builder(FrameBuilderOptions{}, sequence.camera(), ClassTable::cityscapes().names());
  OdometryOptions options;
  options.keyframe_flow = 15.0;  // px: most keyframes of this short drive by their flow
  // A slow window: mapping is still on the last keyframe when the next one is asked for.
  options.window_optimizer.max_iterations = 30;
  options.window_optimizer.point_stride = 1;
  Odometry odometry(options, sequence.camera(), MappingMode::kParallel);
  std::map<int, FramePose> poses;
  std::map<int, int> keyframe_id_of_frame;
  const auto takeKeyframes = [&] {
    for (const auto& window : odometry.takeNewWindows()) keyframe_id_of_frame[window->frame_index] = window->keyframes.back()->id;
  };
  for (int i = 0; i < 60; ++i) {
    ExtractionError error;
    for (const FramePose& pose : odometry.process(builder.build(i, sequence.frame(i).time, sequence.frame(i).gray, ClassEvidence{}, &error)))
      poses[pose.index] = pose;
    takeKeyframes();
  }
  odometry.finishMapping();
  takeKeyframes();
  int checked = 0;
  for (const auto& [frame, keyframe_id] : keyframe_id_of_frame) {
    const auto asked = poses.find(frame), next = poses.find(frame + 1);
    if (asked == poses.end() || next == poses.end() || !asked->second.trusted || !next->second.trusted) continue;
    if (!(asked->second.tracking.mean_flow > options.keyframe_flow)) continue;
    EXPECT_GE(next->second.keyframe_id, keyframe_id) << "frame " << frame + 1 << " after keyframe " << keyframe_id << " (frame " << frame << ")";
    ++checked;
  }
  std::printf("parallel mapping: %d keyframes asked for by their flow, each tracked against by the next frame\n", checked);
  EXPECT_GE(checked, 5);
}

TEST(ParallelMapping, TheOdometryStopsWhileMappingIsBusy) {
  // Destroyed right after the frames that make keyframes (a bag played again, shutdown): the
  // mapping thread finishes the request it is on and stops; nothing hangs or crashes.
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 1));
  const FrameBuilder builder(FrameBuilderOptions{}, sequence.camera(), ClassTable::cityscapes().names());
  for (int frames : {20, 26, 32}) {
    Odometry odometry(OdometryOptions{}, sequence.camera(), MappingMode::kParallel);
    int trusted = 0;
    for (int i = 0; i < frames; ++i) {
      ExtractionError error;
      for (const FramePose& pose : odometry.process(builder.build(i, sequence.frame(i).time, sequence.frame(i).gray, ClassEvidence{}, &error)))
        trusted += pose.trusted;
    }
    EXPECT_GT(trusted, 0) << frames << " frames";
  }
}

}  // namespace
}  // namespace semantic_edge_vo
