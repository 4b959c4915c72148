#include <array>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/fields/shared_class_edge_test.h"

namespace semantic_edge_vo {
namespace {

EdgeSet randomEdges(int n, int width, int height, int num_classes, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, width - 1.0f), v(0.0f, height - 1.0f), angle(-3.14159f, 3.14159f);
  std::uniform_int_distribution<std::uint32_t> mask(1u, (1u << num_classes) - 1u);
  EdgeSet edges;
  for (int i = 0; i < n; ++i) {
    const float a = angle(rng);
    edges.push_back(u(rng), v(rng), std::cos(a), std::sin(a), 1.0f, mask(rng));
  }
  return edges;
}

/// The layers an edge seeds, computed independently of the field's code (SNNF: a layer past the
/// `classes` class layers holds every edge).
bool inLayer(const EdgeSet& edges, std::size_t i, FieldKind kind, int layer, int bins, int classes) {
  if (kind == FieldKind::kAnnf) return true;
  if (kind == FieldKind::kSnnf) return layer >= classes || ((edges.class_mask[i] >> layer) & 1u);
  double angle = std::atan2(edges.normal_y[i], edges.normal_x[i]) * 180.0 / M_PI;
  if (angle < 0) angle += 360.0;
  return static_cast<int>(angle / (360.0 / bins)) % bins == layer;
}

/// Random edges of 5 classes on a 320 x 200 image, and their field of the kind under test.
class FieldAgainstBruteForce : public ::testing::TestWithParam<FieldKind> {
 protected:
  static constexpr int width = 320, height = 200, classes = 5;

