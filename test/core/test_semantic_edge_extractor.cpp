#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/edges/semantic_edge_extractor.h"

namespace semantic_edge_vo {
namespace {

constexpr int kWidth = 80, kHeight = 60, kClasses = 19, kRoad = 0, kPole = 5, kCar = 13;
constexpr double kColumn = 30.3;  // subpixel column of the boundary

/// Dark road on the left, bright car on the right, the boundary at kColumn.
cv::Mat boundaryImage() {
  cv::Mat image(kHeight, kWidth, CV_32F);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      image.at<float>(y, x) = static_cast<float>(50.0 + 150.0 * std::clamp(x + 0.5 - kColumn, 0.0, 1.0));
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.2);
  cv::Mat gray;
  image.convertTo(gray, CV_8U);
  return gray;
}

/// Class probabilities: road 0.9 left of the boundary, car 0.8 right of it, the rest spread thinly.
cv::Mat regionProbabilities() {
  cv::Mat probabilities(kHeight, kWidth, CV_32FC(kClasses), cv::Scalar::all(0.0));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      float* p = probabilities.ptr<float>(y) + x * kClasses;
      const bool left = x < kColumn;
      for (int c = 0; c < kClasses; ++c) p[c] = 0.1f / (kClasses - 1);
      p[left ? kRoad : kCar] = left ? 0.9f : 0.8f;
    }
  return probabilities;
}

/// Per-class edge probabilities: a ridge at kColumn for road (0.8) and car (0.6), a faint one for pole.
cv::Mat classEdgeProbabilities() {
  cv::Mat edges(kHeight, kWidth, CV_32FC(kClasses), cv::Scalar::all(0.0));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const float ridge = static_cast<float>(std::exp(-0.5 * std::pow((x - kColumn) / 1.0, 2)));
      float* p = edges.ptr<float>(y) + x * kClasses;
      p[kRoad] = 0.8f * ridge;
      p[kCar] = 0.6f * ridge;
      p[kPole] = 0.1f * ridge;
    }
  return edges;
}

SemanticEdgeOptions optionsFor(IntakeMode mode) {
  SemanticEdgeOptions options;
  options.mode = mode;
  options.canny.blur_sigma = 0.0;
  return options;
}

void expectBoundaryEdges(const EdgeSet& edges, std::uint32_t expected_mask, double position_tolerance) {
  ASSERT_GT(edges.size(), 40u);
  double mean_u = 0.0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    mean_u += edges.u[i];
    EXPECT_EQ(edges.class_mask[i], expected_mask) << "edge " << i << " at " << edges.u[i] << ", " << edges.v[i];
    EXPECT_NEAR(edges.normal_x[i], 1.0f, 0.02f) << "dark (road) to bright (car)";
    EXPECT_GT(edges.strength[i], 0.0f);
    EXPECT_LE(edges.strength[i], 1.0f);
  }
  EXPECT_NEAR(mean_u / static_cast<double>(edges.size()), kColumn, position_tolerance);
}

TEST(SemanticEdgeExtractor, CannyModeGivesTheSingleEdgeClass) {
  EdgeSet edges;
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kCanny)).extract(boundaryImage(), {}, {}, &edges));
  expectBoundaryEdges(edges, 1u, 0.05);
}

TEST(SemanticEdgeExtractor, FusedBoundaryPixelBelongsToBothSides) {
  const ClassEvidence classes{ClassEvidenceForm::kProbabilities, regionProbabilities(), kClasses};
  EdgeSet edges;
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kFused)).extract(boundaryImage(), classes, {}, &edges));
  expectBoundaryEdges(edges, (1u << kRoad) | (1u << kCar), 0.05);
  // Strength stays the Canny strength: the same edges as in canny mode, with the same strengths.
  EdgeSet canny;
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kCanny)).extract(boundaryImage(), {}, {}, &canny));
  ASSERT_EQ(edges.size(), canny.size());
  for (std::size_t i = 0; i < edges.size(); ++i) EXPECT_EQ(edges.strength[i], canny.strength[i]) << "edge " << i;

  // 8-bit probabilities and the compact label form give the same classes.
  cv::Mat bytes;
  classes.values.convertTo(bytes, CV_8U, 255.0);
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kFused))
                   .extract(boundaryImage(), {ClassEvidenceForm::kProbabilities, bytes, kClasses}, {}, &edges));
  expectBoundaryEdges(edges, (1u << kRoad) | (1u << kCar), 0.05);
  cv::Mat labels(kHeight, kWidth, CV_8UC2);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) labels.at<cv::Vec2b>(y, x) = x < kColumn ? cv::Vec2b(kRoad, 230) : cv::Vec2b(kCar, 200);
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kFused))
                   .extract(boundaryImage(), {ClassEvidenceForm::kLabels, labels, kClasses}, {}, &edges));
  expectBoundaryEdges(edges, (1u << kRoad) | (1u << kCar), 0.05);
}

