// Corner tracks and the two-view motion they measure between keyframes.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/backend/corner_tracks.h"
#include "semantic_edge_vo/backend/keyframe_motion.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"
#include "semantic_edge_vo/backend/two_view_geometry.h"

namespace semantic_edge_vo {
namespace {

double degrees(double radians) { return radians * 180.0 / M_PI; }
double radiansOf(double degrees) { return degrees * M_PI / 180.0; }

TEST(TwoViewMotion, RecoversRotationAndDirectionDespiteOutliers) {
  const PinholeCamera camera = kittiCamera();
  // Forward travel 3 degrees to the right of the axis, with a 1 degree turn: a car on a bend.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d centre = 1.5 * Eigen::Vector3d(std::sin(3.0 * M_PI / 180.0), 0.0, std::cos(3.0 * M_PI / 180.0));
  const Eigen::Vector3d t = -R * centre;  // x_second = R x_first + t
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, camera.width), v(0.0, camera.height), depth(5.0, 60.0);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<cv::Point2f> first, second;
  std::vector<bool> outlier;
  while (first.size() < 300) {
    const Eigen::Vector3d p = camera.backProject(u(random), v(random), depth(random));
    const Eigen::Vector3d q = R * p + t;
    const Eigen::Vector2d a = camera.project(p), b = camera.project(q);
    if (q.z() <= 0.0 || !camera.contains(b.x(), b.y())) continue;
    // A fifth of the tracks slid 8 px across their epipolar line (along it, no two views can tell).
    const bool wrong = first.size() % 5 == 0;
    const Eigen::Vector2d along = (b - camera.project(-t)).normalized();
    const Eigen::Vector2d slid = b + (wrong ? 8.0 : 0.0) * Eigen::Vector2d(-along.y(), along.x());
    first.emplace_back(static_cast<float>(a.x()), static_cast<float>(a.y()));
    second.emplace_back(static_cast<float>(slid.x() + noise(random)), static_cast<float>(slid.y() + noise(random)));
    outlier.push_back(wrong);
  }
  TwoViewMotion motion;
  ASSERT_TRUE(estimateTwoViewMotion(first, second, camera, 0.5, 50, &motion));
  EXPECT_LT(degrees(Eigen::AngleAxisd(motion.R_second_first.transpose() * R).angle()), 0.05);
  EXPECT_LT(degrees(std::acos(std::min(1.0, motion.t_second_first.dot(t.normalized())))), 0.5);
  int outliers_kept = 0;
  for (std::size_t i = 0; i < outlier.size(); ++i) outliers_kept += outlier[i] && motion.inliers[i];
  EXPECT_EQ(outliers_kept, 0);
  EXPECT_GE(motion.inlier_count, 200);
  // Too few agreeing correspondences: no motion.
  EXPECT_FALSE(estimateTwoViewMotion(first, second, camera, 0.5, 290, &motion));
}

TEST(TwoViewMotion, VehicleMotionHoldsOnDistantCornersAndParallelTraffic) {
  const PinholeCamera camera = kittiCamera();
  // A car on a bend: 1 degree of yaw to the left, travelling along the chord (half the turn).
  const ForwardMotionOptions forward;
  const Eigen::Matrix3d R_first_second = Eigen::AngleAxisd(-1.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d travel = 2.0 * forward.chord(R_first_second);  // the second centre, first view
  const Eigen::Matrix3d R = R_first_second.transpose();                  // x_second = R x_first + t
  std::mt19937 random(11);
  std::uniform_real_distribution<double> u(0.0, camera.width), v(0.0, camera.height), depth(40.0, 300.0), speed(-1.0, 2.0);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<cv::Point2f> first, second;
  enum class Kind { kStatic, kTraffic, kOutlier };
  std::vector<Kind> kinds;
  while (first.size() < 300) {
    // Distant static corners; every fourth on a vehicle driving along the road (its own travel is
    // parallel to ours: the same epipole); every tenth slid 6 px across its epipolar line.
    const Kind kind = first.size() % 10 == 0 ? Kind::kOutlier : first.size() % 4 == 0 ? Kind::kTraffic : Kind::kStatic;
    const Eigen::Vector3d p = camera.backProject(u(random), v(random), depth(random));
    const Eigen::Vector3d own_travel = (kind == Kind::kTraffic ? speed(random) : 0.0) * travel;
    const Eigen::Vector3d q = R * (p + own_travel - travel);
    const Eigen::Vector2d a = camera.project(p);
    Eigen::Vector2d b = camera.project(q);
    if (q.z() <= 0.0 || !camera.contains(b.x(), b.y())) continue;
    if (kind == Kind::kOutlier) {
      const Eigen::Vector2d along = (b - camera.project(R * travel)).normalized();
      b += (first.size() % 20 == 0 ? 6.0 : -6.0) * Eigen::Vector2d(-along.y(), along.x());  // both sides
    }
    first.emplace_back(static_cast<float>(a.x()), static_cast<float>(a.y()));
    second.emplace_back(static_cast<float>(b.x() + noise(random)), static_cast<float>(b.y() + noise(random)));
    kinds.push_back(kind);
  }
  TwoViewMotion motion;
  // From no rotation at all (the tracker's guess is usually far closer).
  ASSERT_TRUE(estimateVehicleMotion(first, second, camera, forward, 0.5, 50, Eigen::Matrix3d::Identity(), &motion));
  EXPECT_LT(degrees(Eigen::AngleAxisd(motion.R_second_first.transpose() * R).angle()), 0.02);
  EXPECT_LT(degrees(std::acos(std::min(1.0, motion.t_second_first.dot(-(R * travel).normalized())))), 0.02);
  EXPECT_NEAR(motion.t_second_first.norm(), 1.0, 1e-9);
  int outliers_kept = 0, traffic_kept = 0, traffic = 0;
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    outliers_kept += kinds[i] == Kind::kOutlier && motion.inliers[i];
    traffic += kinds[i] == Kind::kTraffic;
    traffic_kept += kinds[i] == Kind::kTraffic && motion.inliers[i];
  }
  EXPECT_EQ(outliers_kept, 0);
  EXPECT_GE(traffic_kept, traffic * 8 / 10);  // noise puts a few beyond 0.5 px
  EXPECT_FALSE(estimateVehicleMotion(first, second, camera, forward, 0.5, 295, Eigen::Matrix3d::Identity(), &motion));

  // The same views the other way round: the second camera turned back and reversing along the chord.
  ASSERT_TRUE(estimateVehicleMotion(second, first, camera, forward, 0.5, 50, Eigen::Matrix3d::Identity(), &motion));
  EXPECT_LT(degrees(Eigen::AngleAxisd(motion.R_second_first * R).angle()), 0.02);
  const Eigen::Vector3d back_centre = -motion.R_second_first.transpose() * motion.t_second_first;  // first centre, seen from the second
  EXPECT_LT(degrees(std::acos(std::min(1.0, back_centre.dot((R * -travel).normalized())))), 0.02);
}

TEST(CornerTracks, FollowsAShiftedImageAndStartsAtCorners) {
  cv::Mat texture(240, 320, CV_8UC1);
  cv::RNG(3).fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 0, 255, cv::NORM_MINMAX);
  const cv::Point2f shift(3.5f, -2.25f);
  const cv::Mat to = (cv::Mat_<double>(2, 3) << 1, 0, shift.x, 0, 1, shift.y);
  cv::Mat moved;
  cv::warpAffine(texture, moved, to, texture.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);

