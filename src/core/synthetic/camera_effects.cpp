#include "semantic_edge_vo/synthetic/camera_effects.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/synthetic/noise.h"
#include "semantic_edge_vo/synthetic/random.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {
constexpr std::size_t kTableSize = 1u << 20;  // power of two: indices wrap with a mask
}

std::string CameraEffectsOptions::validate() const {
  std::ostringstream error;
  if (!(exposure_variation >= 0.0 && exposure_variation <= 2.0))
    error << "exposure_variation must be in [0, 2] (got " << exposure_variation << ")";
  else if (!(exposure_period > 0.0)) error << "exposure_period must be > 0 s (got " << exposure_period << ")";
  else if (!(vignetting >= 0.0 && vignetting < 1.0)) error << "vignetting must be in [0, 1) (got " << vignetting << ")";
  else if (!(read_noise >= 0.0 && shot_noise >= 0.0))
    error << "read_noise and shot_noise must be >= 0 (got " << read_noise << ", " << shot_noise << ")";
  return error.str();
}

CameraEffects::CameraEffects(const CameraEffectsOptions& options, int width, int height, std::uint64_t seed)
    : options_(options), seed_(seed), vignette_(height, width, CV_32FC1), normal_(kTableSize) {
  const double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1), r2_max = cx * cx + cy * cy;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      vignette_.at<float>(y, x) =
          static_cast<float>(1.0 - options.vignetting * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2_max);
  Random random(hashCombine(seed, 0x6e6f697365ULL));
  for (float& n : normal_) n = static_cast<float>(random.normal());
}

double CameraEffects::exposureGain(double time) const {
  const auto seed32 = static_cast<std::uint32_t>(seed_);
  const double slow = 2.0 * valueNoise1d(time / options_.exposure_period, seed32 ^ 0xe1u) - 1.0;
  const double fast = 2.0 * valueNoise1d(4.0 * time / options_.exposure_period, seed32 ^ 0xe2u) - 1.0;
  return 255.0 * std::exp(options_.exposure_variation * (slow + 0.4 * fast));
}

void CameraEffects::expose(const cv::Mat& radiance, double time, int frame, cv::Mat* color, cv::Mat* gray) const {
  CV_Assert(radiance.type() == CV_32FC3 && radiance.size() == vignette_.size());
  color->create(radiance.size(), CV_8UC3);
  gray->create(radiance.size(), CV_8UC1);
  const auto gain = static_cast<float>(exposureGain(time));
  const auto read_variance = static_cast<float>(options_.read_noise * options_.read_noise);
  const auto shot = static_cast<float>(options_.shot_noise);
  std::size_t index = static_cast<std::size_t>(hashCombine(seed_, static_cast<std::uint64_t>(frame))) & (kTableSize - 1);
  auto noisy = [&](float level) {
    const float sigma = std::sqrt(read_variance + shot * std::max(level, 0.0f));
    const float value = level + sigma * normal_[index];
    index = (index + 1) & (kTableSize - 1);
    return static_cast<std::uint8_t>(std::clamp(value, 0.0f, 255.0f) + 0.5f);
  };
  for (int y = 0; y < radiance.rows; ++y) {
    const auto* in = radiance.ptr<cv::Vec3f>(y);
    const float* vignette = vignette_.ptr<float>(y);
    auto* out = color->ptr<cv::Vec3b>(y);
    auto* luma = gray->ptr<std::uint8_t>(y);
    for (int x = 0; x < radiance.cols; ++x) {
      const float scale = gain * vignette[x];
      const float b = in[x][0] * scale, g = in[x][1] * scale, r = in[x][2] * scale;
      out[x] = cv::Vec3b(noisy(b), noisy(g), noisy(r));
      luma[x] = noisy(0.114f * b + 0.587f * g + 0.299f * r);
    }
  }
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
