#include "semantic_edge_vo/synthetic/noise.h"

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace synthetic {
cv::Mat smoothNoiseField(int width, int height, double scale, std::uint32_t seed) {
  const double step = std::max(1.0, scale / 4.0);
  const int cols = static_cast<int>(std::ceil(width / step)) + 2, rows = static_cast<int>(std::ceil(height / step)) + 2;
  cv::Mat coarse(rows, cols, CV_32FC1);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) coarse.at<float>(r, c) = valueNoise(c * step / scale, r * step / scale, seed);
  cv::Mat field;
  cv::resize(coarse, field, cv::Size(), step, step, cv::INTER_LINEAR);
  return field(cv::Rect(0, 0, width, height)).clone();
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
