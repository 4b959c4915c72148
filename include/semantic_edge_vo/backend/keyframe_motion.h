#pragma once
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/backend/corner_tracks.h"
#include "semantic_edge_vo/frontend/forward_motion_prior.h"
#include "semantic_edge_vo/backend/keyframe.h"

namespace semantic_edge_vo {

/// Corners tracked from each keyframe to the next, whose two-view geometry measures the rotation and
/// direction of travel between them (priors of the windowed optimisation, and re-anchoring).
struct KeyframeMotionOptions {
  int corners = 400;             ///< Shi-Tomasi corners started at each keyframe; 0: not measured
  double min_distance = 10.0;    ///< between corners, px
  int window = 15;               ///< KLT window side, px
  double ransac_threshold = 0.5; ///< essential matrix RANSAC, px
  int min_inliers = 50;          ///< corners that must agree with the motion
  /// Median flow of the agreeing corners once the measured rotation is taken out, px: below it the
  /// baseline is too short for a direction (a turn alone moves the corners too).
  double min_parallax = 3.0;
  /// Sideways angle, deg, beyond which a measured direction of travel is off the chord a car travels
  /// along for the measured rotation (forward_motion.chord, forward or reversed). Seen on curves, from
  /// corners on traffic and from distant corners, whose essential matrix trades a yaw error for
  /// sideways travel (bas-relief ambiguity). Such a measurement, or none (too few corners agree, or
  /// too little parallax), is replaced by the vehicle's motion (estimateVehicleMotion: the rotation
  /// alone, travel on the chord), which the window's measured-motion priors then hold as firmly as
  /// any measurement. Only sideways: a camera's mount pitch is rarely known to a degree (KITTI's
  /// travels about 1 deg above its axis). 0, or forward_motion off: neither the check nor the
  /// replacement.
  double max_chord_deviation_deg = 2.0;
  /// The vehicle's axis of travel (the loader sets the tracker's).
  ForwardMotionOptions forward_motion;
  /// A new keyframe whose tracked motion from the active one is farther than this from the measured
  /// motion (rotation, deg; direction of travel, deg) is moved onto the measured motion (its distance
  /// kept) before the windowed optimisation: the window's priors alone barely move a pose that the
  /// depths, triangulated along the same error, agree with.
  double reanchor_rotation_deg = 0.3;
  double reanchor_direction_deg = 2.0;
  /// ... but not farther than this (deg): such a measurement is more likely wrong (corners on
  /// traffic) than the tracking that far off, and the window's robust priors handle it instead.
  double reanchor_max_rotation_deg = 10.0;
  double reanchor_max_direction_deg = 45.0;

  std::string validate() const;
};

/// Follows corners from a keyframe through the tracked frames and measures, at the next keyframe,
/// the motion between the two from their essential matrix: independent of the map's depths.
class KeyframeMotion {
 public:
  KeyframeMotion(const KeyframeMotionOptions& options, const PinholeCamera& camera);

  bool enabled() const { return options_.corners > 0; }
  /// Starts corners at a keyframe's image (CV_8UC1); the motion is measured from `keyframe_id`.
  void start(int keyframe_id, int frame_index, const cv::Mat& gray);
  /// Follows the corners into the next tracked frame (CV_8UC1).
  void follow(int frame_index, const cv::Mat& gray);
  /// The motion from the keyframe the corners started at to frame `frame_index`, which they must
  /// have been followed into last; not measured (from_id -1) otherwise, or with too few agreeing
  /// corners or too little parallax, and on a car when off its chord with no vehicle motion found
  /// either (max_chord_deviation_deg). `R_from_this_guess` (the frame's orientation in the keyframe,
  /// as tracked) starts the vehicle-motion fit.
  MeasuredMotion measure(int frame_index, const Eigen::Matrix3d& R_from_this_guess) const;

 private:
  KeyframeMotionOptions options_;
  PinholeCamera camera_;
  CornerTracks tracks_;
  int keyframe_id_ = -1;
  int frame_index_ = -1;  ///< the frame the corners were last followed into (or started at)
};

/// Moves the pose of a new keyframe onto its measured motion from an earlier keyframe (its distance
/// from it kept) when its own motion is farther than the options' gates from the measured one, and
/// not implausibly far (reanchor_max_*).
/// @return true when it moved
bool reanchor(const MeasuredMotion& measured, const KeyframeMotionOptions& options, const Eigen::Isometry3d& T_world_earlier,
              Eigen::Isometry3d* T_world_new);

}  // namespace semantic_edge_vo
