// The dense road fit: the plane under a camera from the lane ahead's texture in two rendered
// frames, at the scale of their relative translation, and no plane where the two views disagree.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "semantic_edge_vo/backend/dense_road_fit.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace {

constexpr double kHeight = 1.65;

double degreesBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::acos(std::min(1.0, a.dot(b))) * 180.0 / M_PI; }

class DenseRoadFit : public ::testing::Test {
 protected:
  DenseRoadFit() : sequence_(synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 2)) {
    options_.camera_height = kHeight;
  }

  /// The plane under frame `reference` measured against frame `other`, their motion scaled by
  /// `scale`; with `image`, that frame's image stands in for the other's.
  RoadFit fit(int reference, int other, double scale, double guess, int image = -1) {
    const synthetic::SyntheticFrame a = sequence_.frame(reference);
    synthetic::SyntheticFrame b = sequence_.frame(other);
    Eigen::Isometry3d T_other_reference = b.T_world_cam.inverse() * a.T_world_cam;
    if (image >= 0) b.gray = sequence_.frame(image).gray;
    T_other_reference.translation() *= scale;
    const ImagePyramid pyramid_a(a.gray, sequence_.camera(), 4), pyramid_b(b.gray, sequence_.camera(), 4);
    return DenseRoadFitter(options_, sequence_.camera()).fit(pyramid_a, pyramid_b, T_other_reference, guess);
  }

  synthetic::SyntheticSequence sequence_;
  RoadScaleOptions options_;
};

TEST_F(DenseRoadFit, FindsTheRoadUnderTheCameraFromTheFrameBefore) {
  for (int frame : {30, 60, 90}) {
    const RoadFit road = fit(frame, frame - 1, 1.0, 2.5 * kHeight);  // searched from far off
    ASSERT_TRUE(road.found) << "frame " << frame;
    std::printf("frame %d: the road %.3f m under the camera, its normal %.2f deg off the mounting's\n", frame, road.height,
                degreesBetween(road.down, options_.expectedDown()));
    EXPECT_NEAR(road.height, kHeight, 0.03 * kHeight) << "frame " << frame;
    EXPECT_LT(degreesBetween(road.down, options_.expectedDown()), 2.0) << "frame " << frame;
    EXPECT_GT(road.evidence, 300);
  }
}

TEST_F(DenseRoadFit, TheHeightIsInTheUnitsOfTheMotion) {
  const RoadFit metres = fit(60, 59, 1.0, kHeight), small = fit(60, 59, 0.25, 0.25 * kHeight * 0.5);
  ASSERT_TRUE(metres.found);
  ASSERT_TRUE(small.found);
  EXPECT_NEAR(small.height / metres.height, 0.25, 0.005);
}

TEST_F(DenseRoadFit, FindsNoRoadWhereTheViewsDoNotAgree) {
  // Another stretch of the drive in the frame before's place: no plane carries one lane onto the other.
  EXPECT_FALSE(fit(60, 59, 1.0, kHeight, 200).found);
  EXPECT_FALSE(fit(60, 60, 1.0, kHeight).found) << "no motion, no parallax: the height is not measured";
}

}  // namespace
}  // namespace semantic_edge_vo
