// The same seed gives the same sequence, whatever order the frames are asked in.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

SyntheticSequenceOptions smallOptions(SceneType scene, std::uint64_t seed) {
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(scene, seed);
  options.camera = kittiCamera().scaled(0.4);
  options.network_noise = {0.3, 0.3, 0.3, 0.3};
  return options;
}

bool same(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

void expectSameFrame(const SyntheticFrame& a, const SyntheticFrame& b) {
  EXPECT_TRUE(a.T_world_cam.isApprox(b.T_world_cam, 0.0));
  EXPECT_EQ(a.time, b.time);
  EXPECT_TRUE(same(a.gray, b.gray));
  EXPECT_TRUE(same(a.color, b.color));
  EXPECT_TRUE(same(a.depth, b.depth));
  EXPECT_TRUE(same(a.class_id, b.class_id));
  EXPECT_TRUE(same(a.dynamic, b.dynamic));
  EXPECT_TRUE(same(a.semantics.edge_strength, b.semantics.edge_strength));
  EXPECT_TRUE(same(a.semantics.edge_classes, b.semantics.edge_classes));
  EXPECT_TRUE(same(a.semantics.class_probability, b.semantics.class_probability));
}

TEST(SyntheticDeterminism, SameSeedSameFramesInAnyOrder) {
  for (SceneType scene : {SceneType::kCity, SceneType::kVillage, SceneType::kHighway}) {
    SCOPED_TRACE(toString(scene));
    SyntheticSequence forward(smallOptions(scene, 11)), jumping(smallOptions(scene, 11));
    SyntheticFrame forward_frame;
    for (int i = 0; i <= 40; i += 4) forward_frame = forward.frame(i);
    expectSameFrame(forward_frame, jumping.frame(40));
    expectSameFrame(forward.frame(3), jumping.frame(3));  // going back rebuilds what was dropped
  }
}

TEST(SyntheticDeterminism, OtherSeedOtherWorld) {
  SyntheticSequence a(smallOptions(SceneType::kCity, 1)), b(smallOptions(SceneType::kCity, 2));
  const SyntheticFrame fa = a.frame(20), fb = b.frame(20);
  EXPECT_FALSE(same(fa.class_id, fb.class_id));
  EXPECT_FALSE(fa.T_world_cam.isApprox(fb.T_world_cam, 1e-6));
}

TEST(SyntheticDeterminism, InvalidOptionsAreNamed) {
  SyntheticSequenceOptions options = smallOptions(SceneType::kCity, 1);
  EXPECT_EQ(options.validate(), "");
  options.network_noise.edge_blur = 1.5;
  EXPECT_NE(options.validate().find("edge_blur"), std::string::npos);
  options = smallOptions(SceneType::kCity, 1);
  options.world.ego.min_speed = 0.0;
  EXPECT_NE(options.validate().find("min_speed"), std::string::npos);
}

}  // namespace
}  // namespace synthetic
}  // namespace semantic_edge_vo
