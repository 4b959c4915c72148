#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

/// An edge pixel of the reference frame with known depth.
struct ReferenceEdge {
  Eigen::Vector3d point;        ///< in the reference optical frame, metres
  Eigen::Vector2d normal;       ///< unit gradient direction in the reference image
  std::uint32_t layers = 1;     ///< its SNNF layers (MapPoint::field_layers): it meets the nearest edge of each
  double weight = 1.0;
};

struct EdgeRegistrationOptions {
  int level = 0;               ///< pyramid level of the target field used
  int max_iterations = 50;
  double huber_threshold = 2.0;  ///< pixels of the level
  double min_step = 1e-7;        ///< stop when the update's norm falls below this (twist units)
  double initial_lambda = 1e-4;  ///< Levenberg-Marquardt damping, relative to diag(H)

  std::string validate() const;
};

/// One point-to-tangent residual of a projected reference edge against its match.
struct EdgeResidual {
  double value = 0.0;               ///< n_match . (p_projected - p_match), level pixels
  Eigen::Matrix<double, 1, 6> jacobian;  ///< d value / d twist (left perturbation of T_target_ref)
  double weight = 0.0;              ///< edge weight x Huber weight
};

struct EdgeRegistrationResult {
  Eigen::Isometry3d T_target_ref = Eigen::Isometry3d::Identity();
  int iterations = 0;
  int residuals = 0;     ///< residuals at the solution
  int inliers = 0;       ///< of which below the Huber threshold
  double rmse = 0.0;     ///< of the inlier residuals, level pixels
  bool converged = false;
};

/// Edge-only registration (paper III-A/B): reference edges with depth are projected into the target
/// frame, each is associated with the nearest edge of its field layer (ANNF: all edges; ONNF: the bin
/// of its warped gradient direction; SNNF: each of its classes, one residual per class as in Eq. 10), and the point-to-tangent distances
/// are minimised under a Huber norm by iteratively reweighted Levenberg-Marquardt on SE(3), with the
/// association recomputed every iteration (ICP).
class EdgeRegistration {
 public:
  EdgeRegistration(const PinholeCamera& camera, const EdgeRegistrationOptions& options);

  EdgeRegistrationResult align(const std::vector<ReferenceEdge>& edges, const NearestNeighborFieldView& field,
                               const Eigen::Isometry3d& T_target_ref_initial) const;

  /// Residuals (with weights) at a pose and their robust cost; an association that finds nothing within the
  /// truncation radius costs as much as a residual of that radius, so that costs at different poses
  /// compare even when points lose or gain their matches.
  double evaluate(const std::vector<ReferenceEdge>& edges, const NearestNeighborFieldView& field,
                  const Eigen::Isometry3d& T_target_ref, std::vector<EdgeResidual>* out) const {
    return evaluate(edges, 0, edges.size(), field, T_target_ref, out);
  }
  /// The same for edges[begin, end).
  double evaluate(const std::vector<ReferenceEdge>& edges, std::size_t begin, std::size_t end, const NearestNeighborFieldView& field,
                  const Eigen::Isometry3d& T_target_ref, std::vector<EdgeResidual>* out) const;
  /// Residuals of every association at a pose (exposed for tests and diagnostics).
  std::vector<EdgeResidual> residuals(const std::vector<ReferenceEdge>& edges, const NearestNeighborFieldView& field,
                                      const Eigen::Isometry3d& T_target_ref) const;

 private:
  /// Appends the residual of an edge seen at `p_target` (its pixel `projected`) against `match`, at
  /// `weight`; returns its robust cost.
  double addResidual(double weight, const Eigen::Vector3d& p_target, const Eigen::Vector2d& projected, const FieldMatch& match,
                     std::vector<EdgeResidual>* out) const;
  /// Layers of the field the edge is registered to, at the pose.
  void layersOf(const ReferenceEdge& edge, const Eigen::Isometry3d& T_target_ref, const NearestNeighborFieldView& field,
                std::vector<int>* layers) const;

  PinholeCamera camera_;  ///< of the registration level
  EdgeRegistrationOptions options_;
};

}  // namespace semantic_edge_vo
