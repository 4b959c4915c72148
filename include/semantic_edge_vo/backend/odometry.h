#pragma once
#include <chrono>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "semantic_edge_vo/frontend/class_reliability.h"
#include "semantic_edge_vo/backend/deferred_window_optimization.h"
#include "semantic_edge_vo/backend/epipolar_depth.h"
#include "semantic_edge_vo/frontend/frame_consistency.h"
#include "semantic_edge_vo/frontend/motion_model.h"
#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/keyframe_depths.h"
#include "semantic_edge_vo/backend/keyframe_motion.h"
#include "semantic_edge_vo/frontend/tracker.h"
#include "semantic_edge_vo/backend/two_view_initializer.h"
#include "semantic_edge_vo/backend/window_optimizer.h"

namespace semantic_edge_vo {

enum class OdometryState {
  kInitializing,  ///< no map yet (first frames, or after a loss)
  kTracking,      ///< pose trusted
  kLost,          ///< tracking failed on this frame: its pose is a prediction, not trusted
  kUntrusted,     ///< tracked, but no solution agreed with the recent frames: its pose is a prediction, not trusted
};
const char* toString(OdometryState state);

struct OdometryOptions {
  TrackerOptions tracker;
  InitializerOptions initializer;
  EpipolarSearchOptions epipolar;
  WindowOptimizerOptions window_optimizer;
  KeyframeMotionOptions keyframe_motion;
  ClassReliabilityOptions class_reliability;
  FrameConsistencyOptions consistency;
  bool optimize_window = true;         ///< run the windowed optimisation at each new keyframe
  /// Frames after its keyframe at which the windowed optimisation, run meanwhile on its own thread,
  /// is merged (waiting for it if needed; at the next keyframe at the latest). 0: in line, at once.
  int window_delay = 0;
  double keyframe_flow = 60.0;         ///< new keyframe when the keyframe points moved this much on average, px
  double keyframe_min_in_view = 0.6;   ///< ... or fewer of them are in view (fraction)
  int keyframe_max_interval = 8;      ///< ... or this many frames passed
  /// ... once the camera has travelled: the median flow of the keyframe points that the travel alone
  /// causes (their pixels minus where the rotation alone takes them) is at least this, px. A
  /// keyframe made without parallax measures no depth and would leave tracking without points (a
  /// car waiting at a light made one every keyframe_max_interval frames).
  double keyframe_min_parallax = 5.0;
  double depth_neighbour_radius = 30.0;  ///< new keyframe points take a prior depth from map points this near, px
  int window_size = 7;                 ///< keyframes kept (the map published to users)

  std::string validate() const;
};

/// The pose of one frame, final once returned.
struct FramePose {
  int index = 0;
  double time = 0.0;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  ///< camera-to-world, world = first camera
  bool trusted = false;
  OdometryState state = OdometryState::kInitializing;
  bool recovered = false;   ///< first trusted pose after a loss or a restart
  bool keyframe = false;    ///< the frame became a keyframe
  int keyframe_id = -1;     ///< keyframe it was tracked against
  TrackingResult tracking;
  /// How far the tracked motion was from the prediction, in the car's usual travel per frame (0:
  /// not compared; see FrameConsistencyOptions); for an untrusted frame, the rejected solution's.
  double motion_deviation = 0.0;
  /// A keyframe made (or refused) at this frame: the scale of its points against the map's (1: none).
  double keyframe_scale = 1.0;
  /// How the windowed optimisation moved the pose after it was tracked (a new keyframe's; else identity).
  Eigen::Isometry3d window_correction = Eigen::Isometry3d::Identity();
  double tracking_ms = 0.0, mapping_ms = 0.0;  ///< on the caller's thread (mapping: depths, keyframes, waiting)
  double window_ms = 0.0;  ///< the windowed optimisation merged at this frame (on its own thread when deferred)
};

/// Monocular semantic edge odometry, sequential and deterministic: initialisation, frame-to-keyframe
/// tracking (photometric + edge residuals), keyframe decisions, inverse depths of new points from
/// epipolar search filtered over the following frames (edge points restricted to edges of the same
/// class). The offline runner calls it directly; the nodelets split it between tracking and mapping.
class Odometry {
 public:
  Odometry(const OdometryOptions& options, const PinholeCamera& camera);

