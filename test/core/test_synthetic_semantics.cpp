// Semantic channels of the synthetic sequences and the network noise models.
#include <bitset>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/synthetic/network_noise.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

/// A frame rendered once for all tests here (a small city frame with its exact channels).
const SyntheticFrame& cityFrame() {
  static const SyntheticFrame frame = [] {
    SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(SceneType::kCity, 7);
    options.camera = kittiCamera().scaled(0.5);
    SyntheticSequence sequence(options);
    return sequence.frame(12);
  }();
  return frame;
}

int edgePixels(const SemanticNetworkOutput& out) { return cv::countNonZero(out.edge_strength); }

TEST(SyntheticSemantics, BoundariesCarryTheClassesOfBothSides) {
  const SyntheticFrame& frame = cityFrame();
  const SemanticNetworkOutput& out = frame.semantics;
  int boundaries = 0, texture = 0;
  for (int y = 1; y < frame.class_id.rows - 1; ++y)
    for (int x = 1; x < frame.class_id.cols - 1; ++x) {
      const int own = frame.class_id.at<std::uint8_t>(y, x);
      const int right = frame.class_id.at<std::uint8_t>(y, x + 1);
      const auto mask = static_cast<std::uint32_t>(out.edge_classes.at<std::int32_t>(y, x));
      if (right != own) {
        ++boundaries;
        ASSERT_EQ(out.edge_strength.at<std::uint8_t>(y, x), 255);
        ASSERT_TRUE(mask & (1u << own));
        ASSERT_TRUE(mask & (1u << right));
        EXPECT_FLOAT_EQ(out.edgeProbability(right, x, y), 1.0f);
        EXPECT_EQ(out.class_probability.at<cv::Vec4b>(y, x)[0], own);
      } else if (mask != 0 && out.edge_strength.at<std::uint8_t>(y, x) < 255) {
        ++texture;  // inside a class: its own class only
        ASSERT_EQ(mask, 1u << own);
      }
      if (mask == 0) {
        EXPECT_EQ(out.edge_strength.at<std::uint8_t>(y, x), 0);
      }
    }
  EXPECT_GT(boundaries, 500);
  EXPECT_GT(texture, 500) << "window frames, lane markings and joints give texture edges";
  EXPECT_TRUE(cv::countNonZero(out.topClass() != frame.class_id) == 0) << "no noise: the top class is the truth";
}

TEST(SyntheticSemantics, ZeroStrengthNoiseChangesNothing) {
  SemanticNetworkOutput out = cityFrame().semantics.clone();
  applyNetworkNoise(NetworkNoiseOptions{}, 1, &out);
  EXPECT_EQ(cv::norm(out.edge_strength, cityFrame().semantics.edge_strength, cv::NORM_INF), 0.0);
}

TEST(SyntheticSemantics, LabelConfusionSwapsToNeighbouringClasses) {
  const SyntheticFrame& frame = cityFrame();
  SemanticNetworkOutput out = frame.semantics.clone();
  NetworkNoiseOptions noise;
  noise.label_confusion = 0.5;
  applyNetworkNoise(noise, 3, &out);
  const cv::Mat top = out.topClass();
  int changed = 0;
  for (int y = 0; y < top.rows; ++y)
    for (int x = 0; x < top.cols; ++x) {
      const int truth = frame.class_id.at<std::uint8_t>(y, x), label = top.at<std::uint8_t>(y, x);
      if (label == truth) continue;
      ++changed;
      ASSERT_EQ(label, confusableClass(truth));
    }
  const double fraction = static_cast<double>(changed) / static_cast<double>(top.total());
  EXPECT_GT(fraction, 0.03);
  EXPECT_LT(fraction, 0.6);
}

TEST(SyntheticSemantics, EdgeNoiseModelsDoWhatTheySay) {
  const SemanticNetworkOutput& exact = cityFrame().semantics;
  const int exact_pixels = edgePixels(exact);
  NetworkNoiseOptions blur, missed, spurious;
  blur.edge_blur = 1.0;
  missed.missed_edges = 0.5;
  spurious.spurious_edges = 0.6;
  SemanticNetworkOutput blurred = exact.clone(), dropped = exact.clone(), extra = exact.clone();
  applyNetworkNoise(blur, 5, &blurred);
  applyNetworkNoise(missed, 5, &dropped);
  applyNetworkNoise(spurious, 5, &extra);
  EXPECT_GT(edgePixels(blurred), 1.5 * exact_pixels) << "thick edges";
  EXPECT_LT(edgePixels(dropped), 0.8 * exact_pixels) << "missed edges";
  EXPECT_GT(edgePixels(dropped), 0.2 * exact_pixels);
  EXPECT_GT(edgePixels(extra), exact_pixels + 200) << "spurious edges";
  // Every edge pixel keeps a label, and labels only where there is an edge.
  for (const SemanticNetworkOutput* out : {&blurred, &dropped, &extra})
    EXPECT_EQ(cv::countNonZero(out->edge_strength), cv::countNonZero(out->edge_classes));
  // Deterministic for a seed.
  SemanticNetworkOutput again = exact.clone();
  applyNetworkNoise(missed, 5, &again);
  EXPECT_EQ(cv::norm(again.edge_strength, dropped.edge_strength, cv::NORM_INF), 0.0);
}

TEST(SyntheticSemantics, EveryClassOfTheSceneTypesAppears) {
  // city: road, sidewalk, building, pole, traffic sign, sky, car; village: vegetation, terrain.
  auto classes = [](SceneType scene, int frames) {
    SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(scene, 3);
    options.camera = kittiCamera().scaled(0.3);
    options.semantics = false;
    SyntheticSequence sequence(options);
    std::bitset<32> seen;
    for (int i = 0; i < frames; i += 10) {
      const SyntheticFrame frame = sequence.frame(i);
      for (auto it = frame.class_id.begin<std::uint8_t>(); it != frame.class_id.end<std::uint8_t>(); ++it) seen.set(*it);
    }
    return seen;
  };
  const std::bitset<32> city = classes(SceneType::kCity, 200);
  for (int k : {0, 1, 2, 5, 7, 8, 10, 13}) EXPECT_TRUE(city.test(static_cast<std::size_t>(k))) << "city class " << k;
  const std::bitset<32> village = classes(SceneType::kVillage, 200);
  for (int k : {0, 2, 8, 9, 10}) EXPECT_TRUE(village.test(static_cast<std::size_t>(k))) << "village class " << k;
  const std::bitset<32> highway = classes(SceneType::kHighway, 200);
  for (int k : {0, 3, 4, 7, 9, 10, 13}) EXPECT_TRUE(highway.test(static_cast<std::size_t>(k))) << "highway class " << k;
}

}  // namespace
}  // namespace synthetic
}  // namespace semantic_edge_vo
