#include "semantic_edge_vo/backend/window_optimizer.h"

#include <numeric>
#include <sstream>

#include <ceres/iteration_callback.h>
#include <ceres/loss_function.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "semantic_edge_vo/backend/factors/relative_rotation_factor.h"
#include "semantic_edge_vo/backend/factors/travel_direction_factor.h"
#include "semantic_edge_vo/backend/factors/window_observations.h"
#include "semantic_edge_vo/common/parallel_slices.h"

namespace semantic_edge_vo {
namespace {

/// The nearest edge of the point's semantic layers (any edge for ANNF/ONNF fields), within `radius`.
bool associate(const NearestNeighborFieldView& field, std::uint32_t layers, const Eigen::Vector2d& pixel, double radius,
               FieldMatch* best) {
  bool found = false;
  FieldMatch match;
  for (int layer = 0; layer < field.num_layers; ++layer) {
    if (field.kind == FieldKind::kSnnf && !((layers >> layer) & 1u)) continue;
    if (field.nearestWithin(0, layer, static_cast<float>(pixel.x()), static_cast<float>(pixel.y()), static_cast<float>(radius), &match) &&
        (!found || match.distance < best->distance)) {
      *best = match;
      found = true;
    }
  }
  return found;
}


/// A point of the window, by its host (position in the window) and index: inverse depths live in a
/// vector parallel to these, so that they are written back.
struct PointRef {
  std::size_t host;
  std::size_t index;
};

/// Priors on each pair of consecutive keyframes: the forward motion of a car, and the rotation and
/// direction of travel their corners measured (KeyframeMotion).
void addMeasuredMotionPriors(const WindowOptimizerOptions& options, const std::deque<std::shared_ptr<Keyframe>>& window,
                             std::size_t first, ceres::LossFunction* measured_motion_loss,
                             std::vector<factors::PoseParameters>* poses_out, ceres::Problem* problem) {
  std::vector<factors::PoseParameters>& poses = *poses_out;
  const std::size_t count = window.size() - first;
  for (std::size_t k = 1; k < count; ++k) {
    const Keyframe& earlier = *window[first + k - 1];
    const Keyframe& later = *window[first + k];
    if (options.forward_motion.sigma_deg > 0.0)
      problem->AddResidualBlock(factors::forwardMotionFactor(options.forward_motion, earlier.T_world_cam, later.T_world_cam), nullptr,
                               poses[k - 1].data(), poses[k].data());
    const MeasuredMotion& measured = later.measured_motion;
    if (measured.from_id != earlier.id) continue;
    if (options.measured_rotation_sigma_deg > 0.0)
      problem->AddResidualBlock(new factors::RelativeRotationFactor(measured.R_from_this, options.measured_rotation_sigma_deg * M_PI / 180.0),
                               measured_motion_loss, poses[k - 1].data(), poses[k].data());
    if (options.measured_direction_sigma_deg > 0.0) {
      const double distance = (later.T_world_cam.translation() - earlier.T_world_cam.translation()).norm();
      problem->AddResidualBlock(
          new factors::TravelDirectionFactor(measured.direction, options.measured_direction_sigma_deg * M_PI / 180.0, distance),
          measured_motion_loss, poses[k - 1].data(), poses[k].data());
    }
  }
}

/// Each point's observations in the other keyframes (projection, nearest edge of its layers), found
/// on both cores in slots of their own (count - 1 per point, `found_count` of them used) and
/// returned in order; each point's inverse depth is copied into `inverse_depths`.
std::vector<factors::Observation> observePoints(const WindowOptimizerOptions& options, const std::deque<std::shared_ptr<Keyframe>>& window,
                                                std::size_t first, const std::vector<PointRef>& refs, std::vector<double>* inverse_depths_out,
                                                std::vector<std::size_t>* found_count_out) {
  std::vector<double>& inverse_depths = *inverse_depths_out;
  const std::size_t count = window.size() - first;
  const PinholeCamera& camera = window[first]->frame->pyramid->level(0).camera;
  std::vector<Eigen::Isometry3d> T_target_host(count * count);  // [host * count + target]
  for (std::size_t h = 0; h < count; ++h)
    for (std::size_t t = 0; t < count; ++t) T_target_host[h * count + t] = window[first + t]->T_world_cam.inverse() * window[first + h]->T_world_cam;
  const std::size_t slots = count - 1;
  std::vector<factors::Observation> found(refs.size() * slots);
  std::vector<std::size_t>& found_count = *found_count_out;
  found_count.assign(refs.size(), 0);
  forEachIndex(refs.size(), [&](std::size_t r) {
    const Keyframe& host = *window[first + refs[r].host];
    const MapPoint& point = host.points[refs[r].index];
    inverse_depths[r] = point.inverse_depth;
    factors::Observation observation;
    observation.host = static_cast<int>(refs[r].host);
    observation.host_ray = camera.backProject(point.u, point.v, 1.0);
    observation.host_value = sampleBilinear(host.frame->pyramid->level(0).gradient, point.u, point.v);
    observation.inverse_depth = &inverse_depths[r];
    observation.prior = point.inverse_depth;
    observation.prior_sigma = options.depth_prior_scale * std::sqrt(point.inverse_depth_variance);
    const Eigen::Vector3d X_host = camera.backProject(point.u, point.v, 1.0 / point.inverse_depth);
    for (std::size_t t = 0; t < count; ++t) {
      if (t == refs[r].host) continue;
      const Keyframe& target = *window[first + t];
      const Eigen::Vector3d p = T_target_host[refs[r].host * count + t] * X_host;
      if (p.z() <= 1e-3) continue;
      const Eigen::Vector2d pixel = camera.project(p);
      if (!camera.contains(pixel.x(), pixel.y(), 4.0)) continue;
      observation.target = static_cast<int>(t);
      observation.has_prior = found_count[r] == 0;  // the point's first observation carries its prior
      FieldMatch match;
      observation.has_edge = point.isEdge() && options.edge_weight > 0.0 && target.frame->has_field &&
                             associate(target.frame->field, point.field_layers, pixel, options.edge_radius, &match);
      if (observation.has_edge) {
        observation.match = Eigen::Vector2d(match.u, match.v);
        observation.normal = Eigen::Vector2d(match.normal_x, match.normal_y);
      }
      found[r * slots + found_count[r]++] = observation;
    }
  });
  return found;
}

/// The window's scale toward the road (see WindowOptimizer): each keyframe whose road plane is
/// found and agrees with metres measures log(camera height / plane height) with sigma
/// height_sigma; the scale's change in one solve has the prior sigma scale_sigma. The minimum of
/// those terms along the scale gauge, in closed form, is applied about the oldest keyframe (held).
void scaleTowardTheRoad(const RoadScaleOptions& road, const std::deque<std::shared_ptr<Keyframe>>& window, std::size_t first,
                        WindowOptimizerResult* result) {
  const RoadPlaneFinder finder(road, window[first]->frame->pyramid->level(0).camera);
  double measured = 0.0;  // sum of the keyframes' log scale errors
  for (std::size_t k = first; k < window.size(); ++k) {
    const RoadFit fit = finder.fitKeyframe(*window[k]);
    if (!fit.found || !finder.agreesWithMetres(fit.height)) continue;
    measured += std::log(road.camera_height / fit.height);
    ++result->road_keyframes;
  }
  if (result->road_keyframes == 0) return;  // held
  const double measurement_weight = 1.0 / (road.height_sigma * road.height_sigma), prior_weight = 1.0 / (road.scale_sigma * road.scale_sigma);
  const double scale = std::exp(measured * measurement_weight / (result->road_keyframes * measurement_weight + prior_weight));
  result->scale_step = scale;
  const Eigen::Vector3d about = window[first]->T_world_cam.translation();
  for (std::size_t k = first; k < window.size(); ++k) scaleAbout(scale, about, window[k].get());
}

/// Ends a solve early when asked to (someone waits for the mapping thread), but not before its first
/// iteration (Ceres calls back at iteration 0 too, before any step): each window moves its poses.
class StopWhenAsked : public ceres::IterationCallback {
 public:
  explicit StopWhenAsked(const std::function<bool()>& stop) : stop_(stop) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.iteration >= 1 && stop_() ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<bool()>& stop_;
};

/// Solves the window; true when the solution is usable and no worse than the start. Without `stop`
/// (or while it returns false) the solve is deterministic.
bool solve(int max_iterations, const std::function<bool()>& stop, ceres::Problem* problem, WindowOptimizerResult* result) {
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.max_num_iterations = max_iterations;
  solver.num_threads = 1;  // deterministic: the observations are evaluated on both cores by the callback
  // With bounds (the inverse depths'), Ceres follows each step with a projected line search that
  // evaluates the Jacobians again: 40 % of the solve. The bound is still kept by projection.
  solver.max_num_line_search_step_size_iterations = 0;
  solver.logging_type = ceres::SILENT;
  StopWhenAsked stop_when_asked(stop);
  if (stop) solver.callbacks.push_back(&stop_when_asked);
  ceres::Solver::Summary summary;
  ceres::Solve(solver, problem, &summary);
  result->initial_cost = summary.initial_cost;
  result->final_cost = summary.final_cost;
  return summary.IsSolutionUsable() && summary.final_cost <= summary.initial_cost;
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

factors::ObservationWeights WindowOptimizerOptions::observationWeights() const {
  return {photometric_sigma, photometric_huber, edge_sigma, edge_huber, edge_weight};
}

WindowOptimizerResult WindowOptimizer::optimize(const std::deque<std::shared_ptr<Keyframe>>& window,
                                                const std::function<bool()>& stop) const {
  WindowOptimizerResult result;
  const std::size_t count = std::min(window.size(), static_cast<std::size_t>(options_.keyframes));
  if (count < 2) return result;
  const std::size_t first = window.size() - count;
  result.keyframes = static_cast<int>(count);
  if (road_.enabled()) scaleTowardTheRoad(road_, window, first, &result);

  std::vector<factors::PoseParameters> poses;
  std::vector<std::unique_ptr<ceres::Grid2D<float, 1>>> grids;
  std::vector<std::unique_ptr<factors::Interpolator>> interpolators;
  std::vector<const factors::Interpolator*> images;
  for (std::size_t k = first; k < window.size(); ++k) {
    poses.push_back(factors::toParameters(window[k]->T_world_cam));
    const cv::Mat& gradient = window[k]->frame->pyramid->level(0).gradient;
    CV_Assert(gradient.isContinuous());
    grids.push_back(std::make_unique<ceres::Grid2D<float, 1>>(gradient.ptr<float>(), 0, gradient.rows, 0, gradient.cols));
    interpolators.push_back(std::make_unique<factors::Interpolator>(*grids.back()));
    images.push_back(interpolators.back().get());
  }
  const PinholeCamera& camera = window[first]->frame->pyramid->level(0).camera;
  factors::WindowObservations observations(poses, images, camera, options_.observationWeights());

  // One loss object shared by the measured-motion residuals (the problem does not own it).
  constexpr double kMeasuredMotionHuber = 3.0;  // sigmas: a measurement far off (corners on traffic) pulls with a bounded force
  ceres::HuberLoss measured_motion_loss(kMeasuredMotionHuber);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.evaluation_callback = &observations;
  ceres::Problem problem(problem_options);
  for (factors::PoseParameters& pose : poses) problem.AddParameterBlock(pose.data(), 7, new factors::PoseManifold());
  problem.SetParameterBlockConstant(poses[0].data());
  addMeasuredMotionPriors(options_, window, first, &measured_motion_loss, &poses, &problem);

  std::vector<PointRef> refs;
  std::vector<double> inverse_depths;
  for (std::size_t h = 0; h < count; ++h)
    for (std::size_t i = 0; i < window[first + h]->points.size(); i += static_cast<std::size_t>(options_.point_stride))
      if (window[first + h]->points[i].hasDepth()) refs.push_back({h, i});
  inverse_depths.resize(refs.size());
  std::vector<std::size_t> found_count;
  const std::vector<factors::Observation> found = observePoints(options_, window, first, refs, &inverse_depths, &found_count);
  const std::size_t slots = count - 1;
  observations.reserve(std::accumulate(found_count.begin(), found_count.end(), std::size_t{0}));
  for (std::size_t r = 0; r < refs.size(); ++r) {
    if (found_count[r] == 0) continue;
    for (std::size_t k = 0; k < found_count[r]; ++k) {
      const factors::Observation& observation = found[r * slots + k];
      problem.AddResidualBlock(observations.add(observation), nullptr, poses[static_cast<std::size_t>(observation.host)].data(),
                               poses[static_cast<std::size_t>(observation.target)].data(), &inverse_depths[r]);
      ++result.photometric_residuals;
      result.edge_residuals += observation.has_edge;
    }
    problem.SetParameterLowerBound(&inverse_depths[r], 0, 1e-4);
    ++result.points;
  }
  if (result.photometric_residuals == 0) return result;
  problem.AddResidualBlock(observations.remainderBlock(), nullptr, poses.back().data());  // the newest pose is never held

  result.solved = solve(options_.max_iterations, stop, &problem, &result);
  if (!result.solved) return result;

  for (std::size_t k = 1; k < count; ++k) window[first + k]->T_world_cam = factors::fromParameters(poses[k].data());
  for (std::size_t r = 0; r < refs.size(); ++r)
    if (problem.HasParameterBlock(&inverse_depths[r])) window[first + refs[r].host]->points[refs[r].index].inverse_depth = inverse_depths[r];
  return result;
}

}  // namespace semantic_edge_vo