  /// Processes the next frame (frames in order). Returns the poses that became final: normally this
  /// frame's; none while initialising; all the waiting frames' when initialisation succeeds.
  std::vector<FramePose> process(const std::shared_ptr<const OdometryFrame>& frame);
  /// Forgets the map: the next frame starts a new initialisation, as after a loss (the new map
  /// begins where the odometry predicts that frame, at the old map's scale: odom stays continuous),
  /// but without trying the old map first. While initialising it only stops those tries.
  void restart();
  /// Poses of frames still waiting for initialisation, as untrusted constant-velocity predictions (end of a sequence).
  std::vector<FramePose> flush();

  OdometryState state() const { return state_; }
  const std::deque<std::shared_ptr<Keyframe>>& keyframes() const { return keyframes_; }

 private:
  /// `start`: when the frame's processing began (its time is the waiting frame's).
  std::vector<FramePose> initialize(const std::shared_ptr<const OdometryFrame>& frame, std::chrono::steady_clock::time_point start);
  void startInitialization(const std::shared_ptr<const OdometryFrame>& frame);
  /// The first waiting frame as the first keyframe, with the initialiser's depths, where the
  /// odometry predicts it (at the last map's scale after a loss); `T_last_first` gets the newest
  /// waiting frame's pose relative to it at that scale.
  std::shared_ptr<const Keyframe> makeFirstKeyframe(Eigen::Isometry3d* T_last_first);
  /// The poses of the frames that waited for the initialisation: the keyframe's, then each tracked
  /// against it from its share of `T_last_first`; the odometry tracks on.
  std::vector<FramePose> posesOfWaitingFrames(const Keyframe& keyframe, const Eigen::Isometry3d& T_last_first, double keyframe_ms);
  /// After a loss, tracks the frame against the map it had (the view may come back: an occlusion, a
  /// standing car). On success the odometry tracks on, `poses` gets the waiting frames' untrusted
  /// predictions and the frame's pose; otherwise nothing changes.
  bool relocalize(const std::shared_ptr<const OdometryFrame>& frame, std::vector<FramePose>* poses);
  FramePose track(const std::shared_ptr<const OdometryFrame>& frame);
  /// How a tracked solution compares with the recent frames.
  FrameAgreement agreementOf(const OdometryFrame& frame, const TrackingResult& result) const;
  /// When the solution disagrees with the recent frames, the frame is tracked again from the
  /// prediction, photometric residuals alone and (SNNF) every edge point in the all-edges layer;
  /// of the solutions whose motion agrees, the one with the most inliers is kept. Returns whether
  /// one did (`result` can be trusted).
  bool retrackUnlessConsistent(const OdometryFrame& frame, const Eigen::Isometry3d& prediction, TrackingResult* result,
                               double* motion_deviation);
  /// The pose of a frame tracked against the active keyframe (lost when the tracking failed; the
  /// prediction when `consistent` is false); the depths, corners and keyframe decision follow from it.
  FramePose trackedPose(const std::shared_ptr<const OdometryFrame>& frame, const TrackingResult& result, bool consistent,
                        double tracking_ms);
  /// Median flow of the keyframe's measured points between where the frame's rotation alone and its
  /// whole motion take them, px: the parallax a keyframe made from the frame would triangulate with.
  double travelParallax(const Keyframe& keyframe, const Eigen::Isometry3d& T_frame_kf) const;
  /// Refines the active keyframe's depths with a tracked frame. Returns the frame's edge test (null
  /// without a field), which the frame keeps if it becomes a keyframe.
  std::shared_ptr<const SharedClassEdgeTest> refineDepths(const OdometryFrame& frame, const Eigen::Isometry3d& T_frame_kf);
  /// Makes the frame a keyframe when its points, triangulated from the tracked pose, agree with the
  /// map's scale (FrameConsistencyOptions::max_keyframe_scale_change): it joins the window, the
  /// windowed optimisation settles its pose (in line; `pose` gets it), then its points are
  /// triangulated from there. It keeps `frame_edges` (refineDepths' test) for the next keyframe's
  /// epipolar search. False when the scale disagrees: nothing changed, the frame is not to be trusted.
  bool makeKeyframe(const std::shared_ptr<const OdometryFrame>& frame, std::shared_ptr<const SharedClassEdgeTest> frame_edges,
                    FramePose* pose);
  /// The keyframe's points from its frame's candidates, their depths triangulated against the
  /// previous keyframe (KeyframeDepths::triangulate, whose scale it returns).
  double triangulatePoints(Keyframe* keyframe, const Keyframe& previous) const;
  /// The frame's pose when no solution could be trusted: the prediction; lost after too many in a row.
  FramePose untrustedPose(const OdometryFrame& frame, FramePose pose);
  /// Optimises the window at a new keyframe: in line, or started on its own thread.
  void optimizeWindow(int frame_index, FramePose* pose);
  /// Merges the deferred optimisation; the recent poses move with the active keyframe, whose points
  /// are triangulated again from its settled pose (the caller hands it to the tracker).
  /// @return the correction of the active keyframe's pose (identity when it did not move)
  Eigen::Isometry3d mergeWindow(FramePose* pose);
  void setActiveKeyframe(std::shared_ptr<Keyframe> keyframe);
  /// The keyframe's points from its frame's candidates, each matched in the SNNF layers the drive's
  /// class reliability gives its classes.
  void takeCandidates(Keyframe* keyframe) const;
  /// Follows the active keyframe's corners into a tracked frame (KeyframeMotion).
  void followCorners(const OdometryFrame& frame);
  /// Initial guesses for the frame, from the last pose and the frame intervals since it.
  std::vector<Eigen::Isometry3d> guesses(const Keyframe& keyframe, const OdometryFrame& frame) const;
  static FrameStamp stampOf(const OdometryFrame& frame) { return {frame.index, frame.time}; }
  /// A final pose: the motion model's, and its inlier ratio among the recent ones when trusted.
  void remember(const FramePose& pose);

