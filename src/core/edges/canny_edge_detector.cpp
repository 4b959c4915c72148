#include "semantic_edge_vo/edges/canny_edge_detector.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// L2 gradient magnitudes of the three rows around the current one from the 16-bit Sobel
/// derivatives, in a rolling window (no full-image map, stays in L1): squared, as integers, for the
/// edge decisions, or as floats for the subpixel fit. cv::Canny's frame: 0 one column left and right
/// of each row and in the rows outside the image. (|Sobel 3x3| <= 1020: squares sum exactly in
/// int32 and float alike.)
template <typename T>
class MagnitudeRows {
 public:
  MagnitudeRows(const cv::Mat& dx, const cv::Mat& dy)
      : dx_(dx), dy_(dy), stride_(static_cast<std::size_t>(dx.cols) + 2), rows_(3 * stride_, T(0)), zero_(stride_, T(0)) {}

  /// Fills row y (the slot of row y - 3).
  void compute(int y) {
    const std::int16_t* gx = dx_.ptr<std::int16_t>(y);
    const std::int16_t* gy = dy_.ptr<std::int16_t>(y);
    T* out = rows_.data() + offset(y);
    int x = 0;
    for (; x + 8 <= dx_.cols; x += 8) {
      cv::v_int16x8 pairs_lo, pairs_hi;  // (gx, gy) interleaved: a dot product per pixel gives gx^2 + gy^2
      cv::v_zip(cv::v_load(gx + x), cv::v_load(gy + x), pairs_lo, pairs_hi);
      store(out + x, cv::v_dotprod(pairs_lo, pairs_lo));
      store(out + x + 4, cv::v_dotprod(pairs_hi, pairs_hi));
    }
    for (; x < dx_.cols; ++x) out[x] = fromSquare(gx[x] * gx[x] + gy[x] * gy[x]);
  }

  /// Row y's values from column -1 to cols.
  const T* row(int y) const {
    return y < 0 || y >= dx_.rows ? zero_.data() + 1 : rows_.data() + offset(y);
  }

 private:
  /// Where row y's column 0 is in its slot.
  std::size_t offset(int y) const { return static_cast<std::size_t>(y % 3) * stride_ + 1; }
  static T fromSquare(int square);
  static void store(T* out, const cv::v_int32x4& squares);

  const cv::Mat& dx_;
  const cv::Mat& dy_;
  std::size_t stride_;
  std::vector<T> rows_, zero_;
};

template <>
int MagnitudeRows<int>::fromSquare(int square) { return square; }
template <>
float MagnitudeRows<float>::fromSquare(int square) { return std::sqrt(static_cast<float>(square)); }
template <>
void MagnitudeRows<int>::store(int* out, const cv::v_int32x4& squares) { cv::v_store(out, squares); }
template <>
void MagnitudeRows<float>::store(float* out, const cv::v_int32x4& squares) {
  cv::v_store(out, cv::v_sqrt(cv::v_cvt_f32(squares)));
}

/// Bilinear interpolation of float magnitudes at (x, y) >= 0, within one row of the window.
float bilinear(const MagnitudeRows<float>& magnitude, float x, float y) {
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);  // non-negative: truncation floors
  const float ax = x - static_cast<float>(x0), ay = y - static_cast<float>(y0);
  const float* top = magnitude.row(y0) + x0;
  const float* bottom = magnitude.row(y0 + 1) + x0;
  return (1 - ay) * ((1 - ax) * top[0] + ax * top[1]) + ay * ((1 - ax) * bottom[0] + ax * bottom[1]);
}

/// cv::Canny's non-maximum test of squared magnitude m at column x: it beats its neighbours across
/// the gradient (gx, gy), whose direction is quantised to 0, 45, 90 or 135 degrees by integer
/// tangents (ties go to one side only).
inline bool localMaximum(int m, int gx, int gy, const int* above, const int* here, const int* below, int x) {
  constexpr int kShift = 15;
  constexpr int kTan22 = 13573;  // tan(22.5 deg) << 15, rounded
  const int ax = std::abs(gx), ay = std::abs(gy) << kShift;
  const int tan22x = ax * kTan22;
  if (ay < tan22x) return m > here[x - 1] && m >= here[x + 1];
  if (ay > tan22x + (ax << (kShift + 1))) return m > above[x] && m >= below[x];  // beyond tan(67.5 deg)
  const int s = (gx ^ gy) < 0 ? -1 : 1;
  return m > above[x - s] && m > below[x + s];
}

