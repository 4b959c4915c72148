#include "semantic_edge_vo/backend/two_view_geometry.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

bool estimateTwoViewMotion(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second,
                           const PinholeCamera& camera, double threshold, int min_inliers, TwoViewMotion* motion) {
  if (static_cast<int>(first.size()) < std::max(min_inliers, 5)) return false;
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Mat inliers;
  const cv::Mat E = cv::findEssentialMat(first, second, K, cv::RANSAC, 0.999, threshold, inliers);
  if (E.rows != 3 || E.cols != 3) return false;  // degenerate (several solutions stacked, or none)
  cv::Mat R, t;
  motion->inlier_count = cv::recoverPose(E, first, second, K, R, t, inliers);
  if (motion->inlier_count < min_inliers) return false;
  cv::cv2eigen(R, motion->R_second_first);
  cv::cv2eigen(t, motion->t_second_first);
  motion->inliers.assign(inliers.begin<std::uint8_t>(), inliers.end<std::uint8_t>());
  return true;
}

namespace {

/// Unit translation of the vehicle motion with rotation R_second_first, driving forward: the second
/// centre lies along the chord in the first view, so t = -R c (reversing: the opposite).
Eigen::Vector3d vehicleTranslation(const Eigen::Matrix3d& R_second_first, const ForwardMotionOptions& forward) {
  return -(R_second_first * forward.chord(R_second_first.transpose()));
}

/// Signed Sampson distance of a correspondence of normalised image points, in pixels of focal length f.
double sampson(const Eigen::Matrix3d& E, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2, double f) {
  const Eigen::Vector3d Ex1 = E * x1, Etx2 = E.transpose() * x2;
  const double norm = std::sqrt(Ex1.head<2>().squaredNorm() + Etx2.head<2>().squaredNorm());
  return norm > 0.0 ? f * x2.dot(Ex1) / norm : 0.0;
}

/// Is the point seen along x1 and x2 (x2 d2 = R x1 d1 + t, least squares) in front of both views?
bool inFront(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  Eigen::Matrix<double, 3, 2> A;
  A << R * x1, -x2;
  const Eigen::Vector2d depths = (A.transpose() * A).ldlt().solve(-A.transpose() * t);
  return depths.allFinite() && depths[0] > 0.0 && depths[1] > 0.0;
}

}  // namespace

bool estimateVehicleMotion(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second,
                           const PinholeCamera& camera, const ForwardMotionOptions& forward, double threshold, int min_inliers,
                           const Eigen::Matrix3d& R_second_first_guess, TwoViewMotion* motion) {
  const std::size_t n = first.size();
  if (static_cast<int>(n) < std::max(min_inliers, 3)) return false;
  std::vector<Eigen::Vector3d> x1(n), x2(n);
  for (std::size_t i = 0; i < n; ++i) {
    x1[i] = camera.backProject(first[i].x, first[i].y, 1.0);
    x2[i] = camera.backProject(second[i].x, second[i].y, 1.0);
  }
  const double f = camera.fx;
  // Sampson distances do not change with the sign of t: the fit holds for forward and reverse travel alike.
  const auto essential = [&](const Eigen::Matrix3d& R) -> Eigen::Matrix3d { return skew(vehicleTranslation(R, forward)) * R; };
  const auto cost = [&](const Eigen::Matrix3d& E) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += huberCost(sampson(E, x1[i], x2[i], f), threshold);
    return sum;
  };
  Eigen::Matrix3d R = R_second_first_guess;
  double current_cost = cost(essential(R));
  // Three parameters and a few hundred correspondences: central differences of a left rotation
  // perturbation (through the chord's half turn) cost less than a millisecond.
  constexpr double kStep = 1e-6;  // rad
  constexpr int kMaxIterations = 20;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    const Eigen::Matrix3d E = essential(R);
    Eigen::Matrix3d E_plus[3], E_minus[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d delta = kStep * Eigen::Vector3d::Unit(k);
      E_plus[k] = essential(so3Exp(delta) * R);
      E_minus[k] = essential(so3Exp(-delta) * R);
    }
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const double r = sampson(E, x1[i], x2[i], f);
      Eigen::Vector3d J;
      for (int k = 0; k < 3; ++k) J[k] = (sampson(E_plus[k], x1[i], x2[i], f) - sampson(E_minus[k], x1[i], x2[i], f)) / (2 * kStep);
      const double weight = huberWeight(r, threshold);
      H += weight * J * J.transpose();
      b += weight * r * J;
    }
    const Eigen::Vector3d step = -H.ldlt().solve(b);
    if (!step.allFinite()) return false;
    const Eigen::Matrix3d candidate = so3Exp(step) * R;
    const double candidate_cost = cost(essential(candidate));
    if (!(candidate_cost < current_cost)) break;  // converged, or a step that would not help
    R = candidate;
    current_cost = candidate_cost;
    if (step.norm() < 1e-9) break;
  }
  // Forward or reverse: the sign that puts more of the agreeing correspondences in front of both
  // views. They stay inliers either way: a distant corner's depth sign is noise, and traffic faster
  // than the car lies "behind" while agreeing with the direction.
  const Eigen::Matrix3d E = essential(R);
  const Eigen::Vector3d t = vehicleTranslation(R, forward);
  motion->inliers.assign(n, 0);
  motion->inlier_count = 0;
  int ahead = 0, behind = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(sampson(E, x1[i], x2[i], f)) > threshold) continue;
    motion->inliers[i] = 1;
    ++motion->inlier_count;
    if (inFront(R, t, x1[i], x2[i])) ++ahead;
    else if (inFront(R, -t, x1[i], x2[i])) ++behind;
  }
  motion->R_second_first = R;
  motion->t_second_first = behind > ahead ? Eigen::Vector3d(-t) : t;
  return motion->inlier_count >= min_inliers;
}

}  // namespace semantic_edge_vo
