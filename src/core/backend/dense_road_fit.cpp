#include "semantic_edge_vo/backend/dense_road_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Cholesky>

namespace semantic_edge_vo {
namespace {

constexpr int kCoarsestLevel = 3, kFinestLevel = 1;  // level 1 holds thousands of lane pixels; level 0 would cost four times as much
constexpr float kMinGradient = 2.0f;          // gray levels / px: untextured road pixels carry no parallax
constexpr double kHuber = 10.0;               // gray levels
constexpr int kIterations = 12;               // per level
constexpr int kHeightSteps = 41;              // the search over heights, from a third to three times the guess
constexpr double kSearchRange = 3.0;
constexpr int kMinPixels = 300;               // at the finest level, carried into the other image
constexpr double kMinInlierRatio = 0.5;
constexpr double kMaxRelativeSigma = 0.02;    // of the height, from the Gauss-Newton covariance
constexpr double kMaxGain = 1.5;              // brightness change between neighbouring frames: more is a collapsed fit
constexpr double kNormalSigma = 2.0 * M_PI / 180.0;  // the road's normal about the mounting's: pitching, slopes

/// A textured pixel of the lane ahead: its viewing ray (z = 1) and intensity in the reference.
struct RoadPixel {
  Eigen::Vector3d ray;
  double intensity;
};

/// Plane n / height (m: a pixel's inverse depth is m . ray) and the brightness change a, b.
struct PlaneModel {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  double a = 1.0, b = 0.0;
};

using Vector5d = Eigen::Matrix<double, 5, 1>;
using Matrix5d = Eigen::Matrix<double, 5, 5>;

/// Sums over the residuals at one model: Huber cost, counts, and the normal equations when asked.
struct Sums {
  double cost = 0.0, weighted_squares = 0.0, residual_sum = 0.0;
  int residuals = 0, inliers = 0;
  Matrix5d H = Matrix5d::Zero();
  Vector5d g = Vector5d::Zero();
};

double huberCost(double e) {
  const double a = std::abs(e);
  return a <= kHuber ? 0.5 * e * e : kHuber * (a - 0.5 * kHuber);
}

float sample(const cv::Mat& image, double x, double y) { return sampleBilinear(image, static_cast<float>(x), static_cast<float>(y)); }

/// The lane's textured pixels at one pyramid level and their residuals against the other image.
class LevelProblem {
 public:
  LevelProblem(const PyramidLevel& reference, const PyramidLevel& other, const Eigen::Isometry3d& T_other_reference,
               const RoadPlaneFinder& finder)
      : other_(other), R_(T_other_reference.linear()), t_(T_other_reference.translation()) {
    const PinholeCamera& camera = reference.camera;
    for (int y = 2; y < camera.height - 2; ++y)
      for (int x = 2; x < camera.width - 2; ++x) {
        if (reference.gradient.at<float>(y, x) < kMinGradient) continue;
        const Eigen::Vector3d ray((x - camera.cx) / camera.fx, (y - camera.cy) / camera.fy, 1.0);
        if (finder.inLaneAhead(ray)) pixels_.push_back({ray, reference.intensity.at<float>(y, x)});
      }
  }

  int pixels() const { return static_cast<int>(pixels_.size()); }

  /// Residuals (intensity in the other image minus the reference's, brightness-corrected) at `model`;
  /// with `normal`, the Huber-weighted normal equations too.
  Sums evaluate(const PlaneModel& model, bool normal) const {
    Sums sums;
    const PinholeCamera& camera = other_.camera;
    for (const RoadPixel& pixel : pixels_) {
      const double inverse_depth = model.m.dot(pixel.ray);
      if (inverse_depth <= 0.0) continue;
      const Eigen::Vector3d q = R_ * pixel.ray + inverse_depth * t_;  // the point in the other frame, times its inverse depth
      if (q.z() <= 1e-6) continue;
      const double x = camera.fx * q.x() / q.z() + camera.cx, y = camera.fy * q.y() / q.z() + camera.cy;
      if (!camera.contains(x, y, 2.0)) continue;
      const double e = sample(other_.intensity, x, y) - model.a * pixel.intensity - model.b;
      ++sums.residuals;
      sums.residual_sum += e;
      sums.cost += huberCost(e);
      const double w = std::abs(e) <= kHuber ? 1.0 : kHuber / std::abs(e);
      if (std::abs(e) <= kHuber) ++sums.inliers;
      sums.weighted_squares += w * e * e;
      if (!normal) continue;
      const double gx = 0.5 * (sample(other_.intensity, x + 1.0, y) - sample(other_.intensity, x - 1.0, y));
      const double gy = 0.5 * (sample(other_.intensity, x, y + 1.0) - sample(other_.intensity, x, y - 1.0));
      const double iz = 1.0 / q.z();
      // d pixel / d q, then d q / d m = t ray^T
      const Eigen::Vector3d dpixel_dq_x(camera.fx * iz, 0.0, -camera.fx * q.x() * iz * iz);
      const Eigen::Vector3d dpixel_dq_y(0.0, camera.fy * iz, -camera.fy * q.y() * iz * iz);
      const double de_dq_t = (gx * dpixel_dq_x + gy * dpixel_dq_y).dot(t_);
      Vector5d J;
      J << de_dq_t * pixel.ray, -pixel.intensity, -1.0;
      sums.H.noalias() += w * J * J.transpose();
      sums.g.noalias() += w * e * J;
    }
    return sums;
  }

