#include "semantic_edge_vo/frontend/point_sampler.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// Index of a row or column outside [0, n) mirrored into it (OpenCV's default border).
inline int mirrored(int i, int n) {
  if (n == 1) return 0;
  return i < 0 ? -i : i >= n ? 2 * n - 2 - i : i;
}

/// Eight bytes as signed 16-bit lanes (differences of them are exact; unsigned ones would saturate at 0).
inline cv::v_int16x8 widened(const std::uint8_t* bytes) { return cv::v_reinterpret_as_s16(cv::v_load_expand(bytes)); }

/// DSO's gradient magnitude (central differences, gray levels per pixel) of the pixels of `rect`,
/// row-major into `out`; the border mirrors, so the derivative across it is 0. Computed per block
/// where it is used instead of as a full-image float map: no large buffers, eight pixels at a time.
void centralGradientMagnitude(const cv::Mat& gray, const cv::Rect& rect, float* out) {
  const int cols = gray.cols;
  // Eight pixels from x read bytes x - 1 .. x + 8, which must lie inside the row.
  const int vector_begin = std::max(rect.x, 1), vector_end = std::min(rect.br().x, cols - 1);
  for (int y = rect.y; y < rect.br().y; ++y, out += rect.width) {
    const std::uint8_t* row = gray.ptr<std::uint8_t>(y);
    const std::uint8_t* up = gray.ptr<std::uint8_t>(mirrored(y - 1, gray.rows));
    const std::uint8_t* down = gray.ptr<std::uint8_t>(mirrored(y + 1, gray.rows));
    const auto scalar = [&](int x) {
      const int dx = row[mirrored(x + 1, cols)] - row[mirrored(x - 1, cols)], dy = down[x] - up[x];
      out[x - rect.x] = 0.5f * std::sqrt(static_cast<float>(dx * dx + dy * dy));  // = sqrt((dx/2)^2 + (dy/2)^2)
    };
    int x = rect.x;
    for (; x < vector_begin; ++x) scalar(x);
    for (; x + 8 <= vector_end; x += 8) {
      const cv::v_int16x8 dx = widened(row + x + 1) - widened(row + x - 1);
      const cv::v_int16x8 dy = widened(down + x) - widened(up + x);
      cv::v_int16x8 pairs_lo, pairs_hi;  // (dx, dy) interleaved: a dot product per pixel gives dx^2 + dy^2
      cv::v_zip(dx, dy, pairs_lo, pairs_hi);
      const cv::v_float32x4 half = cv::v_setall_f32(0.5f);
      cv::v_store(out + x - rect.x, half * cv::v_sqrt(cv::v_cvt_f32(cv::v_dotprod(pairs_lo, pairs_lo))));
      cv::v_store(out + x - rect.x + 4, half * cv::v_sqrt(cv::v_cvt_f32(cv::v_dotprod(pairs_hi, pairs_hi))));
    }
    for (; x < rect.br().x; ++x) scalar(x);
  }
}

/// Median of gradient magnitudes from a histogram of 1-gray-level bins clamped at 49, as DSO's pixel
/// selector computes its block thresholds (linear time, no sorting). Four histograms filled in turn,
/// so that runs of pixels in the same bin do not wait on each other's increments.
float blockMedian(const float* magnitude, int n) {
  int histogram[4][50] = {};
  for (int i = 0; i < n; ++i) ++histogram[i & 3][std::min(49, static_cast<int>(magnitude[i]))];
  int seen = 0;
  for (int bin = 0; bin < 50; ++bin)
    if ((seen += histogram[0][bin] + histogram[1][bin] + histogram[2][bin] + histogram[3][bin]) > n / 2)
      return static_cast<float>(bin) + 0.5f;
  return 49.5f;
}

/// The largest margin (magnitude - threshold) of n pixels that are not excluded, at least 0; four
/// at a time, without the loop-carried compare-and-select of a scalar arg-max.
float largestMargin(const float* magnitude, const std::uint8_t* excluded, int n, float threshold) {
  const cv::v_float32x4 limit = cv::v_setall_f32(threshold);
  cv::v_float32x4 best = cv::v_setzero_f32();
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const cv::v_float32x4 kept = cv::v_reinterpret_as_f32(cv::v_load_expand_q(excluded + i) == cv::v_setzero_u32());
    best = cv::v_max(best, (cv::v_load(magnitude + i) - limit) & kept);  // excluded: margin 0
  }
  float result = cv::v_reduce_max(best);
  for (; i < n; ++i)
    if (!excluded[i]) result = std::max(result, magnitude[i] - threshold);
  return result;
}

/// Gradient magnitudes of one block (row-major over `rect`) and its adaptive threshold.
struct BlockMagnitude {
  cv::Rect rect;
  const float* values;
  float threshold;

  const float* at(int x, int y) const { return values + (y - rect.y) * rect.width + (x - rect.x); }
};

