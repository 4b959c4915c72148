// Geometric ground truth of the synthetic sequences: depth and poses agree to subpixel accuracy,
// class maps agree with the geometry.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

constexpr int kSky = 10, kRoad = 0;

SyntheticSequenceOptions smallOptions(SceneType scene, std::uint64_t seed) {
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(scene, seed);
  options.camera = kittiCamera().scaled(0.5);
  return options;
}

struct Reprojection {
  std::vector<double> errors;  // px, of points seen on one plane in both frames
  int occluded = 0;            // points hidden in the second frame
  int class_checked = 0, class_agreed = 0;
};

/// Points of frame i (every `step` px) moved with the ground-truth poses into frame j, where the
/// depth map is read at the subpixel projection (inverse depth is affine across a plane, so
/// bilinear interpolation of it is exact there) and the point is moved back into frame i.
Reprojection reproject(const SyntheticFrame& a, const SyntheticFrame& b, const PinholeCamera& camera, int step) {
  Reprojection result;
  const Eigen::Isometry3d T_b_a = b.T_world_cam.inverse() * a.T_world_cam;
  for (int y = step; y < camera.height - step; y += step)
    for (int x = step; x < camera.width - step; x += step) {
      const float depth = a.depth.at<float>(y, x);
      if (depth <= 0.0f || a.dynamic.at<std::uint8_t>(y, x)) continue;
      const Eigen::Vector3d point = T_b_a * camera.backProject(x, y, depth);
      if (point.z() < 1.0) continue;
      const Eigen::Vector2d q = camera.project(point);
      if (!camera.contains(q.x(), q.y(), 1.0)) continue;
      const int qx = static_cast<int>(std::lround(q.x())), qy = static_cast<int>(std::lround(q.y()));
      const float nearest_depth = b.depth.at<float>(qy, qx);
      if (nearest_depth > 0.0f && std::abs(nearest_depth - point.z()) < 0.03 * point.z() && !b.dynamic.at<std::uint8_t>(qy, qx)) {
        ++result.class_checked;
        result.class_agreed += b.class_id.at<std::uint8_t>(qy, qx) == a.class_id.at<std::uint8_t>(y, x);
      }
      const int x0 = static_cast<int>(std::floor(q.x())), y0 = static_cast<int>(std::floor(q.y()));
      double inverse[2][2];
      bool usable = true;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const float d = b.depth.at<float>(y0 + dy, x0 + dx);
          usable = usable && d > 0.0f && !b.dynamic.at<std::uint8_t>(y0 + dy, x0 + dx) &&
                   b.class_id.at<std::uint8_t>(y0 + dy, x0 + dx) == b.class_id.at<std::uint8_t>(y0, x0);
          inverse[dy][dx] = d > 0.0f ? 1.0 / d : 0.0;
        }
      // Four samples of one plane: the mixed difference of an affine function vanishes.
      if (!usable || std::abs(inverse[0][0] + inverse[1][1] - inverse[0][1] - inverse[1][0]) > 1e-5 * inverse[0][0]) continue;
      const double tx = q.x() - x0, ty = q.y() - y0;
      const double interpolated = (1 - ty) * ((1 - tx) * inverse[0][0] + tx * inverse[0][1]) +
                                  ty * ((1 - tx) * inverse[1][0] + tx * inverse[1][1]);
      if (std::abs(interpolated * point.z() - 1.0) > 0.01) {
        ++result.occluded;
        continue;
      }
      const Eigen::Vector2d back = camera.project(T_b_a.inverse() * camera.backProject(q.x(), q.y(), 1.0 / interpolated));
      result.errors.push_back((back - Eigen::Vector2d(x, y)).norm());
    }
  return result;
}

TEST(SyntheticGeometry, PointsReprojectWithSubpixelAccuracy) {
  for (SceneType scene : {SceneType::kCity, SceneType::kHighway}) {
    SyntheticSequence sequence(smallOptions(scene, 5));
    const SyntheticFrame a = sequence.frame(10), b = sequence.frame(13);
    const Reprojection result = reproject(a, b, sequence.camera(), 4);
    ASSERT_GT(result.errors.size(), 500u) << toString(scene);
    std::vector<double> errors = result.errors;
    std::sort(errors.begin(), errors.end());
    std::cout << toString(scene) << ": " << errors.size() << " points, reprojection error median "
              << errors[errors.size() / 2] << " px, max " << errors.back() << " px, " << result.occluded << " occluded\n";
    EXPECT_LT(errors[errors.size() / 2], 0.01) << toString(scene) << ": median reprojection error, px";
    EXPECT_LT(errors[errors.size() * 99 / 100], 0.05) << toString(scene) << ": 99th percentile, px";
    EXPECT_LT(result.occluded, static_cast<int>(result.errors.size() / 5)) << toString(scene);
    ASSERT_GT(result.class_checked, 500) << toString(scene);
    EXPECT_GT(result.class_agreed, 0.98 * result.class_checked) << toString(scene) << ": classes follow the geometry";
  }
}

