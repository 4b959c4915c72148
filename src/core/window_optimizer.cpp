#include "semantic_edge_vo/window_optimizer.h"

#include <sstream>

#include "semantic_edge_vo/factors/edge_factor.h"
#include "semantic_edge_vo/factors/relative_rotation_factor.h"
#include "semantic_edge_vo/factors/travel_direction_factor.h"
#include "semantic_edge_vo/factors/inverse_depth_prior.h"
#include "semantic_edge_vo/factors/photometric_factor.h"

namespace semantic_edge_vo {
namespace {

/// The nearest edge of a class the point has (any edge for ANNF/ONNF fields), within `radius`.
bool associate(const NearestNeighborFieldView& field, std::uint32_t class_mask, const Eigen::Vector2d& pixel, double radius,
               FieldMatch* best) {
  bool found = false;
  FieldMatch match;
  for (int layer = 0; layer < field.num_layers; ++layer) {
    if (field.kind == FieldKind::kSnnf && !((class_mask >> layer) & 1u)) continue;
    if (field.nearestWithin(0, layer, static_cast<float>(pixel.x()), static_cast<float>(pixel.y()), static_cast<float>(radius), &match) &&
        (!found || match.distance < best->distance)) {
      *best = match;
      found = true;
    }
  }
  return found;
}

}  // namespace

std::string WindowOptimizerOptions::validate() const {
  std::ostringstream error;
  if (keyframes < 2 || max_iterations < 1 || point_stride < 1) error << "need keyframes >= 2, max_iterations >= 1, point_stride >= 1";
  else if (!(photometric_sigma > 0 && photometric_huber > 0 && edge_sigma > 0 && edge_huber > 0 && edge_weight >= 0 && edge_radius > 0 &&
             depth_prior_scale > 0))
    error << "sigmas, Huber thresholds, the edge radius and depth_prior_scale must be > 0, edge_weight >= 0";
  else if (!(measured_rotation_sigma_deg >= 0 && measured_direction_sigma_deg >= 0))
    error << "measured_rotation_sigma and measured_direction_sigma must be >= 0 deg (0: off)";
  return error.str();
}

WindowOptimizerResult WindowOptimizer::optimize(const std::deque<std::shared_ptr<Keyframe>>& window) const {
  WindowOptimizerResult result;
  const std::size_t count = std::min(window.size(), static_cast<std::size_t>(options_.keyframes));
  if (count < 2) return result;
  const std::size_t first = window.size() - count;
  result.keyframes = static_cast<int>(count);

  std::vector<factors::PoseParameters> poses;
  std::vector<std::unique_ptr<ceres::Grid2D<float, 1>>> grids;
  std::vector<std::unique_ptr<factors::Interpolator>> interpolators;
  for (std::size_t k = first; k < window.size(); ++k) {
    poses.push_back(factors::toParameters(window[k]->T_world_cam));
    const cv::Mat& gradient = window[k]->frame->pyramid->level(0).gradient;
    CV_Assert(gradient.isContinuous());
    grids.push_back(std::make_unique<ceres::Grid2D<float, 1>>(gradient.ptr<float>(), 0, gradient.rows, 0, gradient.cols));
    interpolators.push_back(std::make_unique<factors::Interpolator>(*grids.back()));
  }
  const PinholeCamera& camera = window[first]->frame->pyramid->level(0).camera;
  std::vector<factors::PosePairCache> pair_caches(count * count);  // [host * count + target]

  // One loss object per kind of residual, shared by all of them (the problem does not own them):
  // a window has tens of thousands of residuals.
  constexpr double kMeasuredMotionHuber = 3.0;  // sigmas: a measurement far off (corners on traffic) pulls with a bounded force
  ceres::HuberLoss measured_motion_loss(kMeasuredMotionHuber);
  ceres::HuberLoss photometric_loss(options_.photometric_huber / options_.photometric_sigma);
  ceres::ScaledLoss edge_loss(new ceres::HuberLoss(options_.edge_huber / options_.edge_sigma), options_.edge_weight, ceres::TAKE_OWNERSHIP);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (factors::PoseParameters& pose : poses) problem.AddParameterBlock(pose.data(), 7, new factors::PoseManifold());
  problem.SetParameterBlockConstant(poses[0].data());
  for (std::size_t k = 1; k < count; ++k) {
    const Keyframe& earlier = *window[first + k - 1];
    const Keyframe& later = *window[first + k];
    if (options_.forward_motion.sigma_deg > 0.0)
      problem.AddResidualBlock(factors::forwardMotionFactor(options_.forward_motion, earlier.T_world_cam, later.T_world_cam), nullptr,
                               poses[k - 1].data(), poses[k].data());
    const MeasuredMotion& measured = later.measured_motion;
    if (measured.from_id != earlier.id) continue;
    if (options_.measured_rotation_sigma_deg > 0.0)
      problem.AddResidualBlock(new factors::RelativeRotationFactor(measured.R_from_this, options_.measured_rotation_sigma_deg * M_PI / 180.0),
                               &measured_motion_loss, poses[k - 1].data(), poses[k].data());
    if (options_.measured_direction_sigma_deg > 0.0) {
      const double distance = (later.T_world_cam.translation() - earlier.T_world_cam.translation()).norm();
      problem.AddResidualBlock(
          new factors::TravelDirectionFactor(measured.direction, options_.measured_direction_sigma_deg * M_PI / 180.0, distance),
          &measured_motion_loss, poses[k - 1].data(), poses[k].data());
    }
  }

  // Inverse depths live in a vector parallel to (host, point index) so that they are written back.
  struct PointRef {
    std::size_t host;
    std::size_t index;
  };
  std::vector<PointRef> refs;
  std::vector<double> inverse_depths;
  for (std::size_t h = 0; h < count; ++h)
    for (std::size_t i = 0; i < window[first + h]->points.size(); i += static_cast<std::size_t>(options_.point_stride))
      if (window[first + h]->points[i].hasDepth()) refs.push_back({h, i});
  inverse_depths.resize(refs.size());

  for (std::size_t r = 0; r < refs.size(); ++r) {
    const Keyframe& host = *window[first + refs[r].host];
    const MapPoint& point = host.points[refs[r].index];
    inverse_depths[r] = point.inverse_depth;
    const Eigen::Vector3d ray = camera.backProject(point.u, point.v, 1.0);
    const double host_value = sampleBilinear(host.frame->pyramid->level(0).gradient, point.u, point.v);
    int observed = 0;
    for (std::size_t t = 0; t < count; ++t) {
      if (t == refs[r].host) continue;
      const Keyframe& target = *window[first + t];
      const Eigen::Vector3d p = target.T_world_cam.inverse() * host.T_world_cam * camera.backProject(point.u, point.v, 1.0 / point.inverse_depth);
      if (p.z() <= 1e-3) continue;
      const Eigen::Vector2d pixel = camera.project(p);
      if (!camera.contains(pixel.x(), pixel.y(), 4.0)) continue;
      double* host_pose = poses[refs[r].host].data();
      double* target_pose = poses[t].data();
      factors::PosePairCache& pair = pair_caches[refs[r].host * count + t];
      problem.AddResidualBlock(new factors::PhotometricFactor(pair, ray, host_value, *interpolators[t], camera, options_.photometric_sigma),
                               &photometric_loss, host_pose, target_pose, &inverse_depths[r]);
      ++result.photometric_residuals;
      ++observed;
      FieldMatch match;
      if (point.isEdge() && options_.edge_weight > 0.0 && target.frame->has_field &&
          associate(target.frame->field, point.class_mask, pixel, options_.edge_radius, &match)) {
        problem.AddResidualBlock(
            new factors::EdgeFactor(pair, ray, Eigen::Vector2d(match.u, match.v), Eigen::Vector2d(match.normal_x, match.normal_y), camera,
                                    options_.edge_sigma),
            &edge_loss, host_pose, target_pose, &inverse_depths[r]);
        ++result.edge_residuals;
      }
    }
    if (observed == 0) continue;
    const double prior_sigma = options_.depth_prior_scale * std::sqrt(point.inverse_depth_variance);
    problem.AddResidualBlock(factors::InverseDepthPrior::Create(point.inverse_depth, prior_sigma), nullptr, &inverse_depths[r]);
    problem.SetParameterLowerBound(&inverse_depths[r], 0, 1e-4);
    ++result.points;
  }
  if (result.photometric_residuals == 0) return result;

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.max_num_iterations = options_.max_iterations;
  solver.num_threads = 1;  // deterministic, and the pose-pair caches are not thread-safe
  // With bounds (the inverse depths'), Ceres follows each step with a projected line search that
  // evaluates the Jacobians again: 40 % of the solve. The bound is still kept by projection.
  solver.max_num_line_search_step_size_iterations = 0;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.solved = summary.IsSolutionUsable() && summary.final_cost <= summary.initial_cost;
  if (!result.solved) return result;

  for (std::size_t k = 1; k < count; ++k) window[first + k]->T_world_cam = factors::fromParameters(poses[k].data());
  for (std::size_t r = 0; r < refs.size(); ++r)
    if (problem.HasParameterBlock(&inverse_depths[r])) window[first + refs[r].host]->points[refs[r].index].inverse_depth = inverse_depths[r];
  return result;
}

}  // namespace semantic_edge_vo