TEST(SemanticEdgeExtractor, FusedEdgesWithoutClassEvidenceAreDropped) {
  // Labels: road left of the boundary, unlabeled (index >= C) right of it up to the image's end,
  // in the upper half; road everywhere in the lower half.
  cv::Mat labels(kHeight, kWidth, CV_8UC2, cv::Scalar(kRoad, 255));
  labels(cv::Rect(kColumn - 6, 0, kWidth - kColumn + 6, kHeight / 2)).setTo(cv::Scalar(255, 255));
  EdgeSet edges;
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kFused))
                   .extract(boundaryImage(), {ClassEvidenceForm::kLabels, labels, kClasses}, {}, &edges));
  ASSERT_FALSE(edges.u.empty());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    EXPECT_EQ(edges.class_mask[i], 1u << kRoad);
    EXPECT_GT(edges.v[i], kHeight / 2 - 3.0f) << "an edge among unlabeled pixels was kept";
    EXPECT_GT(edges.strength[i], 0.0f);
  }
  EXPECT_EQ(edges.strength.size(), edges.size());
}

TEST(SemanticEdgeExtractor, FusedWithALearnedEdgeMap) {
  cv::Mat edge_probability(kHeight, kWidth, CV_32F);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      edge_probability.at<float>(y, x) = static_cast<float>(0.9 * std::exp(-0.5 * std::pow(x - kColumn, 2)));
  const ClassEvidence classes{ClassEvidenceForm::kProbabilities, regionProbabilities(), kClasses};
  EdgeSet edges;
  ASSERT_FALSE(SemanticEdgeExtractor(optionsFor(IntakeMode::kFused)).extract(boundaryImage(), classes, edge_probability, &edges));
  expectBoundaryEdges(edges, (1u << kRoad) | (1u << kCar), 0.15);
  EXPECT_EQ(edges.size(), static_cast<std::size_t>(kHeight - 4)) << "one pixel per row: thinned";
}

TEST(SemanticEdgeExtractor, PerClassEdgeProbabilitiesAndTheBitmaskForm) {
  EdgeSet edges;
  const SemanticEdgeExtractor extractor(optionsFor(IntakeMode::kSemanticEdges));
  ASSERT_FALSE(extractor.extract(boundaryImage(), {ClassEvidenceForm::kProbabilities, classEdgeProbabilities(), kClasses}, {}, &edges));
  expectBoundaryEdges(edges, (1u << kRoad) | (1u << kCar), 0.15);  // the faint pole ridge stays out
  EXPECT_EQ(edges.size(), static_cast<std::size_t>(kHeight - 4));

  // Compact: class bits (road, car) on a 3-pixel band, strength as a ridge.
  cv::Mat bitmask(kHeight, kWidth, CV_8UC4, cv::Scalar::all(0));
  const std::uint32_t bits = (1u << kRoad) | (1u << kCar);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 29; x <= 31; ++x) {
      const double strength = 0.9 * std::exp(-0.5 * std::pow(x - kColumn, 2));
      bitmask.at<cv::Vec4b>(y, x) = cv::Vec4b(bits & 0xff, (bits >> 8) & 0xff, (bits >> 16) & 0xff,
                                              static_cast<std::uint8_t>(std::lround(255.0 * strength)));
    }
  ASSERT_FALSE(extractor.extract(boundaryImage(), {ClassEvidenceForm::kBitmask, bitmask, kClasses}, {}, &edges));
  expectBoundaryEdges(edges, bits, 0.5);
}

