#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {
namespace synthetic {

namespace detail {

inline std::uint32_t hash32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline float latticeValue(std::int64_t ix, std::int64_t iy, std::uint32_t seed) {
  const std::uint32_t h = hash32(static_cast<std::uint32_t>(ix) * 0x8da6b343U ^
                                 hash32(static_cast<std::uint32_t>(iy) * 0xd8163841U ^ seed));
  return static_cast<float>(h >> 8) * (1.0f / 16777216.0f);
}

inline float smooth(float t) { return t * t * (3.0f - 2.0f * t); }

/// Integral of a pulse train (pulse width w, period p = 1 / inverse_period) from 0 to x.
inline double pulseIntegral(double x, double period, double inverse_period, double width) {
  const double cycles = std::floor(x * inverse_period);
  return cycles * width + std::min(x - cycles * period, width);
}

}  // namespace detail

/// Smooth value noise in [0, 1] with unit lattice spacing (cubic Hermite interpolation of hashed
/// lattice values). Deterministic for a seed; the building block of the procedural textures.
inline float valueNoise(double x, double y, std::uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const float tx = detail::smooth(static_cast<float>(x - fx)), ty = detail::smooth(static_cast<float>(y - fy));
  const float v00 = detail::latticeValue(ix, iy, seed), v10 = detail::latticeValue(ix + 1, iy, seed);
  const float v01 = detail::latticeValue(ix, iy + 1, seed), v11 = detail::latticeValue(ix + 1, iy + 1, seed);
  const float top = v00 + (v10 - v00) * tx, bottom = v01 + (v11 - v01) * tx;
  return top + (bottom - top) * ty;
}
/// One-dimensional value noise in [0, 1] with unit lattice spacing.
inline float valueNoise1d(double t, std::uint32_t seed) {
  const double ft = std::floor(t);
  const auto it = static_cast<std::int64_t>(ft);
  const float a = detail::latticeValue(it, 0, seed), b = detail::latticeValue(it + 1, 0, seed);
  return a + (b - a) * detail::smooth(static_cast<float>(t - ft));
}

/// Octaves of value noise, in [0, 1]: the coarsest has period `period` (metres), each next one half
/// of it. Octaves with a period below two `footprint`s (metres per pixel) fade out, which keeps
/// distant textures from aliasing.
inline float fractalNoise(double x, double y, double period, int octaves, double footprint, std::uint32_t seed) {
  float sum = 0.0f, weight_sum = 0.0f, amplitude = 1.0f;
  for (int octave = 0; octave < octaves; ++octave, period *= 0.5, amplitude *= 0.5f) {
    // Full weight above 4 footprints per period, none below 2 (the Nyquist limit).
    const float keep = std::clamp(static_cast<float>(period / footprint) * 0.5f - 1.0f, 0.0f, 1.0f);
    weight_sum += amplitude;
    if (keep <= 0.0f) {
      sum += 0.5f * amplitude;  // the mean of the octave
      continue;
    }
    const float n = valueNoise(x / period, y / period, seed + 0x9e37u * static_cast<std::uint32_t>(octave));
    sum += amplitude * (0.5f + keep * (n - 0.5f));
  }
  return sum / weight_sum;
}

/// Fraction of the interval [x - footprint/2, x + footprint/2] covered by a train of pulses of
/// width `width` repeating every `period` (pulses start at 0, period, 2 period, ...): a pattern
/// line box-filtered over a pixel, exact at every distance.
inline float pulseCoverage(double x, double period, double width, double footprint) {
  const double inverse_period = 1.0 / period;
  if (footprint < 1e-6) return x - std::floor(x * inverse_period) * period < width ? 1.0f : 0.0f;
  if (footprint > period) footprint = period;  // wider filters only average to width / period
  const double h = 0.5 * footprint;
  return static_cast<float>((detail::pulseIntegral(x + h, period, inverse_period, width) -
                             detail::pulseIntegral(x - h, period, inverse_period, width)) / footprint);
}

/// Fraction of [x - footprint/2, x + footprint/2] inside the single interval [start, start + width].
inline float intervalCoverage(double x, double start, double width, double footprint) {
  if (footprint < 1e-6) return x >= start && x < start + width ? 1.0f : 0.0f;
  const double h = 0.5 * footprint;
  const double overlap = std::min(x + h, start + width) - std::max(x - h, start);
  return overlap > 0.0 ? static_cast<float>(std::min(overlap, footprint) / footprint) : 0.0f;
}

/// Smooth random field in [0, 1] of width x height (CV_32FC1) with features of about `scale` pixels:
/// value noise evaluated on a coarse grid and upsampled (cheap at full resolution).
cv::Mat smoothNoiseField(int width, int height, double scale, std::uint32_t seed);

}  // namespace synthetic
}  // namespace semantic_edge_vo
