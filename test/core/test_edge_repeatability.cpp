#include <gtest/gtest.h>

#include "semantic_edge_vo/experiments/edge_repeatability.h"

namespace semantic_edge_vo {
namespace {

constexpr float kPlaneDepth = 10.0f;  // m, fronto-parallel plane
constexpr int kSpacing = 20;          // px between edge pixels: far more than the 1.5 px radius

/// Edge pixels on a 20 px grid, shifted by (du, dv), class bit (column index mod 3) shifted left by `class_shift`.
EdgeSet gridEdges(float du, float dv, int class_shift = 0) {
  EdgeSet edges;
  for (int v = 10; v < 376; v += kSpacing)
    for (int u = 10; u < 1241; u += kSpacing)
      edges.push_back(u + du, v + dv, 1.0f, 0.0f, 1.0f, 1u << ((u / kSpacing) % 3 + class_shift));
  return edges;
}

RepeatabilityFrame planeFrame(const EdgeSet& edges, double camera_x) {
  RepeatabilityFrame frame;
  frame.edges = edges.view();
  frame.depth = cv::Mat(376, 1241, CV_32FC1, cv::Scalar(kPlaneDepth));
  frame.T_world_cam.translation() = Eigen::Vector3d(camera_x, 0.0, 0.0);
  return frame;
}

/// Image shift of the plane when the camera moves `dx` metres to the right.
float shiftOf(double dx) { return static_cast<float>(-kittiCamera().fx * dx / kPlaneDepth); }

TEST(EdgeRepeatability, IdenticalFramesRepeatFully) {
  const EdgeSet edges = gridEdges(0.3f, -0.2f);
  const RepeatabilityFrame frame = planeFrame(edges, 0.0);
  const RepeatabilityCount count = measureRepeatability(kittiCamera(), frame, frame, RepeatabilityOptions());
  EXPECT_EQ(count.edges, edges.size());
  EXPECT_EQ(count.eligible, edges.size()) << "every grid pixel is 10 px from the border";
  EXPECT_EQ(count.sampled, count.eligible) << "fewer than 9000";
  EXPECT_DOUBLE_EQ(count.rate(), 1.0);
  EXPECT_DOUBLE_EQ(count.classRate(), 1.0);
}

TEST(EdgeRepeatability, TranslationOfAPlane) {
  const double dx = 0.12;  // 8.63 px to the left
  const EdgeSet first_edges = gridEdges(0.0f, 0.0f);
  const RepeatabilityFrame first = planeFrame(first_edges, 0.0);
  const RepeatabilityOptions options;

  const EdgeSet moved = gridEdges(shiftOf(dx), 0.0f);
  const RepeatabilityCount exact = measureRepeatability(kittiCamera(), first, planeFrame(moved, dx), options);
  // The first column leaves the image (u = 10 - 8.63 < border).
  EXPECT_EQ(exact.eligible, first_edges.size() - 19);
  EXPECT_DOUBLE_EQ(exact.rate(), 1.0);

  const EdgeSet off_by_one = gridEdges(shiftOf(dx) + 1.0f, 0.8f);  // 1.28 px from the projections
  EXPECT_DOUBLE_EQ(measureRepeatability(kittiCamera(), first, planeFrame(off_by_one, dx), options).rate(), 1.0);
  const EdgeSet off_by_two = gridEdges(shiftOf(dx) + 1.6f, 0.0f);
  EXPECT_DOUBLE_EQ(measureRepeatability(kittiCamera(), first, planeFrame(off_by_two, dx), options).rate(), 0.0);
  EXPECT_DOUBLE_EQ(measureRepeatability(kittiCamera(), first, planeFrame(first_edges, dx), options).rate(), 0.0)
      << "edges that did not move with the camera are 8.6 px off";
}

TEST(EdgeRepeatability, HalfTheEdgesReappear) {
  const double dx = 0.07;
  const EdgeSet first_edges = gridEdges(0.0f, 0.0f);  // outlives the frame's view
  const RepeatabilityFrame first = planeFrame(first_edges, 0.0);
  const EdgeSet all = gridEdges(shiftOf(dx), 0.0f);
  EdgeSet half;
  for (std::size_t i = 0; i < all.size(); i += 2)
    half.push_back(all.u[i], all.v[i], all.normal_x[i], all.normal_y[i], all.strength[i], all.class_mask[i]);
  const RepeatabilityCount count = measureRepeatability(kittiCamera(), first, planeFrame(half, dx), RepeatabilityOptions());
  EXPECT_NEAR(count.rate(), 0.5, 0.02);
}

TEST(EdgeRepeatability, SameClassNeedsASharedClassBit) {
  const EdgeSet edges = gridEdges(0.0f, 0.0f);
  const EdgeSet other_class = gridEdges(0.0f, 0.0f, 1);
  const RepeatabilityFrame frame = planeFrame(edges, 0.0);
  const RepeatabilityCount count = measureRepeatability(kittiCamera(), frame, planeFrame(other_class, 0.0), RepeatabilityOptions());
  EXPECT_DOUBLE_EQ(count.rate(), 1.0);
  EXPECT_DOUBLE_EQ(count.classRate(), 0.0);

  EdgeSet two_classes = edges;
  for (auto& mask : two_classes.class_mask) mask |= mask << 1;
  const RepeatabilityCount soft = measureRepeatability(kittiCamera(), planeFrame(two_classes, 0.0), planeFrame(other_class, 0.0),
                                                       RepeatabilityOptions());
  EXPECT_DOUBLE_EQ(soft.classRate(), 1.0) << "an edge in two classes matches either";
}

TEST(EdgeRepeatability, SkyDynamicAndOccludedPixelsAreLeftOut) {
  const EdgeSet edges = gridEdges(0.0f, 0.0f);
  RepeatabilityFrame first = planeFrame(edges, 0.0), second = planeFrame(edges, 0.0);
  first.depth.rowRange(0, 100).setTo(0.0f);                         // sky: rows 10..90 of the grid (5 rows)
  first.dynamic = cv::Mat(376, 1241, CV_8UC1, cv::Scalar(0));
  first.dynamic.colRange(0, 200).setTo(255);                         // moving: columns 10..190 (10 columns)
  second.depth.colRange(1000, 1241).setTo(2.0f);                     // occluder in front: columns 1010..1230 (12 columns)
  const RepeatabilityCount count = measureRepeatability(kittiCamera(), first, second, RepeatabilityOptions());
  EXPECT_EQ(count.eligible, static_cast<std::size_t>((19 - 5) * (62 - 10 - 12)));
  EXPECT_DOUBLE_EQ(count.rate(), 1.0);
}

TEST(EdgeRepeatability, SamplesAFixedNumberDeterministically) {
  const EdgeSet edges = gridEdges(0.0f, 0.0f);
  EdgeSet half;
  for (std::size_t i = 0; i < edges.size(); i += 2)
    half.push_back(edges.u[i], edges.v[i], edges.normal_x[i], edges.normal_y[i], edges.strength[i], edges.class_mask[i]);
  RepeatabilityOptions options;
  options.sample_size = 300;
  const RepeatabilityFrame first = planeFrame(edges, 0.0), second = planeFrame(half, 0.0);
  const RepeatabilityCount a = measureRepeatability(kittiCamera(), first, second, options);
  const RepeatabilityCount b = measureRepeatability(kittiCamera(), first, second, options);
  EXPECT_EQ(a.sampled, 300u);
  EXPECT_EQ(a.repeated, b.repeated);
  EXPECT_NEAR(a.rate(), 0.5, 0.1) << "a random sample, not the first 300 pixels";
}

TEST(EdgeRepeatability, OptionsAreValidated) {
  EXPECT_EQ(RepeatabilityOptions().validate(), "");
  RepeatabilityOptions options;
  options.radius = 0.0;
  EXPECT_NE(options.validate(), "");
  options = RepeatabilityOptions();
  options.sample_size = 0;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