  const std::vector<cv::Point2f> corners = detectCorners(texture, 100, 10.0);
  ASSERT_GE(corners.size(), 50u);
  for (const cv::Point2f& corner : corners) {
    EXPECT_TRUE(corner.x >= 0 && corner.y >= 0 && corner.x < texture.cols && corner.y < texture.rows);
  }
  CornerTracks tracks(15);
  tracks.reset(texture, corners);
  const std::size_t kept = tracks.track(moved);
  EXPECT_GE(kept, corners.size() * 8 / 10);  // only those near the border may go
  EXPECT_EQ(tracks.framesTracked(), 1);
  const cv::Rect interior(20, 20, texture.cols - 40, texture.rows - 40);  // the warp reflects at the border
  for (std::size_t i = 0; i < kept; ++i) {
    EXPECT_EQ(tracks.first()[i], corners[static_cast<std::size_t>(tracks.ids()[i])]);
    if (!interior.contains(tracks.first()[i])) continue;
    EXPECT_LT(cv::norm(tracks.current()[i] - tracks.first()[i] - shift), 0.1) << "track " << i;
  }
  tracks.reset(texture, {});
  EXPECT_EQ(tracks.track(moved), 0u);  // nothing to follow, and no throw
}

double directionOffDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return degrees(std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)));
}

