#pragma once
#include <string>
#include <vector>

#include "semantic_edge_vo/frontend/edge_registration.h"
#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

/// One frame pair of the convergence experiment: reference edges with ground-truth depth, the
/// target frame's edges (its field is built per kind), and the true relative pose.
struct RegistrationProblem {
  PinholeCamera camera;
  std::vector<ReferenceEdge> reference;
  EdgeSet target_edges;
  std::vector<std::string> class_names;
  Eigen::Isometry3d T_target_ref = Eigen::Isometry3d::Identity();  ///< ground truth
};

struct ConvergenceOptions {
  std::vector<double> displacements_m = {0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0};
  std::vector<double> rotations_deg = {0.0, 1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 10.0, 12.0, 15.0};
  int trials = 40;                       ///< random directions per displacement and problem
  double success_translation_m = 0.10;   ///< a trial succeeds when the final error is below both
  double success_rotation_deg = 0.5;
  std::uint64_t seed = 1;
  EdgeRegistrationOptions registration;  ///< single level, as in the paper
  FieldOptions field;                    ///< kind set per run; one pyramid level is enough

  std::string validate() const;
};

struct ConvergenceRow {
  double displacement = 0.0;       ///< metres (translation table) or degrees (rotation table)
  double median_error_m = 0.0;     ///< median final translation error over the trials
  double median_error_deg = 0.0;   ///< median final rotation error over the trials
  double success_rate = 0.0;       ///< fraction of trials below both success thresholds
  int trials = 0;
};

struct ConvergenceCurve {
  FieldKind kind = FieldKind::kSnnf;
  std::vector<ConvergenceRow> translation;  ///< initial pose displaced in random 3D directions
  std::vector<ConvergenceRow> rotation;     ///< initial pose rotated about random axes
  double basin_m = 0.0;    ///< largest displacement with success >= 50 % (all smaller ones too)
  double basin_deg = 0.0;  ///< the same for rotations
};

/// Runs the edge-only registration of every problem from perturbed initial poses with one field
/// kind. Deterministic for options.seed: every kind sees the same perturbations.
ConvergenceCurve runConvergence(const std::vector<RegistrationProblem>& problems, FieldKind kind,
                                const ConvergenceOptions& options);

/// Largest x with success >= 50 % such that every smaller x also reaches it (0 when none).
double basinOf(const std::vector<ConvergenceRow>& rows);

/// The curves as JSON: {"<kind>": {"basin_m", "basin_deg", "translation": [rows], "rotation": [rows]}}.
std::string convergenceJson(const std::vector<ConvergenceCurve>& curves, const std::string& description);

}  // namespace semantic_edge_vo
