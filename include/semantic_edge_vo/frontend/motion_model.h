#pragma once
#include <cstddef>
#include <deque>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/common/se3.h"

namespace semantic_edge_vo {

/// A frame's, or a pose's, index and time stamp.
struct FrameStamp {
  int index = 0;
  double time = 0.0;
};

/// The camera's recent motion, which predicts where the next frame is: the last two final poses
/// (constant velocity), the usual interval between frames (so that frames a stream dropped count),
/// and the travel of the last trusted frames that drove (the guess after a stop, and a new map's
/// scale after a loss).
class MotionModel {
 public:
  static constexpr std::size_t kDrivingMotions = 100;  ///< 10 s at 10 Hz
  static constexpr double kStandingFraction = 0.1;     ///< of the driving travel: standing, or nearly
  static constexpr int kMaxDeadReckoning = 50;         ///< frames predicted on from the last trusted pose: 5 s at 10 Hz

  /// A final pose (trusted, or a prediction); `window_correction`: how the windowed optimisation
  /// moved it after it was tracked (see predictAtTrackedVelocity).
  void remember(const Eigen::Isometry3d& T_world_cam, const FrameStamp& stamp, bool trusted,
                const Eigen::Isometry3d& window_correction = Eigen::Isometry3d::Identity());
  /// Moves the last two poses with a correction of the map (the windowed optimisation's).
  void correct(const Eigen::Isometry3d& correction);
  /// Scales the last two poses' positions about `about` and the driving travel by `scale` (the map
  /// was rescaled about that point).
  void rescale(double scale, const Eigen::Vector3d& about);
  /// Forgets the driving travel (it was at another map's scale).
  void forgetDrivingMotions() { driving_motions_.clear(); }

  int posesSeen() const { return poses_seen_; }
  const Eigen::Isometry3d& lastPose() const { return T_world_last_; }
  const FrameStamp& lastStamp() const { return last_stamp_; }

  /// Frame intervals from one to the other, a whole number, at least 1: by the stamps at the usual
  /// interval, so that frames the stream dropped count; by the indices without stamps.
  double framesBetween(const FrameStamp& from, const FrameStamp& to) const;
  /// Frame intervals from the last pose to the frame that the velocity is extrapolated over: fewer
  /// (down to 0) once kMaxDeadReckoning frames passed since the last trusted pose.
  double framesToExtrapolate(const FrameStamp& frame) const;
  /// The motion of one frame interval at the velocity of the last two poses (identity before two).
  Eigen::Isometry3d frameMotion() const;
  /// The frame's pose at constant velocity from the last pose (framesToExtrapolate).
  Eigen::Isometry3d predict(const FrameStamp& frame) const;
  /// As predict(), at the velocity the last pose was tracked at: without the window's correction of
  /// it, which is a move of the map, not motion the next frames repeat. What a frame's tracked motion
  /// is checked against (the tracker still starts from predict(), the guess the map's move suits).
  Eigen::Isometry3d predictAtTrackedVelocity(const FrameStamp& frame) const;
  /// The median travel (rotation left out) of the newest `newest` driving motions (zero before any).
  Vector6d drivingMotion(std::size_t newest = kDrivingMotions) const;
  /// Where the frame may be, best first: constant velocity, no motion, half and double the velocity,
  /// and, when standing, one frame's driving travel (the last pose alone before two).
  std::vector<Eigen::Isometry3d> guesses(const FrameStamp& frame) const;

 private:
  /// The motion of one frame interval, of `motion` from the before pose to the last.
  Eigen::Isometry3d perFrame(const Eigen::Isometry3d& motion) const;
  /// The last pose moved on at `per_frame` to the frame (framesToExtrapolate intervals).
  Eigen::Isometry3d extrapolate(const Eigen::Isometry3d& per_frame, const FrameStamp& frame) const;

  // The last two final poses and whether any exists.
  Eigen::Isometry3d T_world_last_ = Eigen::Isometry3d::Identity(), T_world_before_ = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d last_window_correction_ = Eigen::Isometry3d::Identity();  ///< of the last pose
  int poses_seen_ = 0;
  FrameStamp last_stamp_, before_stamp_;  ///< of those two poses
  FrameStamp last_trusted_stamp_;
  /// Time between consecutive frame indices over the last poses, s: their median is the usual interval.
  std::deque<double> frame_intervals_;
  static constexpr std::size_t kFrameIntervals = 10;
  /// Frame-to-frame travel (rotation left out) of the last trusted frames that moved.
  std::deque<Vector6d> driving_motions_;
};

}  // namespace semantic_edge_vo