TEST(KeyframeMotion, MeasuresTheTrueMotionBetweenSyntheticKeyframes) {
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 3));
  KeyframeMotion motion(KeyframeMotionOptions{}, sequence.camera());
  const synthetic::SyntheticFrame keyframe = sequence.frame(10);
  motion.start(7, 10, keyframe.gray);
  EXPECT_EQ(motion.measure(10, Eigen::Matrix3d::Identity()).from_id, -1);  // nothing followed yet
  synthetic::SyntheticFrame last;
  for (int i = 11; i <= 16; ++i) {
    last = sequence.frame(i);
    motion.follow(i, last.gray);
  }
  EXPECT_EQ(motion.measure(15, Eigen::Matrix3d::Identity()).from_id, -1);  // not the frame the corners are in
  const MeasuredMotion measured = motion.measure(16, Eigen::Matrix3d::Identity());
  ASSERT_EQ(measured.from_id, 7);
  const Eigen::Isometry3d T_true = keyframe.T_world_cam.inverse() * last.T_world_cam;
  ASSERT_GT(T_true.translation().norm(), 3.0);  // the test drives: about 1.3 m per frame
  EXPECT_LT(degrees(Eigen::AngleAxisd(measured.R_from_this.transpose() * T_true.linear()).angle()), 0.1);
  EXPECT_LT(directionOffDeg(measured.direction, T_true.translation()), 1.0);
  EXPECT_NEAR(measured.direction.norm(), 1.0, 1e-9);

  // The next keyframe starts on the frame the corners were followed into (its pyramid is reused).
  motion.start(8, 16, last.gray);
  synthetic::SyntheticFrame next;
  for (int i = 17; i <= 20; ++i) {
    next = sequence.frame(i);
    motion.follow(i, next.gray);
  }
  const MeasuredMotion from_next = motion.measure(20, Eigen::Matrix3d::Identity());
  ASSERT_EQ(from_next.from_id, 8);
  EXPECT_LT(directionOffDeg(from_next.direction, (last.T_world_cam.inverse() * next.T_world_cam).translation()), 1.0);
}

TEST(KeyframeMotion, OnABendAMeasurementOffTheChordIsReplacedByTheVehicleFit) {
  // A city corner: about 4.5 degrees of yaw from keyframe frame 60 to frame 63.
  synthetic::SyntheticSequence sequence(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 3));
  const Eigen::Isometry3d T_true = sequence.frame(60).T_world_cam.inverse() * sequence.frame(63).T_world_cam;
  ASSERT_GT(degrees(Eigen::AngleAxisd(T_true.linear()).angle()), 3.0);
  // The tracked rotation, 1 degree of yaw off, starts the fit.
  const Eigen::Matrix3d guess = T_true.linear() * Eigen::AngleAxisd(radiansOf(1.0), Eigen::Vector3d::UnitY()).toRotationMatrix();
  const auto measureWith = [&](double max_chord_deviation_deg, double mount_yaw_deg) {
    KeyframeMotionOptions options;
    options.max_chord_deviation_deg = max_chord_deviation_deg;
    options.forward_motion.yaw_deg = mount_yaw_deg;
    KeyframeMotion motion(options, sequence.camera());
    motion.start(7, 60, sequence.frame(60).gray);
    for (int i = 61; i <= 63; ++i) motion.follow(i, sequence.frame(i).gray);
    return std::make_pair(motion.measure(63, guess), options.forward_motion);
  };
  const auto rotationOffDeg = [&](const MeasuredMotion& m) { return degrees(Eigen::AngleAxisd(m.R_from_this.transpose() * T_true.linear()).angle()); };

  // Any sideways deviation at all is too much: the fit replaces the corners' own measurement.
  const auto [fitted, forward] = measureWith(1e-6, 0.0);
  ASSERT_EQ(fitted.from_id, 7);
  EXPECT_LT(directionOffDeg(fitted.direction, forward.chord(fitted.R_from_this)), 1e-6);  // on its chord, forward
  EXPECT_LT(rotationOffDeg(fitted), 0.1);                                                 // from 1 degree off
  EXPECT_LT(directionOffDeg(fitted.direction, T_true.translation()), 0.5);

  // Options that claim a mount travelling 5 degrees right of the optical axis: the true measurement is
  // off that chord and replaced; with the check off it is kept.
  const auto [replaced, claimed] = measureWith(2.0, 5.0);
  ASSERT_EQ(replaced.from_id, 7);
  EXPECT_LT(directionOffDeg(replaced.direction, claimed.chord(replaced.R_from_this)), 1e-6);
  EXPECT_GT(directionOffDeg(replaced.direction, T_true.translation()), 3.0);
  const MeasuredMotion kept = measureWith(0.0, 5.0).first;
  ASSERT_EQ(kept.from_id, 7);
  EXPECT_LT(rotationOffDeg(kept), 0.1);
  EXPECT_LT(directionOffDeg(kept.direction, T_true.translation()), 1.0);
}