 private:
  const PyramidLevel& other_;
  Eigen::Matrix3d R_;
  Eigen::Vector3d t_;
  std::vector<RoadPixel> pixels_;
};

/// The height (normal fixed at `down`, no gain) whose warp best agrees, at the coarsest level.
double searchHeight(const LevelProblem& problem, const Eigen::Vector3d& down, double height_guess) {
  double best_height = height_guess, best_cost = std::numeric_limits<double>::infinity();
  for (int step = 0; step < kHeightSteps; ++step) {
    const double height = height_guess * std::pow(kSearchRange, 2.0 * step / (kHeightSteps - 1) - 1.0);
    PlaneModel model;
    model.m = down / height;
    const Sums offset = problem.evaluate(model, false);
    if (offset.residuals < problem.pixels() / 2) continue;  // most of the lane leaves the other image
    model.b = offset.residual_sum / offset.residuals;  // the brightness change, as an offset
    const Sums sums = problem.evaluate(model, false);
    const double cost = sums.cost / sums.residuals;
    if (cost < best_cost) {
      best_cost = cost;
      best_height = height;
    }
  }
  return best_height;
}

/// The prior on the plane's normal: the mounting's `down`, sigma kNormalSigma. Its residual is the
/// normal's component across `down` (m's over |m|), weighed against photometric residuals of
/// `spread` (gray levels^2).
void addNormalPrior(const Eigen::Vector3d& down, double spread, const PlaneModel& model, bool normal, Sums* sums) {
  const double weight = spread / (kNormalSigma * kNormalSigma), norm2 = model.m.squaredNorm();
  const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - down * down.transpose();
  sums->cost += 0.5 * weight * (across * model.m).squaredNorm() / norm2;
  if (!normal) return;
  sums->H.topLeftCorner<3, 3>() += weight * across / norm2;  // Jacobian across / |m| near the prior
  sums->g.head<3>() += weight * across * model.m / norm2;
}

/// Gauss-Newton with step halving at one level, with the normal's prior; returns the last sums.
Sums solveLevel(const LevelProblem& problem, const Eigen::Vector3d& down, bool free_normal, PlaneModel* model) {
  Sums sums = problem.evaluate(*model, true);
  // Held normal: the prior a million times as strong.
  const double spread = std::max(1.0, sums.weighted_squares / std::max(1, sums.residuals)) * (free_normal ? 1.0 : 1e6);
  const auto total = [&](const PlaneModel& at, bool normal) {
    Sums result = problem.evaluate(at, normal);
    addNormalPrior(down, spread, at, normal, &result);
    return result;
  };
  sums = total(*model, true);
  for (int iteration = 0; iteration < kIterations && sums.residuals > 5; ++iteration) {
    Matrix5d H = sums.H;
    H.diagonal() *= 1.0 + 1e-6;
    const Vector5d delta = H.ldlt().solve(-sums.g);
    if (!delta.allFinite()) break;
    bool accepted = false;
    for (double step = 1.0; step > 0.05 && !accepted; step *= 0.5) {
      PlaneModel trial = *model;
      trial.m += step * delta.head<3>();
      trial.a += step * delta(3);
      trial.b += step * delta(4);
      const Sums trial_sums = total(trial, false);
      if (trial_sums.residuals < sums.residuals * 0.9 || trial_sums.cost / trial_sums.residuals >= sums.cost / sums.residuals) continue;
      *model = trial;
      accepted = true;
    }
    if (!accepted) break;
    sums = total(*model, true);
    if (delta.head<3>().norm() < 1e-4 * model->m.norm()) break;
  }
  return sums;
}

}  // namespace

RoadFit DenseRoadFitter::fit(const ImagePyramid& reference, const ImagePyramid& other, const Eigen::Isometry3d& T_other_reference,
                             double height_guess) const {
  RoadFit fit;
  const int coarsest = std::min({kCoarsestLevel, reference.levels() - 1, other.levels() - 1});
  if (coarsest < kFinestLevel || !(height_guess > 0.0) || T_other_reference.translation().norm() < 1e-9 * height_guess) return fit;
  const Eigen::Vector3d down = options_.expectedDown();
  PlaneModel model;
  Sums sums;
  for (int level = coarsest; level >= kFinestLevel; --level) {
    const LevelProblem problem(reference.level(level), other.level(level), T_other_reference, finder_);
    if (level == coarsest) model.m = down / searchHeight(problem, down, height_guess);
    sums = solveLevel(problem, down, level == kFinestLevel, &model);
    fit.evidence = problem.pixels();
  }
  if (sums.residuals < kMinPixels || sums.inliers < kMinInlierRatio * sums.residuals || !(model.m.norm() > 0.0)) return fit;
  fit.down = model.m.normalized();
  fit.height = 1.0 / model.m.norm();
  const double cos_max_deviation = std::cos(options_.max_normal_deviation_deg * M_PI / 180.0);
  const Matrix5d covariance = sums.weighted_squares / std::max(1, sums.residuals - 5) * sums.H.inverse();
  const double relative_sigma = std::sqrt(std::max(0.0, fit.down.dot(covariance.topLeftCorner<3, 3>() * fit.down))) * fit.height;
  fit.found = fit.down.dot(down) >= cos_max_deviation && relative_sigma <= kMaxRelativeSigma && model.a >= 1.0 / kMaxGain &&
              model.a <= kMaxGain;
  return fit;
}

}  // namespace semantic_edge_vo
