#pragma once
#include <string>

#include <Eigen/Core>

namespace semantic_edge_vo {

/// When a tracked frame's solution is trusted: its motion must agree with the recent frames'. One
/// that does not, or whose photometric inlier ratio falls below accept_inlier_ratio of theirs, is
/// tracked again (Odometry); a frame no solution of which agrees is not trusted.
struct FrameConsistencyOptions {
  /// Its motion since the last pose differs from the constant-velocity prediction by at most this
  /// fraction of the car's usual travel per frame. A car's speed and heading change smoothly: on
  /// KITTI's ground truth the difference stays under 0.1 of it (braking into a 77 degree turn
  /// included); a wrong basin's pose is off by a third or more.
  double max_motion_deviation = 0.25;
  /// Frames in a row that may go untrusted (predicted) before tracking counts as lost, and the map
  /// is tried again or a new one is made.
  int max_untrusted_frames = 5;
  /// The largest change of the map's scale between consecutive keyframes, as a fraction: a new
  /// keyframe whose triangulated depths disagree with the map's by more (the median ratio) is not
  /// made, its frame is not trusted.
  double max_keyframe_scale_change = 0.3;

  std::string validate() const;
};

/// How a tracked frame's solution compares with the recent frames.
struct FrameAgreement {
  bool inliers_ok = true;         ///< photometric inlier ratio at least accept_inlier_ratio of the recent frames' median
  bool motion_ok = true;          ///< motion within max_motion_deviation of the prediction
  double motion_deviation = 0.0;  ///< |travel - predicted travel| over the usual travel (0: no usual travel known)
  bool ok() const { return inliers_ok && motion_ok; }
};

/// @param[in] inlier_ratio, usual_inlier_ratio the frame's photometric inlier ratio, the recent
///            frames' median (<= 0: none known, not checked)
/// @param[in] min_inlier_fraction the fraction of the usual ratio the frame must reach
/// @param[in] travel, predicted_travel the frame's camera centre in the last pose's frame, as
///            tracked and as predicted at constant velocity (map units)
/// @param[in] usual_travel how far the car usually travels over as many frames (<= 0: unknown, the
///            motion is not checked)
FrameAgreement compareWithRecentFrames(double inlier_ratio, double usual_inlier_ratio, double min_inlier_fraction,
                                       const Eigen::Vector3d& travel, const Eigen::Vector3d& predicted_travel,
                                       double usual_travel, const FrameConsistencyOptions& options);

}  // namespace semantic_edge_vo
