#include "semantic_edge_vo/fields/shared_class_edge_test.h"

#include <algorithm>
#include <cmath>

#include "semantic_edge_vo/common/parallel_slices.h"

namespace semantic_edge_vo {
namespace {

// A query anywhere within a pixel is at most half its diagonal from the pixel's centre.
constexpr float kHalfDiagonal = 0.70711f;

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
  near_layers_.assign(static_cast<std::size_t>(width_) * height_, 0u);
  const float reach = radius_ + kHalfDiagonal, reach2 = reach * reach;
  const int span = static_cast<int>(std::ceil(reach));
  const std::size_t cells = static_cast<std::size_t>(level.grid_cols) * level.grid_rows;
  const int layers = std::min(field.num_layers, 32);
  // Slices of mask rows; each reads the buckets that reach into its rows and writes only its own.
  forEachSlice([&](int slice) {
    const auto [begin, end] = sliceRange(static_cast<std::size_t>(height_), slice);
    const int row_begin = static_cast<int>(begin), row_end = static_cast<int>(end);
    if (row_begin >= row_end) return;
    const int grid_begin = std::max(0, (row_begin - span) / level.cell_size);
    const int grid_end = std::min(level.grid_rows, (row_end + span) / level.cell_size + 1);
    for (int layer = 0; layer < layers; ++layer) {
      const std::uint32_t bit = 1u << layer;
      const std::uint32_t* starts = level.cell_start.data() + static_cast<std::size_t>(layer) * cells;
      for (std::uint32_t e = starts[static_cast<std::size_t>(grid_begin) * level.grid_cols];
           e < starts[static_cast<std::size_t>(grid_end) * level.grid_cols]; ++e) {
        const std::uint32_t s = level.entry_seed[e];
        const float u = level.seed_u[s], v = level.seed_v[s];
        const int cy = roundToPixel(v);
        for (int y = std::max(row_begin, cy - span); y <= std::min(row_end - 1, cy + span); ++y) {
          const float dy2 = (y - v) * (y - v);
          if (dy2 > reach2) continue;  // adding a square cannot bring the sum back under
          // The disc's chord on this row, one pixel wider on each side for rounding; the test below
          // decides, as over the whole square.
          const float half = std::sqrt(reach2 - dy2);
          const int x_begin = std::max(0, static_cast<int>(std::floor(u - half)) - 1);
          const int x_end = std::min(width_ - 1, static_cast<int>(std::ceil(u + half)) + 1);
          std::uint32_t* row = near_layers_.data() + static_cast<std::size_t>(y) * width_;
          for (int x = x_begin; x <= x_end; ++x)
            if ((x - u) * (x - u) + dy2 <= reach2) row[x] |= bit;
        }
      }
    }
  });
}

bool SharedClassEdgeTest::operator()(std::uint32_t class_mask, float x, float y) const {
  const bool semantic = classRestricted();
  const int px = roundToPixel(x), py = roundToPixel(y);
  if (px >= 0 && py >= 0 && px < width_ && py < height_ && field_.num_layers <= 32) {
    const std::uint32_t near = near_layers_[static_cast<std::size_t>(py) * width_ + px];
    if (!(semantic ? near & class_mask : near)) return false;  // no seed of a wanted layer that close
  }
  const FieldLevelView& level = field_.levels[0];
  for (int layer = 0; layer < field_.num_layers; ++layer) {
    const bool wanted = !semantic || ((class_mask >> layer) & 1u);
    if (wanted && level.anyWithin(layer, x, y, radius_)) return true;
  }
  return false;
}

}  // namespace semantic_edge_vo
