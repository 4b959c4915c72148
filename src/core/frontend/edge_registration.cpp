#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/frontend/edge_registration.h"

#include <cmath>
#include <sstream>

namespace semantic_edge_vo {

std::string EdgeRegistrationOptions::validate() const {
  std::ostringstream error;
  if (level < 0) error << "level must be >= 0 (got " << level << ")";
  else if (max_iterations < 1) error << "max_iterations must be >= 1 (got " << max_iterations << ")";
  else if (!(huber_threshold > 0.0)) error << "huber_threshold must be > 0 pixels (got " << huber_threshold << ")";
  else if (!(initial_lambda >= 0.0)) error << "initial_lambda must be >= 0 (got " << initial_lambda << ")";
  return error.str();
}

EdgeRegistration::EdgeRegistration(const PinholeCamera& camera, const EdgeRegistrationOptions& options)
    : camera_(camera.scaled(std::ldexp(1.0, -options.level))), options_(options) {}

void EdgeRegistration::layersOf(const ReferenceEdge& edge, const Eigen::Isometry3d& T_target_ref,
                                const NearestNeighborFieldView& field, std::vector<int>* layers) const {
  layers->clear();
  switch (field.kind) {
    case FieldKind::kAnnf:
      layers->push_back(0);
      return;
    case FieldKind::kSnnf:
      for (int layer = 0; layer < field.num_layers; ++layer)
        if ((edge.layers >> layer) & 1u) layers->push_back(layer);
      return;
    case FieldKind::kOnnf: {
      // The gradient direction as the current estimate warps it: move one pixel along the normal
      // at the same depth in the reference image, and see where both points land in the target.
      const Eigen::Vector2d p = camera_.project(edge.point);
      const Eigen::Vector3d along = camera_.backProject(p.x() + edge.normal.x(), p.y() + edge.normal.y(), edge.point.z());
      const Eigen::Vector3d a = T_target_ref * edge.point, b = T_target_ref * along;
      if (a.z() <= 0.0 || b.z() <= 0.0) return;
      const Eigen::Vector2d direction = camera_.project(b) - camera_.project(a);
      layers->push_back(field.orientationBin(static_cast<float>(direction.x()), static_cast<float>(direction.y())));
      return;
    }
  }
}

double EdgeRegistration::addResidual(double weight, const Eigen::Vector3d& p_target, const Eigen::Vector2d& projected,
                                     const FieldMatch& match, std::vector<EdgeResidual>* out) const {
  const double z = p_target.z();
  const Eigen::Vector2d normal(match.normal_x, match.normal_y);
  EdgeResidual residual;
  residual.value = normal.dot(projected - Eigen::Vector2d(match.u, match.v));
  Eigen::Matrix<double, 2, 3> d_pixel_d_point;
  d_pixel_d_point << camera_.fx / z, 0.0, -camera_.fx * p_target.x() / (z * z),  //
      0.0, camera_.fy / z, -camera_.fy * p_target.y() / (z * z);
  Eigen::Matrix<double, 3, 6> d_point_d_twist;  // left perturbation: exp(xi) * p = p + v + w x p
  d_point_d_twist << Eigen::Matrix3d::Identity(), -skew(p_target);
  residual.jacobian = normal.transpose() * d_pixel_d_point * d_point_d_twist;
  residual.weight = weight * huberWeight(residual.value, options_.huber_threshold);
  out->push_back(residual);
  return weight * huberCost(residual.value, options_.huber_threshold);
}

double EdgeRegistration::evaluate(const std::vector<ReferenceEdge>& edges, std::size_t begin, std::size_t end,
                                  const NearestNeighborFieldView& field, const Eigen::Isometry3d& T_target_ref,
                                  std::vector<EdgeResidual>* out) const {
  out->clear();
  const double unmatched_cost = huberCost(field.truncation_radius, options_.huber_threshold);
  double cost = 0.0;
  std::vector<int> layers;
  for (std::size_t i = begin; i < end; ++i) {
    const ReferenceEdge& edge = edges[i];
    layersOf(edge, T_target_ref, field, &layers);
    if (layers.empty()) continue;
    const Eigen::Vector3d p_target = T_target_ref * edge.point;
    // One association per layer: a pixel of several classes meets the nearest edge of each (Eq. 10).
    const double weight = edge.weight;
    if (!(p_target.z() > 1e-3)) {
      cost += static_cast<double>(layers.size()) * weight * unmatched_cost;
      continue;
    }
    const Eigen::Vector2d projected = camera_.project(p_target);
    const float x = static_cast<float>(projected.x()), y = static_cast<float>(projected.y());
    for (int layer : layers) {
      FieldMatch match;
      const bool matched = field.nearest(options_.level, layer, x, y, &match);
      cost += matched ? addResidual(weight, p_target, projected, match, out) : weight * unmatched_cost;
    }
  }
  return cost;
}

std::vector<EdgeResidual> EdgeRegistration::residuals(const std::vector<ReferenceEdge>& edges,
                                                      const NearestNeighborFieldView& field,
                                                      const Eigen::Isometry3d& T_target_ref) const {
  std::vector<EdgeResidual> out;
  evaluate(edges, field, T_target_ref, &out);
  return out;
}

EdgeRegistrationResult EdgeRegistration::align(const std::vector<ReferenceEdge>& edges,
                                               const NearestNeighborFieldView& field,
                                               const Eigen::Isometry3d& T_target_ref_initial) const {
  EdgeRegistrationResult result;
  result.T_target_ref = T_target_ref_initial;
  std::vector<EdgeResidual> current, candidate;
  double cost = evaluate(edges, field, result.T_target_ref, &current);
  double lambda = options_.initial_lambda;
  for (; result.iterations < options_.max_iterations; ++result.iterations) {
    if (current.size() < 6) break;  // too few associations to constrain 6 degrees of freedom
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Vector6d b = Vector6d::Zero();
    for (const EdgeResidual& r : current) {
      H.noalias() += r.weight * r.jacobian.transpose() * r.jacobian;
      b.noalias() += r.weight * r.jacobian.transpose() * r.value;
    }
    bool accepted = false;
    Vector6d step = Vector6d::Zero();
    for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
      Eigen::Matrix<double, 6, 6> damped = H;
      damped.diagonal() += lambda * H.diagonal();
      step = -damped.ldlt().solve(b);
      const Eigen::Isometry3d T_candidate = se3Exp(step) * result.T_target_ref;
      const double candidate_cost = evaluate(edges, field, T_candidate, &candidate);
      if (candidate_cost < cost) {
        accepted = true;
        result.T_target_ref = T_candidate;
        cost = candidate_cost;
        current.swap(candidate);
        lambda = std::max(lambda * 0.25, 1e-9);
      } else {
        lambda = std::max(lambda, 1e-6) * 8.0;
      }
    }
    if (!accepted || step.norm() < options_.min_step) {
      result.converged = true;
      break;
    }
  }
  result.residuals = static_cast<int>(current.size());
  double sum = 0.0;
  for (const EdgeResidual& r : current) {
    if (std::abs(r.value) <= options_.huber_threshold) {
      ++result.inliers;
      sum += r.value * r.value;
    }
  }
  result.rmse = result.inliers ? std::sqrt(sum / result.inliers) : 0.0;
  return result;
}

}  // namespace semantic_edge_vo