/// Canny edges with L2 magnitudes from the 16-bit derivatives: the pixels cv::Canny(dx, dy, ...)
/// marks (local maxima above the low threshold, 8-connected to one above the high threshold),
/// without its per-call thread pool, deque and output pass. Returns a map framed by one pixel on
/// each side, 2 at edge pixels, and their number in `count`.
cv::Mat cannyMap(const cv::Mat& dx, const cv::Mat& dy, double low_threshold, double high_threshold, std::size_t* count) {
  // As cv::Canny: squared magnitudes against the floored squared thresholds.
  const int low = cvFloor(std::pow(std::min(32767.0, low_threshold), 2));
  const int high = cvFloor(std::pow(std::min(32767.0, high_threshold), 2));
  // 0: a local maximum above `low` not (yet) reached from an edge; 1: no edge; 2: edge.
  cv::Mat map(dx.rows + 2, dx.cols + 2, CV_8U, cv::Scalar(1));
  std::vector<std::uint8_t*> stack;
  stack.reserve(dx.total() / 16);  // edges are a few percent of the pixels: usually no regrowth
  MagnitudeRows<int> magnitude(dx, dy);
  magnitude.compute(0);
  const cv::v_int32x4 lows = cv::v_setall_s32(low);
  for (int y = 0; y < dx.rows; ++y) {
    if (y + 1 < dx.rows) magnitude.compute(y + 1);
    const int* above = magnitude.row(y - 1);
    const int* here = magnitude.row(y);
    const int* below = magnitude.row(y + 1);
    const std::int16_t* gx = dx.ptr<std::int16_t>(y);
    const std::int16_t* gy = dy.ptr<std::int16_t>(y);
    std::uint8_t* out = map.ptr<std::uint8_t>(y + 1) + 1;
    for (int x = 0; x < dx.cols; ++x) {
      // Most pixels are below `low`: four at a time.
      if (x % 4 == 0 && x + 4 <= dx.cols && !cv::v_check_any(cv::v_load(here + x) > lows)) {
        x += 3;
        continue;
      }
      const int m = here[x];
      if (m <= low || !localMaximum(m, gx[x], gy[x], above, here, below, x)) continue;
      out[x] = m > high ? 2 : 0;
      if (m > high) stack.push_back(out + x);
    }
  }
  *count = stack.size();
  // Hysteresis: grow the edges through the local maxima above `low` (the frame is 1: it stops there).
  const auto step = static_cast<std::ptrdiff_t>(map.step);
  while (!stack.empty()) {
    std::uint8_t* const pixel = stack.back();
    stack.pop_back();
    for (const std::ptrdiff_t offset : {-step - 1, -step, -step + 1, std::ptrdiff_t{-1}, std::ptrdiff_t{1}, step - 1, step, step + 1}) {
      if (pixel[offset] == 0) {
        pixel[offset] = 2;
        stack.push_back(pixel + offset);
        ++*count;
      }
    }
  }
  return map;
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

  cv::Mat dx, dy;
  cv::spatialGradient(smoothed, dx, dy, 3);  // both 3x3 Sobel derivatives in one pass
  std::size_t count = 0;
  const cv::Mat edges = cannyMap(dx, dy, options_.low_threshold, options_.high_threshold, &count);

  // Subpixel positions, directions and strengths at edge pixels, from the 16-bit derivatives.
  EdgeSet result;
  result.reserve(count);
  const int b = options_.border;
  const float inv_high = static_cast<float>(1.0 / options_.high_threshold);
  MagnitudeRows<float> magnitude(dx, dy);
  magnitude.compute(b - 1);
  magnitude.compute(b);
  for (int y = b; y < gray.rows - b; ++y) {
    magnitude.compute(y + 1);
    const std::uint8_t* edge_row = edges.ptr<std::uint8_t>(y + 1) + 1;
    const std::int16_t* gx_row = dx.ptr<std::int16_t>(y);
    const std::int16_t* gy_row = dy.ptr<std::int16_t>(y);
    const float* m_row = magnitude.row(y);
    for (int x = b; x < gray.cols - b; ++x) {
      if (edge_row[x] != 2) continue;
      const float m0 = m_row[x];
      if (m0 <= 0.0f) continue;
      const float nx = gx_row[x] / m0;
      const float ny = gy_row[x] / m0;
      // Subpixel peak of the gradient magnitude along the gradient: a parabola through three samples.
      const float m_minus = bilinear(magnitude, x - nx, y - ny);
      const float m_plus = bilinear(magnitude, x + nx, y + ny);
      const float curvature = m_minus - 2.0f * m0 + m_plus;
      float offset = 0.0f;
      if (curvature < 0.0f) offset = std::clamp(0.5f * (m_minus - m_plus) / curvature, -0.5f, 0.5f);
      result.push_back(x + offset * nx, y + offset * ny, nx, ny, std::min(1.0f, m0 * inv_high), class_mask);
    }
  }
  return result;
}

}  // namespace semantic_edge_vo
