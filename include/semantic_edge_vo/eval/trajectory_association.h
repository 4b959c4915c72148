#pragma once
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {

/// Corresponding poses of a ground truth and an estimate, in frame order (gt[i] <-> est[i]).
struct PosePairs {
  std::vector<Eigen::Isometry3d> gt, est;  ///< T_world_cam of each trajectory in its own world frame
  std::vector<std::size_t> gt_index;       ///< index in the ground truth of each pair (the KITTI frame number)

  /// The ground-truth index of pair i (i itself when the pairs carry no indices).
  std::size_t groundTruthFrame(std::size_t i) const { return i < gt_index.size() ? gt_index[i] : i; }
};

/// Pairs pose i of the ground truth with pose i of the estimate, up to the shorter of the two (an
/// estimate that stops early is evaluated over the frames it has).
PosePairs associateByIndex(const Trajectory& gt, const Trajectory& est);

/// Pairs each ground-truth pose with the estimate pose nearest in time, when within
/// `max_time_difference` seconds (evo's default is 0.01 s); each estimate pose is used at most once.
/// Both trajectories need stamps. Returns an empty string on success, otherwise why nothing matched.
std::string associateByStamps(const Trajectory& gt, const Trajectory& est, double max_time_difference,
                              PosePairs* pairs);

/// The pairs whose ground-truth frame is `first_frame` or later (for a ground truth that is not
/// measured at the start, as KITTI 06's first 12 poses, which are extrapolated at constant velocity).
PosePairs fromGroundTruthFrame(const PosePairs& pairs, std::size_t first_frame);

}  // namespace semantic_edge_vo
