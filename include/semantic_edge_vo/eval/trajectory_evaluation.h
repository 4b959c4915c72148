#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace semantic_edge_vo {

// Trajectory metrics on corresponding poses: gt[i] <-> est[i], both T_world_cam (camera-to-world,
// metres), each in its own world frame and, for the estimate, its own scale. Functions that can fail
// return an empty string on success, otherwise why the metric is not available (outputs unchanged).

/// x -> scale * rotation * x + translation.
struct SimilarityTransform {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const { return scale * (rotation * point) + translation; }
};

/// Least-squares similarity (with_scale) or rigid motion mapping `source` onto `target` (Umeyama 1991,
/// through Eigen::umeyama). Needs >= 3 corresponding points, not all equal.
std::string alignUmeyama(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target,
                         bool with_scale, SimilarityTransform* transform);

/// Summary of non-negative errors (metres or degrees, as the caller says).
struct ErrorStatistics {
  std::size_t count = 0;
  double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;
};
ErrorStatistics errorStatistics(std::vector<double> errors);

/// Rotation angle of a (near-)rotation matrix, radians in [0, pi]: atan2 of the skew and the trace
/// parts, well conditioned at small angles and blind to the symmetric error of R^T R for a slightly
/// non-orthonormal R (KITTI ground truth is orthonormal to about 1e-7 only).
double rotationAngle(const Eigen::Matrix3d& rotation);

/// Absolute trajectory error: RMSE etc. of camera position differences after one Umeyama alignment
/// of the whole estimate (Sim(3) with_scale, SE(3) otherwise).
struct AteResult {
  ErrorStatistics error_m;
  SimilarityTransform alignment;  ///< estimate world -> ground-truth world
};
std::string absoluteTrajectoryError(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                                    bool with_scale, AteResult* result);

/// The paper's ATE protocol (no loop closure, "scale recovered from ground truth every 200 frames",
/// first ten poses discarded).
struct AteProtocolOptions {
  int discard_first_poses = 10;  ///< pairs dropped at the start
  int segment_frames = 200;      ///< frames per independently Sim(3)-aligned segment

  std::string validate() const;
};
struct AteSegment {
  std::size_t first = 0, count = 0;  ///< pair index of the segment's first pose, poses in it
  double scale = 1.0;                ///< Sim(3) scale that maps the estimate onto the ground truth
  double rmse_m = 0.0;
};
struct SegmentedAteResult {
  ErrorStatistics error_m;  ///< over all poses of all segments
  std::vector<AteSegment> segments;
};
/// Drops the first poses, cuts the rest into consecutive segments of `segment_frames` poses (a
/// remainder shorter than half a segment, or than 3 poses, joins the segment before it), aligns each segment with its
/// own Umeyama Sim(3) and takes the statistics of all position differences together.
std::string segmentedAte(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                         const AteProtocolOptions& options, SegmentedAteResult* result);

/// The paper's protocol as it states it: after the discarded poses, the estimate's motion in each
/// segment of `segments` is multiplied by that segment's ground-truth (Sim(3)) scale, the motions are
/// chained from the first kept pose into one trajectory, and that is aligned once (SE(3)).
std::string chainedSegmentAte(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                              const SegmentedAteResult& segments, AteResult* result);

/// Relative pose error of the motions over `delta_frames`: E = (gt_i^-1 gt_j)^-1 (est_i^-1 est_j)
/// with j = i + delta, the estimated translations multiplied by `est_scale` first.
struct RpeResult {
  int delta_frames = 1;
  ErrorStatistics translation_m;  ///< |t(E)|
  ErrorStatistics rotation_deg;   ///< angle(R(E))
};
std::string relativePoseError(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                              int delta_frames, double est_scale, RpeResult* result);

/// KITTI odometry devkit drift (evaluate_odometry.cpp): from every `step_frames`-th frame, for each
/// length L, the first frame whose ground-truth path distance exceeds L; error of the motion between
/// them divided by L; averages over all such segments.
struct KittiDriftOptions {
  std::vector<double> segment_lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
  int step_frames = 10;