TEST(KeyframeMotion, ReanchorsOnlyAKeyframeFarOffItsMeasuredMotionButNotImplausiblyFar) {
  Eigen::Isometry3d T_world_earlier = Eigen::Isometry3d::Identity();
  T_world_earlier.linear() = Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.1, 1.0, 0.0).normalized()).toRotationMatrix();
  T_world_earlier.translation() = Eigen::Vector3d(3.0, -0.2, 10.0);
  MeasuredMotion measured;
  measured.from_id = 1;
  measured.R_from_this = Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY()).toRotationMatrix();
  measured.direction = Eigen::Vector3d(0.02, 0.0, 1.0).normalized();
  const auto newPose = [&](double direction_off_deg, double rotation_off_deg) {
    Eigen::Isometry3d T_earlier_new = Eigen::Isometry3d::Identity();
    T_earlier_new.linear() = measured.R_from_this * Eigen::AngleAxisd(radiansOf(rotation_off_deg), Eigen::Vector3d::UnitY()).toRotationMatrix();
    T_earlier_new.translation() = 2.5 * (Eigen::AngleAxisd(radiansOf(direction_off_deg), Eigen::Vector3d::UnitY()) * measured.direction);
    return T_world_earlier * T_earlier_new;
  };
  const KeyframeMotionOptions options;  // 0.3 deg, 2 deg

  Eigen::Isometry3d near = newPose(1.5, 0.2);
  const Eigen::Isometry3d near_before = near;
  EXPECT_FALSE(reanchor(measured, options, T_world_earlier, &near));
  EXPECT_TRUE(near.isApprox(near_before));

  for (const auto& [direction_off, rotation_off] : {std::pair<double, double>{5.0, 0.0}, {0.0, 0.5}}) {
    Eigen::Isometry3d far = newPose(direction_off, rotation_off);
    EXPECT_TRUE(reanchor(measured, options, T_world_earlier, &far));
    const Eigen::Isometry3d T_earlier_new = T_world_earlier.inverse() * far;
    EXPECT_NEAR(T_earlier_new.translation().norm(), 2.5, 1e-9);  // the distance is kept
    EXPECT_LT(directionOffDeg(T_earlier_new.translation(), measured.direction), 1e-6);
    EXPECT_TRUE(T_earlier_new.linear().isApprox(measured.R_from_this, 1e-9));
  }

  Eigen::Isometry3d implausible = newPose(60.0, 0.0);  // beyond reanchor_max_direction: not believed
  const Eigen::Isometry3d implausible_before = implausible;
  EXPECT_FALSE(reanchor(measured, options, T_world_earlier, &implausible));
  EXPECT_TRUE(implausible.isApprox(implausible_before));

  MeasuredMotion unmeasured = measured;
  unmeasured.from_id = -1;
  Eigen::Isometry3d far = newPose(5.0, 0.0);
  EXPECT_FALSE(reanchor(unmeasured, options, T_world_earlier, &far));
}

}  // namespace
}  // namespace semantic_edge_vo
