#pragma once
#include <string>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

struct CannyOptions {
  double blur_sigma = 1.0;       ///< Gaussian pre-smoothing, pixels (0: none)
  double low_threshold = 40.0;   ///< hysteresis low threshold on the Sobel L2 gradient magnitude (3x3 Sobel units)
  double high_threshold = 100.0; ///< hysteresis high threshold, same units
  int border = 2;                ///< pixels at the image border that never hold edges

  std::string validate() const;
};

/// Canny edges (non-maximum suppressed, hysteresis) with subpixel positions along the gradient,
/// unit gradient directions and a strength (magnitude / high threshold, clamped to 1).
/// Every edge gets `class_mask` (the single "edge" class for the non-semantic intake).
class CannyEdgeDetector {
 public:
  explicit CannyEdgeDetector(const CannyOptions& options) : options_(options) {}

  /// @param[in] gray 8-bit single-channel image
  /// @param[in] class_mask mask given to every edge pixel
  EdgeSet detect(const cv::Mat& gray, std::uint32_t class_mask = 1u) const;

 private:
  CannyOptions options_;
};

}  // namespace semantic_edge_vo
