#include "semantic_edge_vo/edges/edge_probability_thinning.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace {

/// Bilinear interpolation at (x, y) >= 0 (inside the border, so truncation floors).
float bilinear(const cv::Mat& image, float x, float y) {
  const int x0 = static_cast<int>(x);
  const int y0 = static_cast<int>(y);
  const float ax = x - static_cast<float>(x0);
  const float ay = y - static_cast<float>(y0);
  const float* row0 = image.ptr<float>(y0);
  const float* row1 = image.ptr<float>(y0 + 1);
  return (1 - ay) * ((1 - ax) * row0[x0] + ax * row0[x0 + 1]) + ay * ((1 - ax) * row1[x0] + ax * row1[x0 + 1]);
}

/// Unit eigenvector of the smaller eigenvalue of the symmetric matrix [[a, b], [b, c]], the direction
/// 0.5 * atan2(2b, a - c) + pi/2 (so ny >= 0), in closed form instead of atan2, cos and sin.
void minorEigenvector(float a, float b, float c, float* nx, float* ny) {
  const float d = a - c, r = std::sqrt(d * d + 4.0f * b * b);
  // (b, lambda - a) and (lambda - c, b) are both eigenvectors of lambda = (a + c - r) / 2; the longer
  // one is well conditioned.
  float x = b, y = -0.5f * (d + r);
  if (d < 0.0f) {
    x = 0.5f * (d - r);
    y = b;
  }
  const float norm = std::sqrt(x * x + y * y);
  if (norm == 0.0f) {  // isotropic: any direction does; atan2(0, 0) = 0 gave this one
    *nx = 0.0f;
    *ny = 1.0f;
    return;
  }
  const float scale = (y < 0.0f || (y == 0.0f && x > 0.0f)) ? -1.0f / norm : 1.0f / norm;
  *nx = x * scale;
  *ny = y * scale;
}

}  // namespace

std::string EdgeThinningOptions::validate() const {
  std::ostringstream error;
  if (!(threshold > 0.0 && threshold < 1.0)) error << "edge threshold must be in (0, 1) (got " << threshold << ")";
  else if (!(blur_sigma >= 0.0)) error << "edge blur_sigma must be >= 0 (got " << blur_sigma << ")";
  else if (border < 2) error << "border must be >= 2 pixels (got " << border << ")";
  return error.str();
}

EdgeSet thinEdgeProbability(const cv::Mat& probability, const cv::Mat& gray, const EdgeThinningOptions& options) {
  CV_Assert(probability.type() == CV_32FC1 && gray.type() == CV_8UC1 && probability.size() == gray.size());
  // A new buffer: blurring into a header that shares `probability` would overwrite the caller's image.
  cv::Mat smoothed;
  if (options.blur_sigma > 0.0) cv::GaussianBlur(probability, smoothed, cv::Size(0, 0), options.blur_sigma);
  else smoothed = probability;

  EdgeSet result;
  const auto threshold = static_cast<float>(options.threshold);
  const int b = options.border;
  for (int y = b; y < gray.rows - b; ++y) {
    const float* raw = probability.ptr<float>(y);
    const float* s = smoothed.ptr<float>(y);
    const float* up = smoothed.ptr<float>(y - 1);
    const float* down = smoothed.ptr<float>(y + 1);
    const std::uint8_t* g = gray.ptr<std::uint8_t>(y);
    for (int x = b; x < gray.cols - b; ++x) {
      if (raw[x] < threshold) continue;
      // Hessian of the smoothed map; the ridge normal is the eigenvector of its smaller eigenvalue.
      const float dxx = s[x + 1] - 2.0f * s[x] + s[x - 1];
      const float dyy = down[x] - 2.0f * s[x] + up[x];
      const float dxy = 0.25f * (down[x + 1] - down[x - 1] - up[x + 1] + up[x - 1]);
      float nx, ny;
      minorEigenvector(dxx, dxy, dyy, &nx, &ny);
      const float centre = s[x];
      const float before = bilinear(smoothed, x - nx, y - ny);
      const float after = bilinear(smoothed, x + nx, y + ny);
      // Ties go to one side only, so a plateau two pixels wide yields one edge pixel.
      if (!(centre > before && centre >= after)) continue;
      const float curvature = before - 2.0f * centre + after;
      const float offset = curvature < 0.0f ? std::clamp(0.5f * (before - after) / curvature, -0.5f, 0.5f) : 0.0f;
      const float pu = x + offset * nx, pv = y + offset * ny;
      // Dark to bright in the image; the sign of a ridge alone is arbitrary.
      const float gx = static_cast<float>(g[x + 1]) - static_cast<float>(g[x - 1]);
      const float gy = static_cast<float>(gray.ptr<std::uint8_t>(y + 1)[x]) - static_cast<float>(gray.ptr<std::uint8_t>(y - 1)[x]);
      if (nx * gx + ny * gy < 0.0f) {
        nx = -nx;
        ny = -ny;
      }
      result.push_back(pu, pv, nx, ny, std::min(1.0f, raw[x]), 0u);
    }
  }
  return result;
}

}  // namespace semantic_edge_vo
