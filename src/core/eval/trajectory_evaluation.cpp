#include "semantic_edge_vo/eval/trajectory_evaluation.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>  // Eigen::umeyama

namespace semantic_edge_vo {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

std::string checkPairs(std::size_t gt, std::size_t est, std::size_t minimum) {
  std::ostringstream error;
  if (gt != est) error << "the trajectories have " << gt << " and " << est << " poses; corresponding poses expected";
  else if (gt < minimum) error << "needs at least " << minimum << " pose pairs, has " << gt;
  return error.str();
}

Eigen::Isometry3d relativeMotion(const Eigen::Isometry3d& from, const Eigen::Isometry3d& to, double scale) {
  Eigen::Isometry3d motion = from.inverse() * to;
  motion.translation() *= scale;
  return motion;
}

/// Sum of squared position differences after `alignment`, appending each difference to `errors`.
double alignedSquaredErrors(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                            std::size_t first, std::size_t count, const SimilarityTransform& alignment,
                            std::vector<double>* errors) {
  double sum = 0.0;
  for (std::size_t i = first; i < first + count; ++i) {
    const double error = (gt[i] - alignment * est[i]).norm();
    sum += error * error;
    errors->push_back(error);
  }
  return sum;
}

std::vector<Eigen::Vector3d> slice(const std::vector<Eigen::Vector3d>& points, std::size_t first, std::size_t count) {
  return {points.begin() + static_cast<std::ptrdiff_t>(first),
          points.begin() + static_cast<std::ptrdiff_t>(first + count)};
}

}  // namespace

std::string alignUmeyama(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                         bool with_scale, SimilarityTransform* transform) {
  const std::string count_error = checkPairs(source.size(), target.size(), 3);
  if (!count_error.empty()) return "alignment " + count_error;
  const auto n = static_cast<Eigen::Index>(source.size());
  const Eigen::Map<const Eigen::Matrix3Xd> src(source.front().data(), 3, n), dst(target.front().data(), 3, n);
  if ((src.colwise() - src.rowwise().mean()).squaredNorm() <= 0.0)
    return "alignment needs estimated positions that are not all equal";
  const Eigen::Matrix4d T = Eigen::umeyama(src, dst, with_scale);
  const Eigen::Matrix3d scaled_rotation = T.topLeftCorner<3, 3>();
  transform->scale = std::cbrt(scaled_rotation.determinant());
  transform->rotation = scaled_rotation / transform->scale;
  transform->translation = T.topRightCorner<3, 1>();
  return "";
}

ErrorStatistics errorStatistics(std::vector<double> errors) {
  ErrorStatistics statistics;
  statistics.count = errors.size();
  if (errors.empty()) return statistics;
  const double n = static_cast<double>(errors.size());
  double squares = 0.0;
  for (double e : errors) squares += e * e;
  statistics.rmse = std::sqrt(squares / n);
  statistics.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / n;
  statistics.max = *std::max_element(errors.begin(), errors.end());
  const auto middle = errors.begin() + static_cast<std::ptrdiff_t>(errors.size() / 2);
  std::nth_element(errors.begin(), middle, errors.end());
  statistics.median = *middle;
  if (errors.size() % 2 == 0) statistics.median = 0.5 * (statistics.median + *std::max_element(errors.begin(), middle));
  return statistics;
}

double rotationAngle(const Eigen::Matrix3d& rotation) {
  const Eigen::Vector3d skew(rotation(2, 1) - rotation(1, 2), rotation(0, 2) - rotation(2, 0),
                             rotation(1, 0) - rotation(0, 1));
  return std::atan2(0.5 * skew.norm(), 0.5 * (rotation.trace() - 1.0));
}

std::string absoluteTrajectoryError(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                                    bool with_scale, AteResult* result) {
  AteResult ate;
  const std::string error = alignUmeyama(est, gt, with_scale, &ate.alignment);
  if (!error.empty()) return error;
  std::vector<double> errors;
  alignedSquaredErrors(gt, est, 0, gt.size(), ate.alignment, &errors);
  ate.error_m = errorStatistics(std::move(errors));
  *result = ate;
  return "";
}

std::string AteProtocolOptions::validate() const {
  std::ostringstream error;
  if (discard_first_poses < 0) error << "discard_first_poses must be >= 0 (got " << discard_first_poses << ")";
  else if (segment_frames < 3) error << "segment_frames must be >= 3 (got " << segment_frames << ")";
  return error.str();
}

