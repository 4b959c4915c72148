#include "semantic_edge_vo/canny_edge_detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// L2 gradient magnitude at an integer pixel, from the 16-bit Sobel derivatives.
inline float magnitudeAt(const cv::Mat& dx, const cv::Mat& dy, int x, int y) {
  const float gx = dx.ptr<std::int16_t>(y)[x], gy = dy.ptr<std::int16_t>(y)[x];
  return std::sqrt(gx * gx + gy * gy);
}

/// Bilinear interpolation of the gradient magnitude (only the four pixels it needs are computed).
float bilinearMagnitude(const cv::Mat& dx, const cv::Mat& dy, float x, float y) {
  const int x0 = static_cast<int>(std::floor(x));
  const int y0 = static_cast<int>(std::floor(y));
  const float ax = x - static_cast<float>(x0);
  const float ay = y - static_cast<float>(y0);
  return (1 - ay) * ((1 - ax) * magnitudeAt(dx, dy, x0, y0) + ax * magnitudeAt(dx, dy, x0 + 1, y0)) +
         ay * ((1 - ax) * magnitudeAt(dx, dy, x0, y0 + 1) + ax * magnitudeAt(dx, dy, x0 + 1, y0 + 1));
}

}  // namespace

std::string CannyOptions::validate() const {
  std::ostringstream error;
  if (!(blur_sigma >= 0.0)) error << "blur_sigma must be >= 0 (got " << blur_sigma << ")";
  else if (!(low_threshold > 0.0 && high_threshold >= low_threshold))
    error << "need 0 < low_threshold <= high_threshold (got " << low_threshold << ", " << high_threshold << ")";
  else if (border < 2) error << "border must be >= 2 pixels (got " << border << ")";
  return error.str();
}

EdgeSet CannyEdgeDetector::detect(const cv::Mat& gray, std::uint32_t class_mask) const {
  CV_Assert(gray.type() == CV_8UC1);
  // A new buffer: blurring into a header that shares `gray` would overwrite the caller's image.
  cv::Mat smoothed;
  if (options_.blur_sigma > 0.0) cv::GaussianBlur(gray, smoothed, cv::Size(0, 0), options_.blur_sigma);
  else smoothed = gray;

  cv::Mat dx, dy, edges;
  cv::Sobel(smoothed, dx, CV_16S, 1, 0, 3);
  cv::Sobel(smoothed, dy, CV_16S, 0, 1, 3);
  cv::Canny(dx, dy, edges, options_.low_threshold, options_.high_threshold, /*L2gradient=*/true);

  // Magnitudes and directions straight from the 16-bit derivatives, at edge pixels and their
  // subpixel neighbours only.
  EdgeSet result;
  result.reserve(static_cast<std::size_t>(cv::countNonZero(edges)));
  const int b = options_.border;
  const float inv_high = static_cast<float>(1.0 / options_.high_threshold);
  for (int y = b; y < gray.rows - b; ++y) {
    const std::uint8_t* edge_row = edges.ptr<std::uint8_t>(y);
    const std::int16_t* gx_row = dx.ptr<std::int16_t>(y);
    const std::int16_t* gy_row = dy.ptr<std::int16_t>(y);
    for (int x = b; x < gray.cols - b; ++x) {
      if (!edge_row[x]) continue;
      const float m0 = magnitudeAt(dx, dy, x, y);
      if (m0 <= 0.0f) continue;
      const float nx = gx_row[x] / m0;
      const float ny = gy_row[x] / m0;
      // Subpixel peak of the gradient magnitude along the gradient: a parabola through three samples.
      const float m_minus = bilinearMagnitude(dx, dy, x - nx, y - ny);
      const float m_plus = bilinearMagnitude(dx, dy, x + nx, y + ny);
      const float curvature = m_minus - 2.0f * m0 + m_plus;
      float offset = 0.0f;
      if (curvature < 0.0f) offset = std::clamp(0.5f * (m_minus - m_plus) / curvature, -0.5f, 0.5f);
      result.push_back(x + offset * nx, y + offset * ny, nx, ny, std::min(1.0f, m0 * inv_high), class_mask);
    }
  }
  return result;
}

}  // namespace semantic_edge_vo
