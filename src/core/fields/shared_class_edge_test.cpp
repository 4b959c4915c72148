#include "semantic_edge_vo/fields/shared_class_edge_test.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/parallel_slices.h"

namespace semantic_edge_vo {
namespace {

/// std::lround of a pixel coordinate (half away from zero), inline: libm's lroundf cost 1 % of a run.
int roundToPixel(float x) {
  const int whole = static_cast<int>(x);                  // toward zero
  const float fraction = x - static_cast<float>(whole);  // exact
  return whole + (fraction >= 0.5f) - (fraction <= -0.5f);
}

}  // namespace

SharedClassEdgeTest::SharedClassEdgeTest(const NearestNeighborFieldView& field, double radius)
    : field_(field), radius_(std::min(static_cast<float>(radius), field.truncation_radius)) {
  if (field.levels.empty()) return;
  const FieldLevelView& level = field.levels[0];
  width_ = level.width;
  height_ = level.height;
  if (width_ <= 0 || height_ <= 0) return;
  // Each layer's seeds as bits on their nearest pixels, then dilated by a square. A query within
  // `radius_` of a seed lies in a pixel at most radius_ + 1 from the seed's pixel along each axis
  // (half a pixel of rounding at either end), so the square keeps every "maybe": a superset of the
  // discs, built in two separable passes instead of one disc per seed.
  const int reach = static_cast<int>(std::floor(radius_ + 1.0f));
  std::vector<std::uint32_t> seeds(static_cast<std::size_t>(width_) * height_, 0u);
  const std::size_t cells = static_cast<std::size_t>(level.grid_cols) * level.grid_rows;
  const int layers = std::min(field.num_layers, 32);
  for (int layer = 0; layer < layers; ++layer) {
    const std::uint32_t bit = 1u << layer;
    const std::uint32_t* starts = level.cell_start.data() + static_cast<std::size_t>(layer) * cells;
    for (std::uint32_t e = starts[0]; e < starts[cells]; ++e) {
      const std::uint32_t s = level.entry_seed[e];
      const int x = std::clamp(roundToPixel(level.seed_u[s]), 0, width_ - 1);
      const int y = std::clamp(roundToPixel(level.seed_v[s]), 0, height_ - 1);
      seeds[static_cast<std::size_t>(y) * width_ + x] |= bit;
    }
  }
  std::vector<std::uint32_t> rows(seeds.size());
  forEachSlice([&](int slice) {  // along each row
    const auto [begin, end] = sliceRange(static_cast<std::size_t>(height_), slice);
    for (std::size_t y = begin; y < end; ++y) {
      const std::uint32_t* in = seeds.data() + y * width_;
      std::uint32_t* out = rows.data() + y * width_;
      std::copy(in, in + width_, out);
      for (int d = 1; d <= reach && d < width_; ++d) {  // shifted whole rows: loops the compiler vectorises
        for (int x = d; x < width_; ++x) out[x] |= in[x - d];
        for (int x = 0; x + d < width_; ++x) out[x] |= in[x + d];
      }
    }
  });
  near_layers_.assign(seeds.size(), 0u);
  forEachSlice([&](int slice) {  // then down each column
    const auto [begin, end] = sliceRange(static_cast<std::size_t>(height_), slice);
    for (int y = static_cast<int>(begin); y < static_cast<int>(end); ++y) {
      std::uint32_t* out = near_layers_.data() + static_cast<std::size_t>(y) * width_;
      for (int dy = std::max(0, y - reach); dy <= std::min(height_ - 1, y + reach); ++dy) {
        const std::uint32_t* in = rows.data() + static_cast<std::size_t>(dy) * width_;
        for (int x = 0; x < width_; ++x) out[x] |= in[x];
      }
    }
  });
}

bool SharedClassEdgeTest::operator()(std::uint32_t class_mask, float x, float y) const {
  const bool semantic = classRestricted();
  const int px = roundToPixel(x), py = roundToPixel(y);
  const FieldLevelView& level = field_.levels[0];
  if (px >= 0 && py >= 0 && px < width_ && py < height_ && field_.num_layers <= 32) {
    // Only the wanted layers with a seed that close can answer, in the order of the loop below.
    std::uint32_t maybe = near_layers_[static_cast<std::size_t>(py) * width_ + px];
    if (semantic) maybe &= class_mask;
    for (; maybe; maybe &= maybe - 1)
      if (level.anyWithin(__builtin_ctz(maybe), x, y, radius_)) return true;
    return false;
  }
  for (int layer = 0; layer < field_.num_layers; ++layer) {
    const bool wanted = !semantic || ((class_mask >> layer) & 1u);
    if (wanted && level.anyWithin(layer, x, y, radius_)) return true;
  }
  return false;
}

}  // namespace semantic_edge_vo