std::string segmentedAte(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                         const AteProtocolOptions& options, SegmentedAteResult* result) {
  const std::string options_error = options.validate();
  if (!options_error.empty()) return options_error;
  const auto discard = static_cast<std::size_t>(options.discard_first_poses);
  const std::string count_error = checkPairs(gt.size(), est.size(), discard + 3);
  if (!count_error.empty()) return "after discarding " + std::to_string(discard) + " poses, " + count_error;

  const auto length = static_cast<std::size_t>(options.segment_frames);
  SegmentedAteResult ate;
  std::vector<double> errors;
  for (std::size_t first = discard; first < gt.size();) {
    std::size_t count = std::min(length, gt.size() - first);
    const std::size_t rest = gt.size() - first - count;
    if (rest > 0 && rest < std::max<std::size_t>(3, length / 2)) count += rest;  // a short remainder joins in
    SimilarityTransform alignment;
    const std::string error = alignUmeyama(slice(est, first, count), slice(gt, first, count), true, &alignment);
    if (!error.empty()) return "segment at pose " + std::to_string(first) + ": " + error;
    const double squares = alignedSquaredErrors(gt, est, first, count, alignment, &errors);
    ate.segments.push_back({first, count, alignment.scale, std::sqrt(squares / static_cast<double>(count))});
    first += count;
  }
  ate.error_m = errorStatistics(std::move(errors));
  *result = std::move(ate);
  return "";
}

double travelScale(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, std::size_t first, std::size_t step) {
  return travelScale(gt, est, first, std::min(gt.size(), est.size()), step);
}

double travelScale(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, std::size_t first, std::size_t last,
                   std::size_t step) {
  double true_travel = 0.0, travel = 0.0;
  step = std::max<std::size_t>(step, 1);
  const std::size_t end = std::min({last, gt.size() - 1, est.size() - 1});
  for (std::size_t i = first; i < end && !gt.empty() && !est.empty(); i += step) {
    const std::size_t next = std::min(i + step, end);
    true_travel += (gt[next] - gt[i]).norm();
    travel += (est[next] - est[i]).norm();
  }
  return true_travel > 0.0 ? travel / true_travel : 0.0;
}

double scaleChange(double a, double b) { return std::max(a / b, b / a) - 1.0; }

ScaleAlongPath scaleAlongPath(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, double stretch_m,
                              std::size_t step) {
  ScaleAlongPath result;
  std::vector<ScaleStretch>& stretches = result.stretches;
  const std::size_t pairs = std::min(gt.size(), est.size());
  if (pairs < 2 || !(stretch_m > 0.0)) return result;
  ScaleStretch current;
  double along = 0.0;
  for (std::size_t i = 1; i < pairs; ++i) {
    along += (gt[i] - gt[i - 1]).norm();
    if (along - current.from_m < stretch_m && i + 1 < pairs) continue;
    current.last = i;
    current.to_m = along;
    const bool short_tail = i + 1 == pairs && current.to_m - current.from_m < 0.5 * stretch_m;
    if (short_tail && stretches.empty()) break;  // too little travel for one stretch
    if (short_tail) {
      current.first = stretches.back().first;
      current.from_m = stretches.back().from_m;
      stretches.pop_back();
    }
    current.scale = travelScale(gt, est, current.first, current.last, step);
    stretches.push_back(current);
    current = ScaleStretch();
    current.first = i;
    current.from_m = along;
  }
  for (std::size_t k = 0; k < stretches.size(); ++k) {
    if (stretches[k].scale < stretches[result.lowest].scale) result.lowest = k;
    if (stretches[k].scale > stretches[result.highest].scale) result.highest = k;
    if (k > 0 && stretches[k - 1].scale > 0.0 && stretches[k].scale > 0.0)
      result.largest_change = std::max(result.largest_change, scaleChange(stretches[k].scale, stretches[k - 1].scale));
  }
  return result;
}

