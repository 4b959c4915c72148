#include <random>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "semantic_edge_vo/edges/class_evidence.h"

namespace semantic_edge_vo {
namespace {

/// The definition classMaskAcross implements: per-class maximum of value / scale over the pixels,
/// the first most probable class plus every class reaching the threshold, 0 without evidence.
template <typename T>
std::uint32_t referenceMask(const cv::Mat& values, const PixelTriple& pixels, float scale, float threshold, float* best) {
  const int classes = values.channels();
  std::uint32_t mask = 0;
  int top_class = -1;
  *best = 0.0f;
  for (int c = 0; c < classes; ++c) {
    float maximum = 0.0f;
    for (const cv::Point& p : pixels) maximum = std::max(maximum, values.ptr<T>(p.y)[p.x * classes + c] * scale);
    if (maximum > *best) {
      *best = maximum;
      top_class = c;
    }
    if (maximum >= threshold) mask |= 1u << c;
  }
  return top_class < 0 ? 0u : mask | 1u << top_class;
}

/// Values on a coarse grid of levels, so that ties and zeros are common.
template <typename T>
cv::Mat coarseValues(int classes, T step, std::mt19937* random) {
  cv::Mat values(6, 7, CV_MAKETYPE(cv::DataType<T>::depth, classes));
  std::uniform_int_distribution<int> level(0, 4);
  for (int y = 0; y < values.rows; ++y)
    for (int i = 0; i < values.cols * classes; ++i) values.ptr<T>(y)[i] = static_cast<T>(step * level(*random));
  values.reshape(1).row(2).setTo(0);  // pixels without any evidence
  return values;
}

template <typename T>
void expectMasksMatchTheDefinition(T step, float scale) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> x(0, 6), y(0, 5);
  // Fewer classes than SIMD lanes, exact multiples and ragged ends (overlapping registers).
  for (const int classes : {1, 3, 4, 5, 8, 15, 16, 17, 19, 24, 31, 32}) {
    const cv::Mat values = coarseValues<T>(classes, step, &random);
    const ClassEvidence evidence{ClassEvidenceForm::kProbabilities, values, classes};
    for (int trial = 0; trial < 200; ++trial) {
      const PixelTriple pixels = {cv::Point(x(random), y(random)), cv::Point(x(random), y(random)),
                                  trial % 10 == 0 ? cv::Point(1, 2) : cv::Point(x(random), y(random))};
      const float threshold = trial % 2 ? 0.5f : 0.3f;
      float best = -1.0f, expected_best = -1.0f;
      const std::uint32_t mask = evidence.classMaskAcross(pixels, threshold, &best);
      EXPECT_EQ(mask, referenceMask<T>(values, pixels, scale, threshold, &expected_best)) << classes << " classes";
      EXPECT_EQ(best, expected_best) << classes << " classes";
    }
  }
}

TEST(ClassEvidence, ClassMaskAcrossFollowsItsDefinitionForAnyClassCount) {
  expectMasksMatchTheDefinition<float>(0.25f, 1.0f);
  expectMasksMatchTheDefinition<std::uint8_t>(60, 1.0f / 255.0f);  // 0.235 and 0.47 straddle the thresholds
}

TEST(ClassEvidence, LabelsPoolEachClassesLargestConfidence) {
  // (class, confidence x 255): class 3 twice, class 7 as confident as class 3's best, one unlabeled.
  const cv::Mat labels = (cv::Mat_<cv::Vec2b>(1, 4) << cv::Vec2b(3, 100), cv::Vec2b(3, 200), cv::Vec2b(7, 200), cv::Vec2b(255, 255));
  const ClassEvidence with_confidence{ClassEvidenceForm::kLabels, labels, 19};
  const auto at = [](int a, int b, int c) { return PixelTriple{cv::Point(a, 0), cv::Point(b, 0), cv::Point(c, 0)}; };
  float best = 0.0f;
  EXPECT_EQ(with_confidence.classMaskAcross(at(0, 1, 2), 0.5f, &best), (1u << 3) | (1u << 7));
  EXPECT_FLOAT_EQ(best, 200 / 255.0f);
  EXPECT_EQ(with_confidence.classMaskAcross(at(2, 1, 3), 0.9f, &best), 1u << 3) << "ties: the lower class";
  EXPECT_EQ(with_confidence.classMaskAcross(at(0, 0, 3), 0.5f, &best), 1u << 3) << "below the threshold: the best only";
  EXPECT_FLOAT_EQ(best, 100 / 255.0f);
  EXPECT_EQ(with_confidence.classMaskAcross(at(3, 3, 3), 0.5f, &best), 0u) << "unlabeled";
  EXPECT_EQ(best, 0.0f);

  cv::Mat indices;
  cv::extractChannel(labels, indices, 0);
  const ClassEvidence index_only{ClassEvidenceForm::kLabels, indices, 19};
  EXPECT_EQ(index_only.classMaskAcross(at(0, 2, 3), 0.5f, &best), (1u << 3) | (1u << 7));
  EXPECT_EQ(best, 1.0f);
}

TEST(ClassEvidence, InvalidValuesAreFoundInEveryRowAndPosition) {
  for (const int classes : {2, 19}) {
    cv::Mat good(5, 9, CV_32FC(classes));
    good.reshape(1).setTo(0.5);
    const ClassEvidence clean{ClassEvidenceForm::kProbabilities, good, classes};
    EXPECT_EQ(clean.invalidValueCount(), 0u);
    for (const int row : {0, 4})
      for (const int index : {0, classes * 9 - 1}) {
        ClassEvidence spoiled{ClassEvidenceForm::kProbabilities, good.clone(), classes};
        spoiled.values.ptr<float>(row)[index] = -1e-20f;
        EXPECT_EQ(spoiled.invalidValueCount(), 1u) << classes << " classes, row " << row << ", value " << index;
        EXPECT_TRUE(spoiled.invalidInRows(row, row + 1));
        EXPECT_FALSE(spoiled.invalidInRows(row == 0 ? 1 : 0, row == 0 ? 5 : 4));
        std::size_t found = 0;
        spoiled.edgeProbability(&found);
        EXPECT_EQ(found, 1u);
      }
  }
}

}  // namespace
}  // namespace semantic_edge_vo
