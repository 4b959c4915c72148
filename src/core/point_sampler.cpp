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

float median(std::vector<float>* values) {
  auto middle = values->begin() + static_cast<std::ptrdiff_t>(values->size() / 2);
  std::nth_element(values->begin(), middle, values->end());
  return *middle;
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
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  if (n <= wanted) return order;

  // A grid with about one cell per wanted point; each edge's rank within its cell (strongest first)
  // decides the round it is taken in, so every region gets its share before any gets a second.
  const int cell = std::max(2, static_cast<int>(std::sqrt(static_cast<double>(width) * height / wanted)));
  const int cols = (width + cell - 1) / cell;
  auto cellOf = [&](std::uint32_t i) {
    const int cx = std::clamp(static_cast<int>(edges.u[i]) / cell, 0, cols - 1);
    const int cy = std::clamp(static_cast<int>(edges.v[i]) / cell, 0, (height + cell - 1) / cell - 1);
    return cy * cols + cx;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const int ca = cellOf(a), cb = cellOf(b);
    return ca != cb ? ca < cb : edges.strength[a] > edges.strength[b];
  });
  std::vector<std::uint32_t> rank(n);
  for (std::size_t k = 0; k < n; ++k)
    rank[order[k]] = (k > 0 && cellOf(order[k]) == cellOf(order[k - 1])) ? rank[order[k - 1]] + 1 : 0;

  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return rank[a] != rank[b] ? rank[a] < rank[b] : edges.strength[a] > edges.strength[b];
  });
  order.resize(wanted);
  std::sort(order.begin(), order.end());
  return order;
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
  std::vector<float> block_values;
  for (int by = 0; by < block_rows; ++by) {
    for (int bx = 0; bx < block_cols; ++bx) {
      const cv::Rect block_rect = cv::Rect(bx * block, by * block, block, block) & cv::Rect(0, 0, gray.cols, gray.rows);
      const cv::Mat block_magnitude = magnitude(block_rect);
      block_values.assign(block_magnitude.begin<float>(), block_magnitude.end<float>());
      const float threshold = median(&block_values) + static_cast<float>(options_.support_threshold_offset);
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