/// The pixel of `cell` (inside the block) with the largest positive margin above the threshold that
/// is not excluded, the first in row-major order on ties (DSO's pick per sub-cell); false if none.
bool strongestPixel(const BlockMagnitude& block, const cv::Mat& excluded, const cv::Rect& cell, cv::Point* pixel,
                    float* margin) {
  float best = 0.0f;
  for (int y = cell.y; y < cell.br().y; ++y)
    best = std::max(best, largestMargin(block.at(cell.x, y), excluded.ptr<std::uint8_t>(y) + cell.x, cell.width, block.threshold));
  if (!(best > 0.0f)) return false;
  for (int y = cell.y; y < cell.br().y; ++y) {
    const float* row = block.at(cell.x, y);
    const std::uint8_t* out = excluded.ptr<std::uint8_t>(y) + cell.x;
    for (int i = 0; i < cell.width; ++i) {
      if (!out[i] && row[i] - block.threshold == best) {
        *pixel = {cell.x + i, y};
        *margin = best;
        return true;
      }
    }
  }
  return false;  // not reached: `best` came from one of these pixels
}

}  // namespace

std::string PointSamplerOptions::validate() const {
  std::ostringstream error;
  if (max_edge_points < 0 || min_support_points < 0)
    error << "point counts must be >= 0 (max_edge_points = " << max_edge_points
          << ", min_support_points = " << min_support_points << ")";
  else if (support_block_size < 4) error << "support_block_size must be >= 4 pixels (got " << support_block_size << ")";
  else if (support_min_distance < 0) error << "support_min_distance must be >= 0 (got " << support_min_distance << ")";
  return error.str();
}

PointSample PointSampler::sample(const cv::Mat& gray, const EdgeSetView& edges) const {
  PointSample result;
  result.edge_indices = sampleEdges(edges, gray.cols, gray.rows);
  const int shortfall = options_.max_edge_points - static_cast<int>(result.edge_indices.size());
  sampleSupport(gray, edges, options_.min_support_points + std::max(0, shortfall), &result);
  return result;
}