TEST(SyntheticGeometry, SkyHasNoDepthAndEverythingElseHas) {
  SyntheticSequence sequence(smallOptions(SceneType::kVillage, 2));
  const SyntheticFrame frame = sequence.frame(4);
  int sky = 0;
  for (int y = 0; y < frame.depth.rows; ++y)
    for (int x = 0; x < frame.depth.cols; ++x) {
      const bool is_sky = frame.class_id.at<std::uint8_t>(y, x) == kSky;
      sky += is_sky;
      ASSERT_EQ(is_sky, frame.depth.at<float>(y, x) == 0.0f) << "pixel " << x << ", " << y;
    }
  EXPECT_GT(sky, frame.depth.total() / 20) << "the sky is visible";
}

TEST(SyntheticGeometry, RoadPixelsLieOnTheGroundBelowTheCamera) {
  SyntheticSequence sequence(smallOptions(SceneType::kCity, 9));
  const SyntheticFrame frame = sequence.frame(6);
  const PinholeCamera& camera = sequence.camera();
  int checked = 0;
  for (int y = 0; y < frame.depth.rows; y += 3)
    for (int x = 0; x < frame.depth.cols; x += 3) {
      const float depth = frame.depth.at<float>(y, x);
      if (frame.class_id.at<std::uint8_t>(y, x) != kRoad || depth > 15.0f) continue;
      // The camera is 1.65 m above the road; pitch and roll of the car tilt the plane a little.
      EXPECT_NEAR(camera.backProject(x, y, depth).y(), 1.65, 0.12) << "pixel " << x << ", " << y;
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

TEST(SyntheticGeometry, PosesStartAtIdentityAndMoveLikeACar) {
  for (SceneType scene : {SceneType::kCity, SceneType::kVillage, SceneType::kHighway}) {
    SyntheticSequence sequence(smallOptions(scene, 4));
    EXPECT_TRUE(sequence.pose(0).isApprox(Eigen::Isometry3d::Identity(), 1e-12)) << toString(scene);
    const double max_speed = sequence.options().world.ego.max_speed;
    double travelled = 0.0, turned = 0.0;
    for (int i = 1; i <= 600; ++i) {
      const Eigen::Isometry3d step = sequence.pose(i - 1).inverse() * sequence.pose(i);
      EXPECT_NEAR(sequence.time(i) - sequence.time(i - 1), 0.1, 1e-9);
      EXPECT_LE(step.translation().norm(), 0.1 * max_speed + 0.05) << toString(scene) << " frame " << i;
      EXPECT_GT(step.translation().z(), 0.0) << "driving forwards";
      travelled += step.translation().norm();
      turned += std::abs(Eigen::AngleAxisd(step.linear()).angle());
    }
    EXPECT_GT(travelled, 600 * 0.1 * sequence.options().world.ego.min_speed * 0.8) << toString(scene);
    EXPECT_GT(turned, 0.3) << toString(scene) << ": the route has turns";
  }
}

TEST(SyntheticGeometry, VibrationShakesTheCameraNotItsPath) {
  SyntheticSequenceOptions rough = smallOptions(SceneType::kCity, 4);
  rough.world.ego.vibration = 2.0 * M_PI / 180.0;  // make_synthetic_sequence --vibration 2
  SyntheticSequence smooth_sequence(smallOptions(SceneType::kCity, 4)), rough_sequence(rough);
  double largest = 0.0;  // rotation between the two frame-to-frame motions, deg
  for (int i = 1; i <= 200; ++i) {
    const Eigen::Isometry3d smooth_step = smooth_sequence.pose(i - 1).inverse() * smooth_sequence.pose(i);
    const Eigen::Isometry3d rough_step = rough_sequence.pose(i - 1).inverse() * rough_sequence.pose(i);
    EXPECT_NEAR(smooth_step.translation().norm(), rough_step.translation().norm(), 1e-9) << "frame " << i;
    largest = std::max(largest, Eigen::AngleAxisd(smooth_step.linear().transpose() * rough_step.linear()).angle() * 180.0 / M_PI);
  }
  // The default jitter is 0.086 deg; a 2 deg one turns a frame by up to twice that more than the smooth drive.
  EXPECT_GT(largest, 2.0);
  EXPECT_LT(largest, 6.0);
}

}  // namespace
}  // namespace synthetic
}  // namespace semantic_edge_vo