std::string chainedSegmentAte(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                              const SegmentedAteResult& segments, AteResult* result) {
  if (segments.segments.empty()) return "no segments";
  const std::size_t first = segments.segments.front().first;
  std::vector<Eigen::Vector3d> chained{est[first]};
  for (const AteSegment& segment : segments.segments)
    for (std::size_t i = std::max(segment.first, first + 1); i < segment.first + segment.count; ++i)
      chained.push_back(chained.back() + segment.scale * (est[i] - est[i - 1]));
  const std::vector<Eigen::Vector3d> truth = slice(gt, first, chained.size());
  AteResult ate;
  const std::string error = alignUmeyama(chained, truth, false, &ate.alignment);
  if (!error.empty()) return error;
  std::vector<double> errors;
  for (std::size_t i = 0; i < chained.size(); ++i) errors.push_back((ate.alignment * chained[i] - truth[i]).norm());
  ate.error_m = errorStatistics(std::move(errors));
  *result = std::move(ate);
  return "";
}

std::string relativePoseError(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                              int delta_frames, double est_scale, RpeResult* result) {
  if (delta_frames < 1) return "the RPE frame delta must be >= 1 (got " + std::to_string(delta_frames) + ")";
  const auto delta = static_cast<std::size_t>(delta_frames);
  const std::string count_error = checkPairs(gt.size(), est.size(), delta + 1);
  if (!count_error.empty()) return "RPE over " + std::to_string(delta) + " frames " + count_error;
  std::vector<double> translation, rotation;
  for (std::size_t i = 0; i + delta < gt.size(); ++i) {
    const Eigen::Isometry3d error =
        relativeMotion(gt[i], gt[i + delta], 1.0).inverse() * relativeMotion(est[i], est[i + delta], est_scale);
    translation.push_back(error.translation().norm());
    rotation.push_back(rotationAngle(error.linear()) * kDegreesPerRadian);
  }
  result->delta_frames = delta_frames;
  result->translation_m = errorStatistics(std::move(translation));
  result->rotation_deg = errorStatistics(std::move(rotation));
  return "";
}

std::string KittiDriftOptions::validate() const {
  std::ostringstream error;
  if (segment_lengths_m.empty()) error << "segment_lengths_m must not be empty";
  else if (*std::min_element(segment_lengths_m.begin(), segment_lengths_m.end()) <= 0.0)
    error << "segment_lengths_m must be > 0";
  else if (step_frames < 1) error << "step_frames must be >= 1 (got " << step_frames << ")";
  return error.str();
}

std::string kittiDrift(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                       double est_scale, const KittiDriftOptions& options, KittiDriftResult* result) {
  const std::string options_error = options.validate();
  if (!options_error.empty()) return options_error;
  const std::string count_error = checkPairs(gt.size(), est.size(), 2);
  if (!count_error.empty()) return "KITTI drift " + count_error;
  std::vector<double> distance(gt.size(), 0.0);  // ground-truth path distance from frame 0
  for (std::size_t i = 1; i < gt.size(); ++i)
    distance[i] = distance[i - 1] + (gt[i].translation() - gt[i - 1].translation()).norm();

  KittiDriftResult drift;
  double translation_sum = 0.0, rotation_sum = 0.0;
  for (double length : options.segment_lengths_m) {
    KittiDriftLength per_length{length, 0, 0.0, 0.0};
    std::size_t last = 0;
    for (std::size_t first = 0; first < gt.size(); first += static_cast<std::size_t>(options.step_frames)) {
      // The devkit's lastFrameFromSegmentLength: first frame farther than `length` along the path.
      last = std::max(last, first);
      while (last < gt.size() && distance[last] <= distance[first] + length) ++last;
      if (last == gt.size()) break;
      const Eigen::Isometry3d error =
          relativeMotion(est[first], est[last], est_scale).inverse() * relativeMotion(gt[first], gt[last], 1.0);
      const double translation = error.translation().norm() / length;
      const double rotation = rotationAngle(error.linear()) / length;
      ++per_length.count;
      per_length.translation_percent += translation;
      per_length.rotation_deg_per_100m += rotation;
      translation_sum += translation;
      rotation_sum += rotation;
    }
    if (per_length.count == 0) continue;
    drift.count += per_length.count;
    const double n = static_cast<double>(per_length.count);
    per_length.translation_percent *= 100.0 / n;
    per_length.rotation_deg_per_100m *= 100.0 * kDegreesPerRadian / n;
    drift.lengths.push_back(per_length);
  }
  if (drift.count == 0) {
    std::ostringstream error;
    error << "the ground truth is " << distance.back() << " m long, shorter than the shortest KITTI segment ("
          << *std::min_element(options.segment_lengths_m.begin(), options.segment_lengths_m.end()) << " m)";
    return error.str();
  }
  drift.translation_percent = 100.0 * translation_sum / static_cast<double>(drift.count);
  drift.rotation_deg_per_100m = 100.0 * kDegreesPerRadian * rotation_sum / static_cast<double>(drift.count);
  *result = std::move(drift);
  return "";
}