std::vector<std::uint32_t> PointSampler::sampleEdges(const EdgeSetView& edges, int width, int height) const {
  const std::size_t n = edges.size();
  const auto wanted = static_cast<std::size_t>(options_.max_edge_points);
  if (n <= wanted) {
    std::vector<std::uint32_t> all(n);
    std::iota(all.begin(), all.end(), 0u);
    return all;
  }

  // A grid with about one cell per wanted point; each edge's rank within its cell (strongest first)
  // decides the round it is taken in, so every region gets its share before any gets a second.
  const int cell = std::max(2, static_cast<int>(std::sqrt(static_cast<double>(width) * height / wanted)));
  const int cols = (width + cell - 1) / cell, rows = (height + cell - 1) / cell;
  std::vector<std::uint32_t> cell_start(static_cast<std::size_t>(cols * rows) + 1, 0u), cell_of(n);
  for (std::size_t k = 0; k < n; ++k) {
    const int cx = std::clamp(static_cast<int>(edges.u[k]) / cell, 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(edges.v[k]) / cell, 0, rows - 1);
    cell_of[k] = static_cast<std::uint32_t>(cy * cols + cx);
    ++cell_start[cell_of[k] + 1];
  }
  for (std::size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<std::uint32_t> by_cell(n), fill(cell_start.begin(), cell_start.end() - 1);
  for (std::size_t k = 0; k < n; ++k) by_cell[fill[cell_of[k]]++] = static_cast<std::uint32_t>(k);  // edge indices

  const auto stronger = [&](std::uint32_t a, std::uint32_t b) {
    return edges.strength[a] != edges.strength[b] ? edges.strength[a] > edges.strength[b] : a < b;
  };
  // Round r takes the r-th strongest edge of every cell that has one. Whole rounds are counted from
  // the cell sizes alone; then each cell needs only a partition (nth_element) around its edge of the
  // partial round, never a full sort.
  const auto size_of = [&](std::size_t c) { return static_cast<std::size_t>(cell_start[c + 1] - cell_start[c]); };
  std::size_t largest = 0;
  for (std::size_t c = 0; c + 1 < cell_start.size(); ++c) largest = std::max(largest, size_of(c));
  std::vector<std::size_t> cells_larger_than(largest + 1, 0u);  // [r]: cells with more than r edges
  for (std::size_t c = 0; c + 1 < cell_start.size(); ++c)
    if (size_of(c) > 0) ++cells_larger_than[size_of(c) - 1];
  for (std::size_t r = largest; r-- > 0;) cells_larger_than[r] += cells_larger_than[r + 1];
  std::size_t whole = 0, taken = 0;
  while (taken + cells_larger_than[whole] <= wanted) taken += cells_larger_than[whole++];

  std::vector<std::uint32_t> chosen, partial;  // partial: each cell's edge of the partial round
  chosen.reserve(wanted);
  for (std::size_t c = 0; c + 1 < cell_start.size(); ++c) {
    const auto first = by_cell.begin() + cell_start[c], last = by_cell.begin() + cell_start[c + 1];
    if (size_of(c) > whole) {
      std::nth_element(first, first + static_cast<std::ptrdiff_t>(whole), last, stronger);
      partial.push_back(first[static_cast<std::ptrdiff_t>(whole)]);
      chosen.insert(chosen.end(), first, first + static_cast<std::ptrdiff_t>(whole));
    } else {
      chosen.insert(chosen.end(), first, last);
    }
  }
  // The partial round takes its strongest edges.
  const auto rest = static_cast<std::ptrdiff_t>(wanted - taken);
  std::nth_element(partial.begin(), partial.begin() + rest, partial.end(), stronger);
  chosen.insert(chosen.end(), partial.begin(), partial.begin() + rest);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

void PointSampler::sampleSupport(const cv::Mat& gray, const EdgeSetView& edges, int count,
                                 PointSample* sample) const {
  if (count <= 0) return;
  // Pixels near any edge are the edges' business; supportive pixels stay clear of them.
  cv::Mat near_edge(gray.size(), CV_8U, cv::Scalar(0));
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (!(edges.u[i] > -0.5f && edges.v[i] > -0.5f)) continue;
    const int x = nearestPixelIndex(edges.u[i]), y = nearestPixelIndex(edges.v[i]);
    if (x < gray.cols && y < gray.rows) near_edge.at<std::uint8_t>(y, x) = 255;
  }
  if (options_.support_min_distance > 0) {
    const int d = options_.support_min_distance;
    cv::dilate(near_edge, near_edge, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * d + 1, 2 * d + 1)));
  }
  // Where sampled edges already are: supportive pixels elsewhere come first.
  const int block = options_.support_block_size;
  const int block_cols = (gray.cols + block - 1) / block, block_rows = (gray.rows + block - 1) / block;
  std::vector<int> sampled_edges_in_block(static_cast<std::size_t>(block_cols * block_rows), 0);
  for (std::uint32_t i : sample->edge_indices) {
    const int bx = std::clamp(static_cast<int>(edges.u[i]) / block, 0, block_cols - 1);
    const int by = std::clamp(static_cast<int>(edges.v[i]) / block, 0, block_rows - 1);
    ++sampled_edges_in_block[static_cast<std::size_t>(by * block_cols + bx)];
  }

  struct Candidate {
    int x, y;
    bool edges_scarce;
    float margin;  // gradient magnitude above the block's adaptive threshold
  };
  std::vector<Candidate> candidates;
  // Sub-cells with about two candidates per wanted point, one candidate (the strongest pixel above
  // the threshold) per sub-cell, as DSO's pixel selector does.
  const int sub = std::max(2, static_cast<int>(std::sqrt(static_cast<double>(gray.cols) * gray.rows / (2.0 * count))));
  std::vector<float> magnitude(static_cast<std::size_t>(block * block));
  const cv::Rect selectable(2, 2, gray.cols - 4, gray.rows - 4);  // candidates keep 2 px off the border
  for (int by = 0; by < block_rows; ++by) {
    for (int bx = 0; bx < block_cols; ++bx) {
      const cv::Rect block_rect = cv::Rect(bx * block, by * block, block, block) & cv::Rect(0, 0, gray.cols, gray.rows);
      centralGradientMagnitude(gray, block_rect, magnitude.data());
      const float threshold = blockMedian(magnitude.data(), block_rect.area()) +
                              static_cast<float>(options_.support_threshold_offset);
      const BlockMagnitude block_magnitude{block_rect, magnitude.data(), threshold};
      const bool scarce = sampled_edges_in_block[static_cast<std::size_t>(by * block_cols + bx)] == 0;
      for (int sy = block_rect.y; sy < block_rect.br().y; sy += sub) {
        for (int sx = block_rect.x; sx < block_rect.br().x; sx += sub) {
          const cv::Rect cell = cv::Rect(sx, sy, sub, sub) & block_rect & selectable;
          Candidate best{-1, -1, scarce, 0.0f};
          cv::Point pixel;
          if (!cell.empty() && strongestPixel(block_magnitude, near_edge, cell, &pixel, &best.margin)) {
            best.x = pixel.x;
            best.y = pixel.y;
            candidates.push_back(best);
          }
        }
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.edges_scarce != b.edges_scarce ? a.edges_scarce : a.margin > b.margin;
  });
  const std::size_t taken = std::min(candidates.size(), static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < taken; ++i) {
    sample->support_u.push_back(static_cast<float>(candidates[i].x));
    sample->support_v.push_back(static_cast<float>(candidates[i].y));
  }
}

}  // namespace semantic_edge_vo
