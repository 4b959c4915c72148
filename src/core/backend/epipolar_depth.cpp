#include "semantic_edge_vo/frontend/residual_pattern.h"
#include "semantic_edge_vo/backend/epipolar_depth.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace semantic_edge_vo {
std::string EpipolarSearchOptions::validate() const {
  std::ostringstream error;
  if (!(min_inverse_depth > 0 && max_inverse_depth > min_inverse_depth)) error << "need 0 < min_inverse_depth < max_inverse_depth";
  else if (!(min_epipolar_length > 0 && max_epipolar_length > min_epipolar_length)) error << "need 0 < min_epipolar_length < max_epipolar_length";
  else if (!(max_pattern_error > 0 && min_second_best_ratio >= 1 && edge_radius > 0 && pixel_sigma > 0 && sigma_range > 0))
    error << "pattern error, ratio, edge radius, pixel sigma and sigma range must be positive (ratio >= 1)";
  else if (!(min_gradient_alignment >= 0 && min_gradient_alignment < 1)) error << "min_gradient_alignment must be in [0, 1)";
  return error.str();
}

namespace {

/// The pattern around (u, v), its mean subtracted.
void zeroMeanPattern(const cv::Mat& intensity, float u, float v, float pattern[kPattern]) {
  float mean = 0.0f;
  for (int j = 0; j < kPattern; ++j) {
    pattern[j] = sampleBilinear(intensity, u + kPatternOffsets[j][0], v + kPatternOffsets[j][1]);
    mean += pattern[j] / kPattern;
  }
  for (int j = 0; j < kPattern; ++j) pattern[j] -= mean;
}

/// The depth measured at the best of the line's positions (half-pixel steps from rho_min to rho_max,
/// `line_pixels` long) when its pattern error is small and unique, refined between the steps.
bool measureAtBest(const std::vector<double>& errors, int best, double rho_min, double rho_max, double line_pixels, double alignment,
                   const EpipolarSearchOptions& options, DepthMeasurement* measurement) {
  const int steps = static_cast<int>(errors.size()) - 1;
  const double best_error = errors[static_cast<std::size_t>(best)];
  if (std::sqrt(best_error / kPattern) > options.max_pattern_error) return false;
  // Unique: nothing nearly as good farther than two pixels (four half-pixel steps) away.
  double second = std::numeric_limits<double>::max();
  for (int s = 0; s <= steps; ++s)
    if (std::abs(s - best) > 4) second = std::min(second, errors[static_cast<std::size_t>(s)]);
  if (second < options.min_second_best_ratio * best_error + 1e-9) return false;

  // Sub-step refinement: a parabola through the best error and its neighbours.
  double offset = 0.0;
  if (best > 0 && best < steps) {
    const double e0 = errors[static_cast<std::size_t>(best - 1)], e2 = errors[static_cast<std::size_t>(best + 1)];
    const double curvature = e0 - 2.0 * best_error + e2;
    if (e0 < std::numeric_limits<double>::max() && e2 < std::numeric_limits<double>::max() && curvature > 0)
      offset = std::clamp(0.5 * (e0 - e2) / curvature, -0.5, 0.5);
  }
  const double step_rho = (rho_max - rho_min) / steps;
  measurement->inverse_depth = rho_min + (best + offset) * step_rho;
  const double pixels_per_step = line_pixels / steps;
  const double rho_per_pixel = step_rho / pixels_per_step;
  const double pixel_sigma = options.pixel_sigma / alignment;
  measurement->variance = rho_per_pixel * rho_per_pixel * pixel_sigma * pixel_sigma;
  return measurement->inverse_depth > 0.0;
}

}  // namespace