std::string frameToFrameErrors(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                               double min_gt_translation_m, FrameToFrameErrors* result) {
  const std::string count_error = checkPairs(gt.size(), est.size(), 2);
  if (!count_error.empty()) return "frame-to-frame errors " + count_error;
  FrameToFrameErrors errors;
  double rotation_sum = 0.0, direction_sum = 0.0;
  for (std::size_t i = 0; i + 1 < gt.size(); ++i) {
    const Eigen::Isometry3d gt_motion = relativeMotion(gt[i], gt[i + 1], 1.0);
    const Eigen::Isometry3d est_motion = relativeMotion(est[i], est[i + 1], 1.0);
    rotation_sum += rotationAngle(gt_motion.linear().transpose() * est_motion.linear());
    ++errors.motions;
    const Eigen::Vector3d& a = gt_motion.translation();
    const Eigen::Vector3d& b = est_motion.translation();
    if (a.norm() < min_gt_translation_m || b.norm() <= 0.0) continue;
    direction_sum += std::atan2(a.cross(b).norm(), a.dot(b));
    ++errors.direction_motions;
  }
  errors.mean_rotation_error_deg = kDegreesPerRadian * rotation_sum / static_cast<double>(errors.motions);
  if (errors.direction_motions > 0)
    errors.mean_direction_error_deg = kDegreesPerRadian * direction_sum / static_cast<double>(errors.direction_motions);
  *result = errors;
  return "";
}

std::vector<Eigen::Vector3d> positionsOf(const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(poses.size());
  for (const auto& pose : poses) positions.push_back(pose.translation());
  return positions;
}

double pathLength(const std::vector<Eigen::Vector3d>& positions) {
  double length = 0.0;
  for (std::size_t i = 1; i < positions.size(); ++i) length += (positions[i] - positions[i - 1]).norm();
  return length;
}

ErrorStatistics straightLineErrors(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::size_t>& frames) {
  const std::size_t n = std::min(positions.size(), frames.size());
  if (n < 2) return ErrorStatistics();
  double mean_k = 0.0;
  Eigen::Vector3d mean_p = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    mean_k += static_cast<double>(frames[i]) / static_cast<double>(n);
    mean_p += positions[i] / static_cast<double>(n);
  }
  double spread = 0.0;
  Eigen::Vector3d covariance = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const double dk = static_cast<double>(frames[i]) - mean_k;
    spread += dk * dk;
    covariance += dk * (positions[i] - mean_p);
  }
  if (!(spread > 0.0)) return ErrorStatistics();
  const Eigen::Vector3d velocity = covariance / spread;
  std::vector<double> errors;
  for (std::size_t i = 0; i < n; ++i)
    errors.push_back((positions[i] - mean_p - (static_cast<double>(frames[i]) - mean_k) * velocity).norm());
  return errorStatistics(errors);
}

std::string keyframeScaleChanges(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                                 const std::vector<std::size_t>& keyframes, double min_gt_travel_m, KeyframeScaleChanges* result) {
  KeyframeScaleChanges changes;
  double previous_scale = 0.0;
  for (std::size_t k = 1; k < keyframes.size(); ++k) {
    const std::size_t from = keyframes[k - 1], to = keyframes[k];
    if (to <= from || to >= gt.size() || to >= est.size()) return "keyframe pair indices must increase within the pairs";
    const double travelled = (gt[to] - gt[from]).norm();
    if (travelled < min_gt_travel_m) continue;
    const double scale = (est[to] - est[from]).norm() / travelled;
    ++changes.intervals;
    if (previous_scale > 0.0 && scale > 0.0) {
      const double change = scaleChange(scale, previous_scale);
      if (change > changes.largest_change) {
        changes.largest_change = change;
        changes.at_pair = from;
      }
    }
    previous_scale = scale;
  }
  if (changes.intervals < 2) return "fewer than two keyframe intervals in which the camera travelled";
  *result = changes;
  return "";
}

}  // namespace semantic_edge_vo
