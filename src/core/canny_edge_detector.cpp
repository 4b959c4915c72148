#include "semantic_edge_vo/canny_edge_detector.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// L2 gradient magnitudes of the three rows around the current one, computed once per row from the
/// 16-bit Sobel derivatives: the subpixel fit reads at most one row above and below an edge pixel,
/// so a rolling window replaces a full-image float map (no large allocation, stays in L1).
class MagnitudeRows {
 public:
  MagnitudeRows(const cv::Mat& dx, const cv::Mat& dy) : dx_(dx), dy_(dy), rows_(3 * static_cast<std::size_t>(dx.cols)) {}

  /// Fills row y (the slot of row y - 3).
  void compute(int y) {
    const std::int16_t* gx = dx_.ptr<std::int16_t>(y);
    const std::int16_t* gy = dy_.ptr<std::int16_t>(y);
    float* out = slot(y);
    int x = 0;
    // Squares and their sum are exact in float (|Sobel 3x3| <= 1020), so this equals the scalar tail.
    for (; x + 8 <= dx_.cols; x += 8) {
      cv::v_int32x4 x_lo, x_hi, y_lo, y_hi;
      cv::v_expand(cv::v_load(gx + x), x_lo, x_hi);
      cv::v_expand(cv::v_load(gy + x), y_lo, y_hi);
      cv::v_store(out + x, magnitude(cv::v_cvt_f32(x_lo), cv::v_cvt_f32(y_lo)));
      cv::v_store(out + x + 4, magnitude(cv::v_cvt_f32(x_hi), cv::v_cvt_f32(y_hi)));
    }
    for (; x < dx_.cols; ++x) out[x] = std::sqrt(static_cast<float>(gx[x] * gx[x] + gy[x] * gy[x]));
  }

  const float* row(int y) const { return rows_.data() + static_cast<std::size_t>(y % 3) * dx_.cols; }

  /// Bilinear interpolation at (x, y) >= 0, within one row of the last computed rows.
  float bilinear(float x, float y) const {
    const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);  // non-negative: truncation floors
    const float ax = x - static_cast<float>(x0), ay = y - static_cast<float>(y0);
    const float* top = row(y0) + x0;
    const float* bottom = row(y0 + 1) + x0;
    return (1 - ay) * ((1 - ax) * top[0] + ax * top[1]) + ay * ((1 - ax) * bottom[0] + ax * bottom[1]);
  }

 private:
  static cv::v_float32x4 magnitude(const cv::v_float32x4& gx, const cv::v_float32x4& gy) {
    return cv::v_sqrt(gx * gx + gy * gy);
  }
  float* slot(int y) { return rows_.data() + static_cast<std::size_t>(y % 3) * dx_.cols; }

  const cv::Mat& dx_;
  const cv::Mat& dy_;
  std::vector<float> rows_;
};

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
  cv::spatialGradient(smoothed, dx, dy, 3);  // both 3x3 Sobel derivatives in one pass
  cv::Canny(dx, dy, edges, options_.low_threshold, options_.high_threshold, /*L2gradient=*/true);

  // Subpixel positions, directions and strengths at edge pixels, from the 16-bit derivatives.
  EdgeSet result;
  result.reserve(static_cast<std::size_t>(cv::countNonZero(edges)));
  const int b = options_.border;
  const float inv_high = static_cast<float>(1.0 / options_.high_threshold);
  MagnitudeRows magnitude(dx, dy);
  magnitude.compute(b - 1);
  magnitude.compute(b);
  for (int y = b; y < gray.rows - b; ++y) {
    magnitude.compute(y + 1);
    const std::uint8_t* edge_row = edges.ptr<std::uint8_t>(y);
    const std::int16_t* gx_row = dx.ptr<std::int16_t>(y);
    const std::int16_t* gy_row = dy.ptr<std::int16_t>(y);
    const float* m_row = magnitude.row(y);
    for (int x = b; x < gray.cols - b; ++x) {
      if (!edge_row[x]) continue;
      const float m0 = m_row[x];
      if (m0 <= 0.0f) continue;
      const float nx = gx_row[x] / m0;
      const float ny = gy_row[x] / m0;
      // Subpixel peak of the gradient magnitude along the gradient: a parabola through three samples.
      const float m_minus = magnitude.bilinear(x - nx, y - ny);
      const float m_plus = magnitude.bilinear(x + nx, y + ny);
      const float curvature = m_minus - 2.0f * m0 + m_plus;
      float offset = 0.0f;
      if (curvature < 0.0f) offset = std::clamp(0.5f * (m_minus - m_plus) / curvature, -0.5f, 0.5f);
      result.push_back(x + offset * nx, y + offset * ny, nx, ny, std::min(1.0f, m0 * inv_high), class_mask);
    }
  }
  return result;
}

}  // namespace semantic_edge_vo