  FieldOptions kindOptions() const {
    FieldOptions options;
    options.kind = GetParam();
    return options;
  }
  NearestNeighborFieldData build(const EdgeSet& edges, const FieldOptions& options) const {
    return buildNearestNeighborField(edges.view(), width, height, std::vector<std::string>(classes, "c"), options);
  }
};

TEST_P(FieldAgainstBruteForce, NearestAndAnyWithinAreExactAtEveryLevelAndLayer) {
  const EdgeSet edges = randomEdges(600, width, height, classes, 42);
  FieldOptions options = kindOptions();
  options.pyramid_levels = 4;
  options.orientation_bins = 8;
  options.truncation_radius = 25.0f;
  options.cell_size = 6;
  const NearestNeighborFieldData data = build(edges, options);
  const NearestNeighborFieldView field = data.view();
  ASSERT_EQ(field.validate(), "");
  // Coarser levels get smaller buckets (their edges are denser per pixel); the answers stay exact.
  EXPECT_EQ(field.levels[1].cell_size, 6);
  EXPECT_EQ(field.levels[2].cell_size, 3);
  EXPECT_EQ(field.levels[3].cell_size, 2);

  std::mt19937 rng(7);
  int found = 0, checked = 0;
  for (int level = 0; level < options.pyramid_levels; ++level) {
    const float scale = field.levels[static_cast<std::size_t>(level)].scale;
    std::uniform_real_distribution<float> qx(-20.0f, width * scale + 20.0f), qy(-20.0f, height * scale + 20.0f);
    for (int layer = 0; layer < field.num_layers; ++layer) {
      for (int q = 0; q < 300; ++q) {
        const float x = qx(rng), y = qy(rng);
        float best = std::numeric_limits<float>::max();
        for (std::size_t i = 0; i < edges.size(); ++i) {
          if (!inLayer(edges, i, options.kind, layer, options.orientation_bins, classes)) continue;
          best = std::min(best, std::hypot(toLevel(edges.u[i], scale) - x, toLevel(edges.v[i], scale) - y));
        }
        FieldMatch match;
        const bool hit = field.nearest(level, layer, x, y, &match);
        ++checked;
        const float radius = std::array<float, 4>{0.5f, 1.5f, 4.0f, 9.0f}[static_cast<std::size_t>(q % 4)];
        const bool any = field.levels[static_cast<std::size_t>(level)].anyWithin(layer, x, y, radius);
        EXPECT_EQ(any, best <= radius) << "anyWithin " << radius << " at level " << level << " layer " << layer << " query " << x << "," << y;
        EXPECT_EQ(any, field.nearestWithin(level, layer, x, y, radius, &match)) << "anyWithin and nearestWithin disagree";
        if (best <= options.truncation_radius) {
          ASSERT_TRUE(hit) << "level " << level << " layer " << layer << " query " << x << "," << y;
          EXPECT_NEAR(match.distance, best, 1e-4f);
          EXPECT_NEAR(std::hypot(match.u - x, match.v - y), best, 1e-4f);
          EXPECT_TRUE(inLayer(edges, match.edge, options.kind, layer, options.orientation_bins, classes));
          EXPECT_EQ(match.normal_x, edges.normal_x[match.edge]);
          ++found;
        } else {
          EXPECT_FALSE(hit) << "found a seed beyond the truncation radius";
        }
      }
    }
  }
  EXPECT_GT(found, checked / 4) << "the test should mostly exercise hits";
}

TEST_P(FieldAgainstBruteForce, AnyWithinAgreesWithNearestOnTheDiscBorder) {
  // Queries a hair inside and outside the radius around seeds, in every direction, also across
  // bucket borders: where float rounding decides, both lookups must decide alike.
  const EdgeSet edges = randomEdges(300, width, height, classes, 5);
  FieldOptions options = kindOptions();
  options.pyramid_levels = 1;
  options.cell_size = 4;
  const NearestNeighborFieldData data = build(edges, options);
  const NearestNeighborFieldView field = data.view();
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> angle(-3.14159f, 3.14159f);
  int inside = 0, checked = 0;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (const float radius : {1.5f, 3.0f, 4.0f}) {
      for (const float factor : {0.9999999f, 1.0f, 1.0000001f}) {
        const float a = angle(rng);
        const float x = edges.u[i] + radius * factor * std::cos(a), y = edges.v[i] + radius * factor * std::sin(a);
        for (int layer = 0; layer < field.num_layers; ++layer) {
          FieldMatch match;
          const bool expected = field.nearestWithin(0, layer, x, y, radius, &match);
          ASSERT_EQ(field.levels[0].anyWithin(layer, x, y, radius), expected)
              << "seed " << edges.u[i] << "," << edges.v[i] << " query " << x << "," << y << " radius " << radius << " layer " << layer;
          inside += expected;
          ++checked;
        }
      }
    }
  }
  EXPECT_GT(inside, checked / 20) << "the test should exercise both answers";  // ONNF: 8 layers, a seed in one
  EXPECT_LT(inside, checked) << "the test should exercise both answers";
}

TEST_P(FieldAgainstBruteForce, SharedClassEdgeTestAgreesWithBruteForce) {
  const EdgeSet edges = randomEdges(3000, width, height, classes, 11);
  FieldOptions options = kindOptions();
  options.cell_size = 4;
  const NearestNeighborFieldData data = build(edges, options);
  const NearestNeighborFieldView field = data.view();
  const double radius = 1.5;
  const SharedClassEdgeTest test(field, radius);

  std::vector<std::uint32_t> layers_of(edges.size(), 0u);  // each edge's layers, as bits
  for (std::size_t i = 0; i < edges.size(); ++i)
    for (int layer = 0; layer < field.num_layers; ++layer)
      if (inLayer(edges, i, options.kind, layer, options.orientation_bins, classes)) layers_of[i] |= 1u << layer;
  const std::uint32_t all_layers = (1u << field.num_layers) - 1u;

  std::mt19937 rng(3);
  std::uniform_real_distribution<float> qx(-3.0f, width + 3.0f), qy(-3.0f, height + 3.0f);
  std::uniform_int_distribution<std::uint32_t> mask(1u, (1u << classes) - 1u);
  int near = 0;
  for (int q = 0; q < 20000; ++q) {
    const float x = qx(rng), y = qy(rng);
    const std::uint32_t class_mask = mask(rng);
    const std::uint32_t wanted = options.kind == FieldKind::kSnnf ? class_mask : all_layers;
    bool expected = false;
    for (std::size_t i = 0; i < edges.size() && !expected; ++i)
      expected = (layers_of[i] & wanted) && std::hypot(edges.u[i] - x, edges.v[i] - y) <= radius;
    ASSERT_EQ(test(class_mask, x, y), expected) << "query " << x << "," << y << " classes " << class_mask;
    near += expected;
  }
  EXPECT_GT(near, 2000) << "the test should exercise both answers";
  EXPECT_LT(near, 18000) << "the test should exercise both answers";
}