bool searchEpipolar(const MapPoint& point, const PyramidLevel& host, const PyramidLevel& target,
                    const SharedClassEdgeTest* target_edges, const Eigen::Isometry3d& T_target_host,
                    const EpipolarSearchOptions& options, DepthMeasurement* measurement) {
  if (!host.camera.contains(point.u, point.v, 3.0)) return false;
  // Zero-mean intensity patterns: more distinctive along the line than gradient magnitude (an edge
  // looks alike on both of its sides there), and insensitive to exposure offsets.
  float reference[kPattern];
  zeroMeanPattern(host.intensity, point.u, point.v, reference);

  // The point at inverse depth rho is R * ray + rho * t (up to scale): its pixel moves along the line.
  // Each pattern pixel has its own ray, so the pattern is warped as the depth would warp it (forward
  // motion scales near points a lot between keyframes).
  Eigen::Vector3d rays[kPattern];
  for (int j = 0; j < kPattern; ++j)
    rays[j] = T_target_host.linear() * host.camera.backProject(point.u + kPatternOffsets[j][0], point.v + kPatternOffsets[j][1], 1.0);
  const Eigen::Vector3d& ray = rays[4];  // offset (0, 0)
  const Eigen::Vector3d& t = T_target_host.translation();
  // A prior (measured, or propagated from the map) bounds the search; without one the line is too
  // long and too ambiguous to search.
  if (!(point.inverse_depth > 0.0)) return false;
  const double sigma = std::sqrt(point.inverse_depth_variance);
  double rho_min = std::max(point.inverse_depth - options.sigma_range * sigma, options.min_inverse_depth);
  double rho_max = std::min(point.inverse_depth + options.sigma_range * sigma, options.max_inverse_depth);
  if (rho_max <= rho_min) return false;
  const auto pixelAt = [&](double rho, Eigen::Vector2d* pixel) {
    const Eigen::Vector3d p = ray + rho * t;
    if (p.z() <= 1e-6) return false;
    *pixel = target.camera.project(p);
    return true;
  };
  Eigen::Vector2d a, b;
  if (!pixelAt(rho_min, &a) || !pixelAt(rho_max, &b)) return false;
  const double length = (b - a).norm();
  if (length < options.min_epipolar_length) return false;  // no parallax: nothing to learn
  // Aperture: along a line parallel to the image structure every position matches (paper III-C:
  // edge depths are unobservable where the epipolar line follows the edge). Measure only where the
  // gradient has a component along the line; the weaker it is, the less the match is worth.
  const Eigen::Vector2d gradient(
      sampleBilinear(host.intensity, point.u + 1.0f, point.v) - sampleBilinear(host.intensity, point.u - 1.0f, point.v),
      sampleBilinear(host.intensity, point.u, point.v + 1.0f) - sampleBilinear(host.intensity, point.u, point.v - 1.0f));
  if (gradient.norm() < 1e-3) return false;
  const double alignment = std::abs(gradient.normalized().dot((b - a) / length));
  if (alignment < options.min_gradient_alignment) return false;
  if (length > options.max_epipolar_length) {
    // Too uncertain to search all of it: centre the window on the prior (or the middle).
    const double centre = point.inverse_depth;
    const double half = 0.5 * (rho_max - rho_min) * options.max_epipolar_length / length;
    rho_min = std::max(rho_min, centre - half);
    rho_max = std::min(rho_max, centre + half);
    if (!pixelAt(rho_min, &a) || !pixelAt(rho_max, &b)) return false;
  }
  const int steps = std::max(2, static_cast<int>(std::ceil(2.0 * (b - a).norm())));  // half-pixel steps
  std::vector<double> errors(static_cast<std::size_t>(steps + 1), std::numeric_limits<double>::max());
  int best = -1;
  const bool edge_gated = point.isEdge() && target_edges;
  // Scores the positions on the line (edge points: those with an edge of one of `classes` near);
  // returns how many passed that edge test.
  const auto scanLine = [&](std::uint32_t classes) {
    int edge_positions = 0;
    for (int s = 0; s <= steps; ++s) {
      const double rho = rho_min + (rho_max - rho_min) * s / steps;
      Eigen::Vector2d pixel;
      if (!pixelAt(rho, &pixel) || !target.camera.contains(pixel.x(), pixel.y(), 4.0)) continue;
      const float x = static_cast<float>(pixel.x()), y = static_cast<float>(pixel.y());
      if (edge_gated && !(*target_edges)(classes, x, y)) continue;
      ++edge_positions;
      float values[kPattern];
      float mean = 0.0f;
      bool inside = true;
      for (int j = 0; j < kPattern && inside; ++j) {
        const Eigen::Vector3d q = rays[j] + rho * t;
        const Eigen::Vector2d warped = target.camera.project(q);
        inside = q.z() > 1e-6 && target.camera.contains(warped.x(), warped.y(), 1.0);
        if (inside) values[j] = sampleBilinear(target.intensity, static_cast<float>(warped.x()), static_cast<float>(warped.y()));
        mean += values[j] / kPattern;
      }
      if (!inside) continue;
      double error = 0.0;
      for (int j = 0; j < kPattern; ++j) error += std::pow(values[j] - mean - reference[j], 2);
      errors[static_cast<std::size_t>(s)] = error;
      if (best < 0 || error < errors[static_cast<std::size_t>(best)]) best = s;
    }
    return edge_positions;
  };
  // Edge points match only where the target has an edge of a class they have. Where the whole line
  // has none, the point's classes are missing there (a label that flickered between the frames):
  // any edge will do then, rather than no measurement (the paper's soft association, Sec. III-B).
  if (scanLine(point.field_layers) == 0 && edge_gated && target_edges->classRestricted()) scanLine(kAllClasses);
  if (best < 0) return false;
  return measureAtBest(errors, best, rho_min, rho_max, (b - a).norm(), alignment, options, measurement);
}

bool fuseDepth(const DepthMeasurement& measurement, MapPoint* point) {
  if (point->observations == 0) {
    point->inverse_depth = measurement.inverse_depth;
    point->inverse_depth_variance = measurement.variance;
    point->observations = 1;
    return true;
  }
  const double innovation = measurement.inverse_depth - point->inverse_depth;
  const double total = point->inverse_depth_variance + measurement.variance;
  if (innovation * innovation > 9.0 * total) {
    // Two measurements that disagree: either may be the outlier. Keep the newer one and start over;
    // with two or more agreeing measurements behind it, the estimate stands and this one is refused.
    if (point->observations > 1) return false;
    point->inverse_depth = measurement.inverse_depth;
    point->inverse_depth_variance = measurement.variance;
    return true;
  }
  const double gain = point->inverse_depth_variance / total;
  point->inverse_depth += gain * innovation;
  point->inverse_depth_variance *= 1.0 - gain;
  ++point->observations;
  return true;
}

}  // namespace semantic_edge_vo
