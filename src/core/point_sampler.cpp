#include "semantic_edge_vo/point_sampler.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// Gradient magnitude from central differences, gray levels per pixel (DSO's definition).
cv::Mat centralGradientMagnitude(const cv::Mat& gray) {
  cv::Mat gx, gy, magnitude;
  cv::Mat kernel = (cv::Mat_<float>(1, 3) << -0.5f, 0.0f, 0.5f);
  cv::filter2D(gray, gx, CV_32F, kernel);
  cv::filter2D(gray, gy, CV_32F, kernel.t());
  cv::magnitude(gx, gy, magnitude);
  return magnitude;
}

/// Median of a block's gradient magnitudes from a histogram of 1-gray-level bins clamped at 49,
/// as DSO's pixel selector computes its block thresholds (linear time, no sorting).
float blockMedian(const cv::Mat& block) {
  int histogram[50] = {0};
  for (int y = 0; y < block.rows; ++y) {
    const float* row = block.ptr<float>(y);
    for (int x = 0; x < block.cols; ++x) ++histogram[std::min(49, static_cast<int>(row[x]))];
  }
  const int half = static_cast<int>(block.total() / 2);
  int seen = 0;
  for (int bin = 0; bin < 50; ++bin)
    if ((seen += histogram[bin]) > half) return static_cast<float>(bin) + 0.5f;
  return 49.5f;
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
  std::vector<std::uint32_t> chosen(n);
  std::iota(chosen.begin(), chosen.end(), 0u);
  if (n <= wanted) return chosen;

  // A grid with about one cell per wanted point; each edge's rank within its cell (strongest first)
  // decides the round it is taken in, so every region gets its share before any gets a second.
  const int cell = std::max(2, static_cast<int>(std::sqrt(static_cast<double>(width) * height / wanted)));
  const int cols = (width + cell - 1) / cell, rows = (height + cell - 1) / cell;
  std::vector<std::uint32_t> cell_start(static_cast<std::size_t>(cols * rows) + 1, 0u), cell_of(n);
  for (std::size_t i = 0; i < n; ++i) {
    const int cx = std::clamp(static_cast<int>(edges.u[i]) / cell, 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(edges.v[i]) / cell, 0, rows - 1);
    cell_of[i] = static_cast<std::uint32_t>(cy * cols + cx);
    ++cell_start[cell_of[i] + 1];
  }
  for (std::size_t c = 1; c < cell_start.size(); ++c) cell_start[c] += cell_start[c - 1];
  std::vector<std::uint32_t> by_cell(n), fill(cell_start.begin(), cell_start.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i) by_cell[fill[cell_of[i]]++] = i;

  const auto stronger = [&](std::uint32_t a, std::uint32_t b) {
    return edges.strength[a] != edges.strength[b] ? edges.strength[a] > edges.strength[b] : a < b;
  };
  std::vector<std::uint32_t> rank(n);
  for (std::size_t c = 0; c + 1 < cell_start.size(); ++c) {
    const auto first = by_cell.begin() + cell_start[c], last = by_cell.begin() + cell_start[c + 1];
    std::sort(first, last, stronger);
    for (auto it = first; it != last; ++it) rank[*it] = static_cast<std::uint32_t>(it - first);
  }
  // Whole rounds first; the last, partial round takes its strongest edges.
  std::nth_element(chosen.begin(), chosen.begin() + static_cast<std::ptrdiff_t>(wanted), chosen.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return rank[a] != rank[b] ? rank[a] < rank[b] : stronger(a, b); });
  chosen.resize(wanted);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

void PointSampler::sampleSupport(const cv::Mat& gray, const EdgeSetView& edges, int count,
                                 PointSample* sample) const {
  if (count <= 0) return;
  const cv::Mat magnitude = centralGradientMagnitude(gray);

  // Pixels near any edge are the edges' business; supportive pixels stay clear of them.
  cv::Mat near_edge(gray.size(), CV_8U, cv::Scalar(0));
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const int x = static_cast<int>(std::lround(edges.u[i]));
    const int y = static_cast<int>(std::lround(edges.v[i]));
    if (x >= 0 && y >= 0 && x < gray.cols && y < gray.rows) near_edge.at<std::uint8_t>(y, x) = 255;
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
  for (int by = 0; by < block_rows; ++by) {
    for (int bx = 0; bx < block_cols; ++bx) {
      const cv::Rect block_rect = cv::Rect(bx * block, by * block, block, block) & cv::Rect(0, 0, gray.cols, gray.rows);
      const float threshold = blockMedian(magnitude(block_rect)) + static_cast<float>(options_.support_threshold_offset);
      const bool scarce = sampled_edges_in_block[static_cast<std::size_t>(by * block_cols + bx)] == 0;
      for (int sy = block_rect.y; sy < block_rect.br().y; sy += sub) {
        for (int sx = block_rect.x; sx < block_rect.br().x; sx += sub) {
          Candidate best{-1, -1, scarce, 0.0f};
          for (int y = std::max(sy, 2); y < std::min({sy + sub, block_rect.br().y, gray.rows - 2}); ++y) {
            const float* row = magnitude.ptr<float>(y);
            const std::uint8_t* excluded = near_edge.ptr<std::uint8_t>(y);
            for (int x = std::max(sx, 2); x < std::min({sx + sub, block_rect.br().x, gray.cols - 2}); ++x) {
              const float margin = row[x] - threshold;
              if (!excluded[x] && margin > best.margin) best = {x, y, scarce, margin};
            }
          }
          if (best.x >= 0) candidates.push_back(best);
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