INSTANTIATE_TEST_SUITE_P(AllKinds, FieldAgainstBruteForce,
                         ::testing::Values(FieldKind::kAnnf, FieldKind::kOnnf, FieldKind::kSnnf),
                         [](const auto& info) { return std::string(toString(info.param)); });

TEST(NearestNeighborField, MultiClassPixelSeedsEachOfItsClassLayersAndTheAllEdgesLayer) {
  EdgeSet edges;
  edges.push_back(10.0f, 10.0f, 1.0f, 0.0f, 1.0f, 0b101u);  // classes 0 and 2
  edges.push_back(40.0f, 10.0f, 1.0f, 0.0f, 1.0f, 0b010u);  // class 1
  FieldOptions options;
  options.pyramid_levels = 1;
  const auto data = buildNearestNeighborField(edges.view(), 64, 64, {"a", "b", "c"}, options);
  const auto field = data.view();
  ASSERT_EQ(field.num_layers, 4);
  ASSERT_EQ(field.all_edges_layer, 3);
  EXPECT_EQ(data.layer_names.back(), "all");
  FieldMatch match;
  EXPECT_TRUE(field.nearest(0, 0, 12.0f, 10.0f, &match));
  EXPECT_FALSE(field.nearest(0, 1, 12.0f, 10.0f, &match));  // class 1 is 28 px away, beyond the truncation radius
  EXPECT_TRUE(field.nearest(0, 2, 12.0f, 10.0f, &match));
  EXPECT_FLOAT_EQ(match.distance, 2.0f);
  // The all-edges layer finds the nearest edge of any class.
  EXPECT_TRUE(field.nearest(0, 3, 37.0f, 10.0f, &match));
  EXPECT_EQ(match.edge, 1u);
  EXPECT_TRUE(field.nearest(0, 3, 12.0f, 10.0f, &match));
  EXPECT_EQ(match.edge, 0u);
}

TEST(NearestNeighborField, OneClassIsItsOwnAllEdgesLayer) {
  EdgeSet edges;
  edges.push_back(10.0f, 10.0f, 1.0f, 0.0f, 1.0f, 1u);
  FieldOptions options;
  options.pyramid_levels = 1;
  const auto field = buildNearestNeighborField(edges.view(), 64, 64, {"edge"}, options).view();
  EXPECT_EQ(field.num_layers, 1);
  EXPECT_EQ(field.all_edges_layer, 0);
}

TEST(NearestNeighborField, ValidateCatchesCorruptArrays) {
  EdgeSet edges;
  edges.push_back(3.0f, 4.0f, 0.0f, 1.0f, 1.0f, 1u);
  auto data = buildNearestNeighborField(edges.view(), 32, 32, {"a"}, FieldOptions());
  data.levels[0].entry_seed[0] = 99;
  EXPECT_NE(data.view().validate(), "");
}

TEST(FieldOptions, RejectsNonsense) {
  FieldOptions options;
  EXPECT_EQ(options.validate(), "");
  options.truncation_radius = 0.0f;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