  std::string validate() const;
};
struct KittiDriftLength {
  double length_m = 0.0;
  std::size_t count = 0;  ///< segments of this length
  double translation_percent = 0.0, rotation_deg_per_100m = 0.0;
};
struct KittiDriftResult {
  std::size_t count = 0;                 ///< segments of all lengths
  double translation_percent = 0.0;      ///< mean translational error / length, %
  double rotation_deg_per_100m = 0.0;    ///< mean rotational error / length, degrees per 100 m
  std::vector<KittiDriftLength> lengths; ///< only the lengths that have segments
};
/// `est_scale` multiplies the estimated translations (1: the devkit as is, for metric estimates).
/// Not available when the ground truth is shorter than the shortest segment length.
std::string kittiDrift(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                       double est_scale, const KittiDriftOptions& options, KittiDriftResult* result);

/// Scale-free errors of each frame-to-frame motion (i -> i+1).
struct FrameToFrameErrors {
  std::size_t motions = 0;             ///< motions compared for rotation
  std::size_t direction_motions = 0;   ///< motions compared for direction (both translations long enough)
  double mean_rotation_error_deg = 0.0;   ///< mean angle(R_gt^T R_est) of the relative rotations
  double mean_direction_error_deg = 0.0;  ///< mean angle between the relative translations
};
/// Directions are compared only where the ground-truth translation is at least
/// `min_gt_translation_m` (a standing car has no direction) and the estimated one is non-zero.
std::string frameToFrameErrors(const std::vector<Eigen::Isometry3d>& gt, const std::vector<Eigen::Isometry3d>& est,
                               double min_gt_translation_m, FrameToFrameErrors* result);

/// How far the estimate's scale jumps from one keyframe to the next. Between consecutive keyframes
/// the estimated camera travel over the true one is the estimate's local scale; the change of that
/// scale from each keyframe interval to the next, compared over the intervals in which the camera
/// travelled at least `min_gt_travel_m` (a standing car has no scale).
struct KeyframeScaleChanges {
  std::size_t intervals = 0;    ///< keyframe intervals whose scale was measured
  double largest_change = 0.0;  ///< max over consecutive intervals of scaleChange (0.3: 30 %)
  std::size_t at_pair = 0;      ///< pair index of the keyframe between the two intervals
};
/// @param[in] keyframes pair indices of the keyframes, increasing
std::string keyframeScaleChanges(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                                 const std::vector<std::size_t>& keyframes, double min_gt_travel_m, KeyframeScaleChanges* result);

/// Camera centres (the translations of the poses), metres.
std::vector<Eigen::Vector3d> positionsOf(const std::vector<Eigen::Isometry3d>& poses);

/// Length of the path through the positions, metres.
double pathLength(const std::vector<Eigen::Vector3d>& positions);

/// The estimate's scale as it is (no alignment): its travel over the true travel from pair `first`
/// to the last, both measured over steps of `step` pairs (frame-to-frame jitter left out); 0 when
/// the truth does not move.
double travelScale(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, std::size_t first, std::size_t step);
/// The same from pair `first` to pair `last`.
double travelScale(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, std::size_t first, std::size_t last,
                   std::size_t step);

/// How far apart two local scales are: max(a/b, b/a) - 1 (0.3: a 30 % change).
double scaleChange(double a, double b);

/// The estimate's local scale along the path: its travel over the true travel (travelScale, steps
/// of `step` pairs) over each stretch of `stretch_m` metres of true travel, in order; a last stretch
/// shorter than half of `stretch_m` joins the one before (none when the whole path is that short).
/// Where a monocular estimate's scale drifts (turns, a restart) shows here; one Sim(3) alignment
/// averages it away.
struct ScaleStretch {
  std::size_t first = 0, last = 0;  ///< pair indices of the stretch's ends
  double from_m = 0.0, to_m = 0.0;  ///< true distance along the path of its ends, metres
  double scale = 0.0;               ///< estimated travel over true travel
};
struct ScaleAlongPath {
  std::vector<ScaleStretch> stretches;
  std::size_t lowest = 0, highest = 0;  ///< indices of the stretches of the lowest and highest scale
  double largest_change = 0.0;          ///< the largest scaleChange between neighbouring stretches
};
ScaleAlongPath scaleAlongPath(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est, double stretch_m,
                              std::size_t step);

/// Distances of the positions from the constant-speed straight line closest to them (least squares
/// in a + b k, k = each position's frame number), metres: what a motion model without vision scores
/// after alignment, the reference an estimate must beat on a nearly straight road. Needs two distinct
/// frame numbers.
ErrorStatistics straightLineErrors(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::size_t>& frames);

}  // namespace semantic_edge_vo
