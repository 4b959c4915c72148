#include "semantic_edge_vo/eval/covariance_consistency.h"

#include <algorithm>
#include <map>

#include <Eigen/Cholesky>

#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {
namespace {

/// Chi-square medians and 95th percentiles for 3 and 6 degrees of freedom.
struct ChiSquare {
  double median, bound_95;
};
ChiSquare chiSquare(int dof) { return dof == 3 ? ChiSquare{2.366, 7.815} : ChiSquare{5.348, 12.592}; }

NeesStatistics statisticsOf(std::vector<double> values, int dof) {
  NeesStatistics s;
  s.dof = dof;
  s.expected_median = chiSquare(dof).median;
  s.bound_95 = chiSquare(dof).bound_95;
  s.count = values.size();
  if (values.empty()) return s;
  double sum = 0.0;
  std::size_t above = 0;
  for (double v : values) {
    sum += v;
    above += v > s.bound_95;
  }
  s.mean = sum / static_cast<double>(values.size());
  s.above_95 = static_cast<double>(above) / static_cast<double>(values.size());
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2), values.end());
  s.median = values[values.size() / 2];
  return s;
}

/// x^T C^-1 x by a Cholesky factorisation; -1 when C is not positive definite.
template <int N>
double mahalanobis2(const Eigen::Matrix<double, N, 1>& x, const Eigen::Matrix<double, N, N>& C) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(C);
  if (llt.info() != Eigen::Success) return -1.0;
  return x.dot(llt.solve(x));
}

}  // namespace

std::string covarianceConsistency(const PosePairs& pairs, const std::vector<TrackedMotion>& motions, double sim3_scale,
                                  CovarianceConsistency* result) {
  std::map<std::size_t, std::size_t> pair_of_frame;
  for (std::size_t i = 0; i < pairs.gt.size(); ++i) pair_of_frame[pairs.groundTruthFrame(i)] = i;
  const bool metric = std::any_of(motions.begin(), motions.end(), [](const TrackedMotion& m) { return m.in_metres; });
  CovarianceConsistency out;
  out.in_metres = metric;
  out.translation_scale = metric ? 1.0 : sim3_scale;
  std::vector<double> pose, rotation, translation;
  for (const TrackedMotion& motion : motions) {
    if (metric && !motion.in_metres) continue;
    const auto frame = pair_of_frame.find(motion.frame), keyframe = pair_of_frame.find(motion.keyframe_frame);
    if (frame == pair_of_frame.end() || keyframe == pair_of_frame.end()) {
      ++out.skipped;
      continue;
    }
    const Eigen::Isometry3d T_true =
        orthonormalized(pairs.gt[frame->second].inverse() * pairs.gt[keyframe->second]);
    Eigen::Isometry3d T_est = motion.T_cam_kf;
    T_est.translation() *= out.translation_scale;
    const Vector6d xi = se3Log(T_est * T_true.inverse());
    // The covariance's translation rows and columns in the same units as xi's.
    Vector6d to_metres;
    to_metres << Eigen::Vector3d::Constant(out.translation_scale), Eigen::Vector3d::Ones();
    const Matrix6d covariance = to_metres.asDiagonal() * motion.covariance * to_metres.asDiagonal();
    const double whole = mahalanobis2<6>(xi, covariance);
    const double turn = mahalanobis2<3>(xi.tail<3>(), covariance.bottomRightCorner<3, 3>());
    const double shift = mahalanobis2<3>(xi.head<3>(), covariance.topLeftCorner<3, 3>());
    if (whole < 0.0 || turn < 0.0 || shift < 0.0) {
      ++out.skipped;
      continue;
    }
    pose.push_back(whole);
    rotation.push_back(turn);
    translation.push_back(shift);
  }
  if (pose.empty()) return "no tracked motion has ground truth for its frame and its keyframe";
  out.pose = statisticsOf(pose, 6);
  out.rotation = statisticsOf(rotation, 3);
  out.translation = statisticsOf(translation, 3);
  *result = out;
  return "";
}

}  // namespace semantic_edge_vo
