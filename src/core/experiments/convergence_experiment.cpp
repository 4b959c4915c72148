#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/experiments/convergence_experiment.h"

#include "semantic_edge_vo/support/json_text.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace semantic_edge_vo {
namespace {


Eigen::Vector3d randomDirection(std::mt19937_64* rng) {
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(gauss(*rng), gauss(*rng), gauss(*rng));
  while (d.norm() < 1e-6);
  return d.normalized();
}

/// The perturbation of trial `trial` at `amount`: a translation (metres) or a rotation (degrees)
/// about a random axis through the reference camera's centre, applied before the true pose.
Eigen::Isometry3d perturbation(bool rotate, double amount, std::mt19937_64* rng) {
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d direction = randomDirection(rng);
  if (rotate) delta.linear() = Eigen::AngleAxisd(amount * M_PI / 180.0, direction).toRotationMatrix();
  else delta.translation() = amount * direction;
  return delta;
}

std::vector<ConvergenceRow> runTable(const std::vector<RegistrationProblem>& problems,
                                     const std::vector<NearestNeighborFieldData>& fields, bool rotate,
                                     const std::vector<double>& amounts, const ConvergenceOptions& options) {
  std::vector<ConvergenceRow> rows;
  std::mt19937_64 rng(options.seed + (rotate ? 7919u : 0u));
  for (double amount : amounts) {
    std::vector<double> errors_m, errors_deg;
    int successes = 0;
    for (std::size_t p = 0; p < problems.size(); ++p) {
      const RegistrationProblem& problem = problems[p];
      const EdgeRegistration registration(problem.camera, options.registration);
      const NearestNeighborFieldView field = fields[p].view();
      for (int t = 0; t < options.trials; ++t) {
        const Eigen::Isometry3d start = problem.T_target_ref * perturbation(rotate, amount, &rng);
        const EdgeRegistrationResult result = registration.align(problem.reference, field, start);
        // Error of the estimated reference camera pose seen from the target: T_est^-1 * T_true.
        const Eigen::Isometry3d error = result.T_target_ref.inverse() * problem.T_target_ref;
        const double error_m = error.translation().norm();
        const double error_deg = Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI;
        errors_m.push_back(error_m);
        errors_deg.push_back(error_deg);
        successes += error_m < options.success_translation_m && error_deg < options.success_rotation_deg;
      }
    }
    ConvergenceRow row;
    row.displacement = amount;
    row.trials = static_cast<int>(errors_m.size());
    row.median_error_m = median(errors_m);
    row.median_error_deg = median(errors_deg);
    row.success_rate = row.trials ? static_cast<double>(successes) / row.trials : 0.0;
    rows.push_back(row);
  }
  return rows;
}

void appendRows(std::ostringstream* json, const std::vector<ConvergenceRow>& rows) {
  *json << "[";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ConvergenceRow& r = rows[i];
    *json << (i ? ", " : "") << "{\"displacement\": " << r.displacement << ", \"median_error_m\": " << r.median_error_m
          << ", \"median_error_deg\": " << r.median_error_deg << ", \"success_rate\": " << r.success_rate
          << ", \"trials\": " << r.trials << "}";
  }
  *json << "]";
}

}  // namespace

std::string ConvergenceOptions::validate() const {
  if (displacements_m.empty() && rotations_deg.empty()) return "no displacement and no rotation to test";
  if (trials < 1) return "trials must be >= 1";
  if (!(success_translation_m > 0.0 && success_rotation_deg > 0.0)) return "success thresholds must be > 0";
  for (double d : displacements_m)
    if (d < 0.0) return "displacements must be >= 0 m";
  for (double d : rotations_deg)
    if (d < 0.0) return "rotations must be >= 0 deg";
  if (!std::is_sorted(displacements_m.begin(), displacements_m.end()) || !std::is_sorted(rotations_deg.begin(), rotations_deg.end()))
    return "displacements and rotations must be increasing";
  const std::string registration_error = registration.validate();
  if (!registration_error.empty()) return "registration: " + registration_error;
  return field.validate();
}

double basinOf(const std::vector<ConvergenceRow>& rows) {
  double basin = 0.0;
  for (const ConvergenceRow& row : rows) {
    if (row.success_rate < 0.5) break;
    basin = row.displacement;
  }
  return basin;
}

ConvergenceCurve runConvergence(const std::vector<RegistrationProblem>& problems, FieldKind kind,
                                const ConvergenceOptions& options) {
  ConvergenceOptions run = options;
  run.field.kind = kind;
  run.field.pyramid_levels = options.registration.level + 1;
  std::vector<NearestNeighborFieldData> fields;
  for (const RegistrationProblem& p : problems)
    fields.push_back(buildNearestNeighborField(p.target_edges.view(), p.camera.width, p.camera.height, p.class_names, run.field));
  ConvergenceCurve curve;
  curve.kind = kind;
  curve.translation = runTable(problems, fields, false, options.displacements_m, run);
  curve.rotation = runTable(problems, fields, true, options.rotations_deg, run);
  curve.basin_m = basinOf(curve.translation);
  curve.basin_deg = basinOf(curve.rotation);
  return curve;
}

std::string convergenceJson(const std::vector<ConvergenceCurve>& curves, const std::string& description) {
  std::ostringstream json;
  json.precision(6);
  json << "{\n  \"description\": " << jsonString(description);
  for (const ConvergenceCurve& c : curves) {
    json << ",\n  \"" << toString(c.kind) << "\": {\"basin_m\": " << c.basin_m << ", \"basin_deg\": " << c.basin_deg
         << ",\n    \"translation\": ";
    appendRows(&json, c.translation);
    json << ",\n    \"rotation\": ";
    appendRows(&json, c.rotation);
    json << "}";
  }
  json << "\n}\n";
  return json.str();
}

}  // namespace semantic_edge_vo
