#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/frontend/residual_pattern.h"
#include "semantic_edge_vo/frontend/tracker.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/common/parallel_slices.h"
#include "semantic_edge_vo/common/pose_uncertainty.h"
#include "semantic_edge_vo/frontend/point_sampler.h"

namespace semantic_edge_vo {
namespace {

// The published covariance, calibrated against ground truth (evaluate_trajectory --tracked-motions:
// KITTI 03 frames 0-499 and a synthetic city drive, in metres; docs/evaluation.md). A point's
// pattern pixels share its depth and overlap in the image, and the depth's own error moves them all:
// the Gauss-Newton covariance times 80 gives the rotation's chi-square median NEES. The translation
// errs further with the travel from the keyframe (the keyframe's depths, the map's scale), by about
// 1 % of the travel along it and 1 % along every axis.
constexpr double kCorrelatedResiduals = 80.0;
constexpr double kScaleSigma = 0.01, kTravelSigma = 0.01;

/// Coarse levels use every n-th point: they only need to find the basin.
int pointStride(int level) { return level >= 2 ? 1 << (level - 1) : 1; }

}  // namespace

std::string TrackerOptions::validate() const {
  std::ostringstream error;
  if (levels < 1 || levels > 8) error << "levels must be in [1, 8] (got " << levels << ")";
  else if (iterations_per_level < 1 || !(min_step >= 0.0)) error << "iterations_per_level must be >= 1, min_step >= 0";
  else if (!(photometric_huber > 0 && photometric_sigma > 0 && edge_huber > 0 && edge_sigma > 0))
    error << "Huber thresholds and sigmas must be > 0";
  else if (!(edge_weight >= 0)) error << "edge_weight must be >= 0";
  else if (!(min_inlier_ratio >= 0 && min_inlier_ratio <= 1 && accept_inlier_ratio >= 0 && accept_inlier_ratio <= 1 &&
             min_points_in_view >= 0 && min_points_in_view <= 1))
    error << "min_inlier_ratio and min_points_in_view must be in [0, 1]";
  else if (!(forward_motion.sigma_deg >= 0 && std::abs(forward_motion.pitch_deg) < 90 && std::abs(forward_motion.yaw_deg) < 90))
    error << "forward_motion: sigma must be >= 0 deg (0: off), pitch and yaw within +-90 deg";
  return error.str();
}

void Tracker::setKeyframe(std::shared_ptr<const Keyframe> keyframe) {
  keyframe_ = std::move(keyframe);
  setReferences();
  const int levels = static_cast<int>(references_.size());
  const PinholeCamera& camera = keyframe_->frame->pyramid->level(0).camera;
  edge_residuals_.clear();
  for (int l = 0; l < levels; ++l) {
    EdgeRegistrationOptions edge_options;
    edge_options.level = l;
    edge_options.huber_threshold = options_.edge_huber;
    edge_residuals_.emplace_back(camera, edge_options);
  }
}

void Tracker::setOptions(const TrackerOptions& options) {
  options_ = options;
  if (keyframe_) setKeyframe(keyframe_);
}

void Tracker::setReferences() {
  const ImagePyramid& pyramid = *keyframe_->frame->pyramid;
  const int levels = std::min(options_.levels, pyramid.levels());
  references_.assign(static_cast<std::size_t>(levels), LevelReference());
  for (int l = 0; l < levels; ++l) {
    const PyramidLevel& level = pyramid.level(l);
    const float scale = static_cast<float>(std::ldexp(1.0, -l));
    LevelReference& reference = references_[static_cast<std::size_t>(l)];
    for (std::size_t i = 0; i < keyframe_->points.size(); i += static_cast<std::size_t>(pointStride(l))) {
      const MapPoint& point = keyframe_->points[i];
      if (!point.hasDepth()) continue;
      const float u = toLevel(point.u, scale), v = toLevel(point.v, scale);
      if (!level.camera.contains(u, v, 3.0)) continue;
      const double z = 1.0 / point.inverse_depth;
      for (const auto& offset : kPatternOffsets) {
        const float x = u + static_cast<float>(offset[0]), y = v + static_cast<float>(offset[1]);
        reference.pattern_points.push_back(level.camera.backProject(x, y, z).cast<float>());
        reference.pattern_values.push_back(sampleBilinear(level.gradient, x, y));
      }
      reference.point_index.push_back(static_cast<int>(i));
    }
  }
  const PinholeCamera& camera = pyramid.level(0).camera;
  const double edge_weight = options_.edge_weight / (options_.edge_sigma * options_.edge_sigma);
  edges_.clear();
  for (const MapPoint& point : keyframe_->points)
    if (point.isEdge() && point.hasDepth())
      edges_.push_back({camera.backProject(point.u, point.v, 1.0 / point.inverse_depth), point.normal.cast<double>(),
                        point.field_layers, edge_weight});
  all_layer_edges_.clear();
  const NearestNeighborFieldView& field = keyframe_->frame->field;
  if (keyframe_->frame->has_field && field.kind == FieldKind::kSnnf && field.all_edges_layer > 0) {
    all_layer_edges_ = edges_;
    for (ReferenceEdge& edge : all_layer_edges_) edge.layers = 1u << field.all_edges_layer;
  }
}

double Tracker::evaluate(const TrackedPoints& points, int level, const Eigen::Isometry3d& T_cam_kf, const ImagePyramid& frame,
                         const NearestNeighborFieldView* field, const ForwardMotionPrior& prior, Normal* normal,
                         TrackingResult* result) const {
  const bool with_edges = field && !points.edges.empty() && options_.edge_weight > 0.0;
  const LevelReference& reference = points.references[static_cast<std::size_t>(level)];
  std::array<LevelSums, kParallelSlices> slices;
  forEachSlice([&](int slice) {
    LevelSums& sums = slices[static_cast<std::size_t>(slice)];
    const auto [begin, end] = sliceRange(reference.point_index.size(), slice);
    addPhotometric(reference, T_cam_kf, frame.level(level), begin, end, normal != nullptr, &sums);
    if (with_edges) {
      const auto [edge_begin, edge_end] = sliceRange(points.edges.size(), slice);
      addEdges(points.edges, level, T_cam_kf, *field, edge_begin, edge_end, normal != nullptr, &sums);
    }
  });
  LevelSums total;
  for (const LevelSums& sums : slices) total += sums;  // in slice order: deterministic
  if (normal) *normal = total.normal;
  if (result) {
    result->points_in_view = total.in_view;
    result->photometric_residuals = total.residuals;
    result->photometric_inliers = total.inliers;
    result->photometric_rmse = total.inliers ? std::sqrt(total.inlier_squares / total.inliers) : 0.0;
    if (with_edges) {
      result->edge_residuals = total.edge_residuals;
      result->edge_inliers = total.edge_inliers;
      result->edge_rmse = total.edge_inliers ? std::sqrt(total.edge_squares / total.edge_inliers) * std::ldexp(1.0, level) : 0.0;
    }
  }
  return total.cost + prior.evaluate(T_cam_kf, normal ? &normal->H : nullptr, normal ? &normal->b : nullptr);
}

void Tracker::addPhotometric(const LevelReference& reference, const Eigen::Isometry3d& T_cam_kf, const PyramidLevel& target,
                             std::size_t begin, std::size_t end, bool with_normal, LevelSums* sums) const {
  const Eigen::Matrix3f R = T_cam_kf.linear().cast<float>();
  const Eigen::Vector3f t = T_cam_kf.translation().cast<float>();
  const float fx = static_cast<float>(target.camera.fx), fy = static_cast<float>(target.camera.fy);
  const float cx = static_cast<float>(target.camera.cx), cy = static_cast<float>(target.camera.cy);
  const float max_x = static_cast<float>(target.camera.width) - 2.0f, max_y = static_cast<float>(target.camera.height) - 2.0f;
  const double k = options_.photometric_huber, inv_var = 1.0 / (options_.photometric_sigma * options_.photometric_sigma);
  const double out_of_view_cost = kPattern * huberCost(2.0 * k, k) * inv_var;
  Eigen::Vector3f projected[kPattern];
  Eigen::Vector2f pixel[kPattern];
  for (std::size_t block = begin; block < end; ++block) {
    bool visible = true;
    for (int j = 0; j < kPattern && visible; ++j) {
      projected[j] = R * reference.pattern_points[block * kPattern + j] + t;
      const float z = projected[j].z();
      pixel[j] = Eigen::Vector2f(fx * projected[j].x() / z + cx, fy * projected[j].y() / z + cy);
      visible = z > 1e-3f && pixel[j].x() >= 1.0f && pixel[j].y() >= 1.0f && pixel[j].x() < max_x && pixel[j].y() < max_y;
    }
    if (!visible) {
      sums->cost += out_of_view_cost;
      continue;
    }
    ++sums->in_view;
    for (int j = 0; j < kPattern; ++j) {
      const float x = pixel[j].x(), y = pixel[j].y();
      const double r = sampleBilinear(target.gradient, x, y) - reference.pattern_values[block * kPattern + j];
      const double a = std::abs(r);
      sums->cost += huberCost(r, k) * inv_var;
      ++sums->residuals;
      if (a <= k) {
        ++sums->inliers;
        sums->inlier_squares += r * r;
      }
      if (!with_normal) continue;
      const double w = huberWeight(r, k) * inv_var;
      const Eigen::Vector3d P = projected[j].cast<double>();
      const double gx = sampleBilinear(target.gradient_dx, x, y) * fx, gy = sampleBilinear(target.gradient_dy, x, y) * fy;
      const Eigen::Vector3d d_point(gx / P.z(), gy / P.z(), -(gx * P.x() + gy * P.y()) / (P.z() * P.z()));
      Vector6d J;
      J << d_point, P.cross(d_point);  // left perturbation: d(exp(xi) P) = v + w x P
      sums->normal.H.noalias() += w * J * J.transpose();
      sums->normal.b.noalias() += w * r * J;
    }
  }
}

void Tracker::addEdges(const std::vector<ReferenceEdge>& edges, int level, const Eigen::Isometry3d& T_cam_kf,
                       const NearestNeighborFieldView& field, std::size_t begin, std::size_t end, bool with_normal,
                       LevelSums* sums) const {
  std::vector<EdgeResidual> residuals;
  sums->cost += edge_residuals_[static_cast<std::size_t>(level)].evaluate(edges, begin, end, field, T_cam_kf, &residuals);
  for (const EdgeResidual& r : residuals) {
    if (with_normal) {
      sums->normal.H.noalias() += r.weight * r.jacobian.transpose() * r.jacobian;
      sums->normal.b.noalias() += r.weight * r.value * r.jacobian.transpose();
    }
    ++sums->edge_residuals;
    if (std::abs(r.value) <= options_.edge_huber) {
      ++sums->edge_inliers;
      sums->edge_squares += r.value * r.value;
    }
  }
}

Tracker::LevelSums& Tracker::LevelSums::operator+=(const LevelSums& other) {
  cost += other.cost;
  inlier_squares += other.inlier_squares;
  edge_squares += other.edge_squares;
  residuals += other.residuals;
  inliers += other.inliers;
  in_view += other.in_view;
  edge_residuals += other.edge_residuals;
  edge_inliers += other.edge_inliers;
  normal.H += other.normal.H;
  normal.b += other.normal.b;
  return *this;
}

double Tracker::optimizeLevel(const TrackedPoints& points, int level, const ImagePyramid& frame, const NearestNeighborFieldView* field,
                              const ForwardMotionPrior& prior, Eigen::Isometry3d* T, int* iterations, Normal* final_normal,
                              TrackingResult* final_counts) const {
  Normal normal;
  TrackingResult counts;  // evaluate()'s counts at *T, kept only when asked
  double cost = evaluate(points, level, *T, frame, field, prior, &normal, final_counts ? &counts : nullptr);
  double lambda = 1e-3;
  for (int it = 0; it < options_.iterations_per_level; ++it) {
    ++*iterations;
    Eigen::Matrix<double, 6, 6> damped = normal.H;
    damped.diagonal() += lambda * normal.H.diagonal() + Vector6d::Constant(1e-9);
    const Vector6d step = -damped.ldlt().solve(normal.b);
    const Eigen::Isometry3d candidate = orthonormalized(se3Exp(step) * *T);
    Normal candidate_normal;
    TrackingResult candidate_counts;
    const double candidate_cost =
        evaluate(points, level, candidate, frame, field, prior, &candidate_normal, final_counts ? &candidate_counts : nullptr);
    if (candidate_cost < cost) {
      *T = candidate;
      cost = candidate_cost;
      normal = candidate_normal;
      counts = candidate_counts;
      lambda = std::max(lambda * 0.5, 1e-6);
      if (step.norm() < options_.min_step) break;
    } else {
      lambda *= 4.0;
      if (lambda > 1e4) break;
    }
  }
  if (final_normal) *final_normal = normal;
  if (final_counts) {
    final_counts->points_in_view = counts.points_in_view;
    final_counts->photometric_residuals = counts.photometric_residuals;
    final_counts->photometric_inliers = counts.photometric_inliers;
    final_counts->photometric_rmse = counts.photometric_rmse;
    final_counts->edge_residuals = counts.edge_residuals;
    final_counts->edge_inliers = counts.edge_inliers;
    final_counts->edge_rmse = counts.edge_rmse;
  }
  return cost;
}

void TrackingResult::scaleTranslation(double scale) {
  T_cam_kf.translation() *= scale;
  covariance.topRows<3>() *= scale;
  covariance.leftCols<3>() *= scale;
}

TrackingResult Tracker::track(const ImagePyramid& frame, const NearestNeighborFieldView* field,
                              const std::vector<Eigen::Isometry3d>& guesses, double previous_inlier_ratio, EdgeLayers layers) const {
  if (!keyframe_ || references_.empty()) return TrackingResult();
  const TrackedPoints points{references_, layers == EdgeLayers::kAllEdges && hasAllEdgesLayer() ? all_layer_edges_ : edges_};
  const int levels = std::min({static_cast<int>(points.references.size()), frame.levels(),
                               field ? static_cast<int>(field->levels.size()) : 99});
  // The first guess (constant velocity) is taken when it tracks well. Otherwise the other guesses
  // are optimised on the coarsest level only (where the basin is found), the one with the lowest
  // cost there goes on through the finer levels, and the lower full-resolution cost of the two wins.
  const std::vector<Eigen::Isometry3d> candidates =
      guesses.empty() ? std::vector<Eigen::Isometry3d>{Eigen::Isometry3d::Identity()} : guesses;
  // The travel the motion model predicts scales the direction prior (frame centre in the keyframe).
  const double predicted_travel = (candidates[0].linear().transpose() * candidates[0].translation()).norm();
  const ForwardMotionPrior prior(options_.forward_motion, predicted_travel);
  const auto refine = [&](TrackingResult* attempt, int from_level) {
    Normal normal;
    double cost = 0.0;
    for (int level = from_level; level > 0; --level)
      optimizeLevel(points, level, frame, field, prior, &attempt->T_cam_kf, &attempt->iterations);
    if (from_level >= 0)  // level 0 leaves its normal equations and counts at the solution
      cost = optimizeLevel(points, 0, frame, field, prior, &attempt->T_cam_kf, &attempt->iterations, &normal, attempt);
    else
      cost = evaluate(points, 0, attempt->T_cam_kf, frame, field, prior, &normal, attempt);
    attempt->covariance = withTravelUncertainty(
        solutionCovariance(normal.H, cost, attempt->photometric_residuals + attempt->edge_residuals, kCorrelatedResiduals),
        attempt->T_cam_kf.translation(), kScaleSigma, kTravelSigma);
    return cost;
  };
  TrackingResult result;
  result.T_cam_kf = candidates[0];
  const double first_cost = refine(&result, levels - 1);
  if (candidates.size() > 1 && result.inlierRatio() < options_.accept_inlier_ratio * previous_inlier_ratio) {
    TrackingResult best;
    double best_coarse = std::numeric_limits<double>::max();
    int iterations = 0;
    for (std::size_t g = 1; g < candidates.size(); ++g) {
      TrackingResult attempt;
      attempt.T_cam_kf = candidates[g];
      attempt.guess = static_cast<int>(g);
      const double coarse = optimizeLevel(points, levels - 1, frame, field, prior, &attempt.T_cam_kf, &iterations);
      if (coarse < best_coarse) {
        best_coarse = coarse;
        best = attempt;
      }
    }
    const double cost = refine(&best, levels - 2);
    iterations += result.iterations + best.iterations;
    if (cost < first_cost) result = best;
    result.iterations = iterations;
  }

  // Mean flow of the keyframe points: keyframe decisions.
  const PinholeCamera& camera = frame.level(0).camera;
  double flow = 0.0;
  int counted = 0;
  for (const MapPoint& point : keyframe_->points) {
    if (!point.hasDepth()) continue;
    const Eigen::Vector3d p = result.T_cam_kf * camera.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    if (p.z() <= 1e-3) continue;
    flow += (camera.project(p) - Eigen::Vector2d(point.u, point.v)).norm();
    ++counted;
  }
  result.mean_flow = counted ? flow / counted : 0.0;
  result.points = static_cast<int>(points.references[0].point_index.size());
  const double blocks = result.points;
  result.ok = blocks > 0 && result.points_in_view >= options_.min_points_in_view * blocks &&
              result.photometric_inliers >= options_.min_inlier_ratio * std::max(1, result.photometric_residuals);
  return result;
}

}  // namespace semantic_edge_vo