TEST(SemanticEdgeExtractor, BadClassInputIsNamed) {
  const cv::Mat gray = boundaryImage();
  const SemanticEdgeExtractor fused(optionsFor(IntakeMode::kFused));
  EdgeSet edges;
  auto reason = [&](const ClassEvidence& classes, const cv::Mat& edge_map = cv::Mat()) {
    return fused.extract(gray, classes, edge_map, &edges).reason;
  };
  const cv::Mat good = regionProbabilities();
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, good, kClasses + 1}), "channel_count_mismatch");
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, good(cv::Rect(0, 0, kWidth / 2, kHeight)), kClasses}), "size_mismatch");
  cv::Mat spoiled = good.clone();
  spoiled.ptr<float>(10)[7] = std::nanf("");
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, spoiled, kClasses}), "invalid_probability");
  spoiled = good.clone();
  spoiled.ptr<float>(50)[100] = -0.2f;
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, spoiled, kClasses}), "invalid_probability");
  const SemanticEdgeExtractor per_class(optionsFor(IntakeMode::kSemanticEdges));
  for (const float bad : {std::nanf(""), -0.2f, 1.5f}) {
    spoiled = good.clone();
    spoiled.ptr<float>(kHeight - 1)[kWidth * kClasses - 1] = bad;  // the last value (tail of the SIMD scan)
    EXPECT_EQ(per_class.extract(gray, {ClassEvidenceForm::kProbabilities, spoiled, kClasses}, {}, &edges).reason,
              "invalid_probability") << bad;
    spoiled = good.clone();
    spoiled.ptr<float>(3)[2 * kClasses + 1] = bad;
    EXPECT_EQ(per_class.extract(gray, {ClassEvidenceForm::kProbabilities, spoiled, kClasses}, {}, &edges).reason,
              "invalid_probability") << bad;
  }
  spoiled = good.clone();
  spoiled.ptr<float>(3)[4] = -0.0f;
  EXPECT_EQ(per_class.extract(gray, {ClassEvidenceForm::kProbabilities, spoiled, kClasses}, {}, &edges).reason, "")
      << "-0 is a valid probability";
  cv::Mat doubles;
  good.convertTo(doubles, CV_64F);
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, doubles, kClasses}), "unsupported_layout");
  EXPECT_EQ(reason({ClassEvidenceForm::kBitmask, cv::Mat(kHeight, kWidth, CV_8UC4), kClasses}), "unsupported_layout");
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, good, kClasses}, cv::Mat(kHeight, kWidth + 1, CV_32F, 0.5)), "size_mismatch");
  EXPECT_TRUE(edges.u.empty()) << "nothing is returned on error";
  EXPECT_EQ(reason({ClassEvidenceForm::kProbabilities, good, kClasses}), "");
}

TEST(SemanticEdgeExtractor, OptionsAreValidated) {
  SemanticEdgeOptions options;
  EXPECT_EQ(options.validate(), "");
  options.class_threshold = 0.0;
  EXPECT_NE(options.validate(), "");
  options = SemanticEdgeOptions();
  options.thinning.threshold = 1.5;
  EXPECT_NE(options.validate(), "");
  IntakeMode mode;
  EXPECT_TRUE(parseIntakeMode("semantic_edges", &mode));
  EXPECT_EQ(mode, IntakeMode::kSemanticEdges);
  EXPECT_FALSE(parseIntakeMode("hed", &mode));
}

}  // namespace
}  // namespace semantic_edge_vo

namespace semantic_edge_vo {
namespace {

TEST(SemanticEdgeExtractor, LeavesItsInputsUntouchedAndRepeats) {
  const cv::Mat gray = boundaryImage(), gray_before = gray.clone();
  cv::Mat edge_map(kHeight, kWidth, CV_32F, cv::Scalar(0));
  edge_map.col(30).setTo(0.9);
  const cv::Mat edge_map_before = edge_map.clone();
  const ClassEvidence classes{ClassEvidenceForm::kProbabilities, regionProbabilities(), kClasses};
  SemanticEdgeOptions options = optionsFor(IntakeMode::kFused);
  options.canny.blur_sigma = 1.0;
  const SemanticEdgeExtractor extractor(options);
  EdgeSet first, second;
  ASSERT_FALSE(extractor.extract(gray, classes, cv::Mat(), &first));
  ASSERT_FALSE(extractor.extract(gray, classes, cv::Mat(), &second));
  EXPECT_EQ(first.u, second.u) << "the same input gives the same edges";
  ASSERT_FALSE(extractor.extract(gray, classes, edge_map, &second));
  EXPECT_EQ(cv::norm(gray, gray_before, cv::NORM_INF), 0.0) << "the image was modified";
  EXPECT_EQ(cv::norm(edge_map, edge_map_before, cv::NORM_INF), 0.0) << "the edge map was modified";
}

}  // namespace
}  // namespace semantic_edge_vo
