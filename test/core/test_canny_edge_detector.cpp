#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/edges/canny_edge_detector.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/support/test_pattern.h"

namespace semantic_edge_vo {
namespace {

/// A vertical step edge between columns, blurred, at a known subpixel column.
cv::Mat stepImage(double edge_column, int width = 80, int height = 60) {
  cv::Mat image(height, width, CV_32F);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      // Area-sampled step: the fraction of pixel [x-0.5, x+0.5] right of the edge.
      const double covered = std::clamp(x + 0.5 - edge_column, 0.0, 1.0);
      image.at<float>(y, x) = static_cast<float>(50.0 + 150.0 * covered);
    }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.2);
  cv::Mat gray;
  image.convertTo(gray, CV_8U);
  return gray;
}

TEST(CannyEdgeDetector, SubpixelPositionAndNormalOfAStepEdge) {
  CannyOptions options;
  options.blur_sigma = 0.0;
  for (double column : {30.0, 30.25, 30.5, 30.75}) {
    const EdgeSet edges = CannyEdgeDetector(options).detect(stepImage(column), 4u);
    ASSERT_GT(edges.size(), 40u) << "column " << column;
    double mean_u = 0.0;
    for (std::size_t i = 0; i < edges.size(); ++i) {
      mean_u += edges.u[i];
      EXPECT_NEAR(edges.normal_x[i], 1.0f, 1e-3f);  // dark to bright: +x
      EXPECT_EQ(edges.class_mask[i], 4u);
      EXPECT_GT(edges.strength[i], 0.0f);
      EXPECT_LE(edges.strength[i], 1.0f);
    }
    mean_u /= static_cast<double>(edges.size());
    // Pixel x covers [x - 0.5, x + 0.5]: the step's half-intensity point, the gradient peak, is at `column`.
    EXPECT_NEAR(mean_u, column, 0.05) << "column " << column;
  }
}

TEST(CannyEdgeDetector, FindsTheEdgePixelsOfOpenCvsCanny) {
  // Our non-maximum suppression and hysteresis replace cv::Canny's (with L2 magnitudes): the same
  // pixels, inside the border, on a scene with all edge directions and noise.
  cv::Mat noise(240, 320, CV_32F), gray;
  cv::randn(noise, 0.0, 25.0);
  cv::Mat pattern;
  renderTestPattern(5, 320, 240).convertTo(pattern, CV_32F);
  cv::Mat(pattern + noise).convertTo(gray, CV_8U);
  const CannyOptions options;
  cv::Mat smoothed, dx, dy, expected;
  cv::GaussianBlur(gray, smoothed, cv::Size(0, 0), options.blur_sigma);
  cv::Sobel(smoothed, dx, CV_16S, 1, 0, 3);
  cv::Sobel(smoothed, dy, CV_16S, 0, 1, 3);
  cv::Canny(dx, dy, expected, options.low_threshold, options.high_threshold, /*L2gradient=*/true);
  const cv::Rect inner(options.border, options.border, gray.cols - 2 * options.border, gray.rows - 2 * options.border);
  const EdgeSet edges = CannyEdgeDetector(options).detect(gray);
  EXPECT_GT(edges.size(), 1000u);
  EXPECT_EQ(edges.size(), static_cast<std::size_t>(cv::countNonZero(expected(inner))));
  for (std::size_t i = 0; i < edges.size(); ++i) {
    // Each edge lies within half a pixel along its normal of a pixel cv::Canny marks.
    const float offset_u = 0.5f * edges.normal_x[i], offset_v = 0.5f * edges.normal_y[i];
    bool marked = false;
    for (const float t : {-1.0f, 0.0f, 1.0f})
      marked = marked || expected.at<std::uint8_t>(static_cast<int>(std::lround(edges.v[i] + t * offset_v)),
                                                  static_cast<int>(std::lround(edges.u[i] + t * offset_u)));
    EXPECT_TRUE(marked) << "edge " << i << " at " << edges.u[i] << ", " << edges.v[i];
  }
}

/// The test pattern's flat shapes plus smooth texture, so that supportive pixels exist off the edges.
cv::Mat texturedPattern() {
  cv::Mat texture(360, 640, CV_32F);
  cv::randn(texture, 0.0, 60.0);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 1.2);
  cv::Mat gray;
  cv::Mat pattern;
  renderTestPattern(3, 640, 360).convertTo(pattern, CV_32F);
  cv::Mat(pattern + texture).convertTo(gray, CV_8U);
  return gray;
}

TEST(PointSampler, SpreadsEdgesAndAddsSupportWhereEdgesAreScarce) {
  const cv::Mat gray = texturedPattern();
  const EdgeSet edges = CannyEdgeDetector(CannyOptions()).detect(gray);
  PointSamplerOptions options;
  options.max_edge_points = 500;
  options.min_support_points = 200;
  const PointSample sample = PointSampler(options).sample(gray, edges.view());
  ASSERT_EQ(sample.edge_indices.size(), 500u);
  EXPECT_GT(sample.support_u.size(), 100u);
  EXPECT_LE(sample.support_u.size(), 200u);
  // Well spread: the sample reaches every quarter of the image.
  int quarters[4] = {0, 0, 0, 0};
  for (std::uint32_t i : sample.edge_indices) ++quarters[(edges.u[i] > 320) + 2 * (edges.v[i] > 180)];
  for (int q : quarters) EXPECT_GT(q, 50);

  options.max_edge_points = static_cast<int>(edges.size()) + 300;  // edges are scarce: 300 short
  const PointSample more = PointSampler(options).sample(gray, edges.view());
  EXPECT_EQ(more.edge_indices.size(), edges.size());
  EXPECT_GT(more.support_u.size(), sample.support_u.size());
}

}  // namespace
}  // namespace semantic_edge_vo