  OdometryOptions options_;
  PinholeCamera camera_;
  Tracker tracker_;
  KeyframeDepths depths_;  ///< of the keyframes' points
  WindowOptimizer window_optimizer_;
  DeferredWindowOptimization deferred_window_;
  int merge_window_at_ = 0;  ///< frame index at which the deferred optimisation is merged
  TwoViewInitializer initializer_;
  KeyframeMotion keyframe_motion_;  ///< corners from the active keyframe
  ClassReliability class_reliability_;
  OdometryState state_ = OdometryState::kInitializing;
  bool recovering_ = false;
  bool relocalizing_ = false;  ///< lost: each frame is tried against the map it had before a new initialisation's
  /// A frame since the initialisation started, with the initialiser's time on it (reported as its tracking time).
  struct WaitingFrame {
    std::shared_ptr<const OdometryFrame> frame;
    double ms = 0.0;
  };
  std::vector<WaitingFrame> waiting_;
  std::deque<std::shared_ptr<Keyframe>> keyframes_;
  std::shared_ptr<Keyframe> active_;
  int next_keyframe_id_ = 0;
  int frames_since_keyframe_ = 0;
  MotionModel motion_;  ///< the recent poses: predictions and initial guesses
  double speed_at_restart_ = 0.0;  ///< driving travel per frame interval (drivingMotion) when the map was given up: the next one's scale
  static constexpr std::size_t kRestartMotions = 10;   ///< the last second of driving: a new map's scale after a loss
  /// Photometric inlier ratios of the last tracked frames: how well the map explained them (relocalize).
  std::deque<double> recent_inlier_ratios_;
  static constexpr std::size_t kRecentInlierRatios = 10;
  double last_inlier_ratio_ = 1.0;  ///< photometric inlier ratio of the last tracked frame (1: none)
  int untrusted_in_a_row_ = 0;      ///< frames tracked but not trusted since the last trusted one
};

}  // namespace semantic_edge_vo
