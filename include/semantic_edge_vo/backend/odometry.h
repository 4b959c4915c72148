#pragma once
#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/mapper.h"
#include "semantic_edge_vo/backend/mapping_link.h"
#include "semantic_edge_vo/backend/odometry_options.h"
#include "semantic_edge_vo/backend/two_view_initializer.h"
#include "semantic_edge_vo/frontend/frame_consistency.h"
#include "semantic_edge_vo/frontend/motion_model.h"
#include "semantic_edge_vo/frontend/tracker.h"

namespace semantic_edge_vo {

enum class OdometryState {
  kInitializing,  ///< no map yet (first frames, or after a loss)
  kTracking,      ///< pose trusted
  kLost,          ///< tracking failed on this frame: its pose is a prediction, not trusted
  kUntrusted,     ///< tracked, but no solution agreed with the recent frames: its pose is a prediction, not trusted
};
const char* toString(OdometryState state);

/// Where the map's scale comes from.
enum class ScaleState {
  kArbitrary,  ///< no camera height, or no road seen yet: monocular, up to an unknown scale
  kMeasured,   ///< the newest window found the road under a keyframe: metres, measured
  kHeld,       ///< metres, but the newest window found no road (or a new map after a loss has not yet): carried on from before
};
const char* toString(ScaleState state);

/// The pose of one frame, final once returned (in parallel mode: as tracked; see Odometry::process).
struct FramePose {
  int index = 0;
  double time = 0.0;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  ///< camera-to-world, world = first camera
  bool trusted = false;
  OdometryState state = OdometryState::kInitializing;
  bool recovered = false;   ///< first trusted pose after a loss or a restart
  bool keyframe = false;    ///< the frame became a keyframe
  int keyframe_id = -1;     ///< keyframe it was tracked against
  int keyframe_frame = -1;  ///< that keyframe's frame index
  TrackingResult tracking;
  /// How far the tracked motion was from the prediction, in the car's usual travel per frame (0:
  /// not compared; see FrameConsistencyOptions); for an untrusted frame, the rejected solution's.
  double motion_deviation = 0.0;
  /// A keyframe made (or refused) at this frame: the scale of its points against the map's (1: none).
  double keyframe_scale = 1.0;
  /// How the windowed optimisation moved the pose after it was tracked (a new keyframe's; else identity).
  Eigen::Isometry3d window_correction = Eigen::Isometry3d::Identity();
  /// On the caller's thread (mapping: depths, keyframe, the windowed optimisation; 0 in parallel mode).
  double tracking_ms = 0.0, mapping_ms = 0.0;
  double window_ms = 0.0;  ///< the windowed optimisation (part of mapping_ms)
  ScaleState scale = ScaleState::kArbitrary;
  /// The fraction of the newest window's keyframes whose road plane was found (0 without a camera height).
  double scale_confidence = 0.0;
};

/// Monocular semantic edge odometry: initialisation, frame-to-keyframe tracking (photometric + edge
/// residuals) with its checks against the recent frames, and the mapping half (Mapper: keyframe
/// decisions, inverse depths of new points from epipolar search filtered over the following frames,
/// edge points restricted to edges of the same class, the windowed optimisation) on its own thread
/// or in another component, behind a MappingLink. Tracking waits for mapping after each frame
/// (MappingMode::kDeterministic, the offline runner's) or only for a keyframe it asked for (kParallel).
class Odometry {
 public:
  /// @param[in] mapping where mapping runs; null: a MappingThread of this object's own
  Odometry(const OdometryOptions& options, const PinholeCamera& camera, MappingMode mode = MappingMode::kDeterministic,
           std::shared_ptr<MappingLink> mapping = nullptr);

  /// Processes the next frame (frames in order). Returns the poses that became final: normally this
  /// frame's; none while initialising; all the waiting frames' when initialisation succeeds. In
  /// parallel mode a pose is returned as tracked: whether its frame becomes a keyframe (and how the
  /// window moves it) is decided later, and shows in takeNewWindows() and the poses after it.
  std::vector<FramePose> process(const std::shared_ptr<const OdometryFrame>& frame);
  ScaleState scaleState() const { return scale_; }
  /// Forgets the map: the next frame starts a new initialisation, as after a loss (the new map
  /// begins where the odometry predicts that frame, at the old map's scale: odom stays continuous),
  /// but without trying the old map first. While initialising it only stops those tries.
  void restart();
  /// New values of the live parameters: the tracker uses them from the next frame, mapping from the
  /// next request it gets.
  void tune(const LiveTuning& tuning);
  /// Poses of frames still waiting for initialisation, as untrusted constant-velocity predictions (end of a sequence).
  std::vector<FramePose> flush();
  /// Waits for mapping to finish what it was handed (parallel mode; at once otherwise), so that
  /// takeNewWindows() has every keyframe made so far.
  void finishMapping();
  /// The windows after each keyframe made since the last call (the first keyframe's after the
  /// frames that waited for it), oldest first.
  std::vector<std::shared_ptr<const KeyframeWindow>> takeNewWindows();

  OdometryState state() const { return state_; }
  MappingMode mappingMode() const { return parallel_ ? MappingMode::kParallel : MappingMode::kDeterministic; }
  /// Frames mapping dropped from its full queue (parallel mode).
  int mappingDropped() const { return mapping_dropped_; }
  /// The keyframe tracking uses: mapping's copy of its active keyframe, refined by the frames so far (null before the first).
  const std::shared_ptr<const Keyframe>& activeKeyframe() const { return keyframe_; }

 private:
  std::vector<FramePose> processFrame(const std::shared_ptr<const OdometryFrame>& frame);
  /// The scale state after a keyframe's window (or a new map).
  void noteScale(const MappingOutcome& outcome);
  /// `start`: when the frame's processing began (its time is the waiting frame's).
  std::vector<FramePose> initialize(const std::shared_ptr<const OdometryFrame>& frame, std::chrono::steady_clock::time_point start);
  void startInitialization(const std::shared_ptr<const OdometryFrame>& frame);
  /// The first waiting frame as the first keyframe of a new map, with the initialiser's depths,
  /// where the odometry predicts it (at the last map's scale after a loss); `T_last_first` gets the
  /// newest waiting frame's pose relative to it at that scale.
  void makeFirstKeyframe(Eigen::Isometry3d* T_last_first);
  /// The poses of the frames that waited for the initialisation: the keyframe's, then each tracked
  /// against it from its share of `T_last_first`; the odometry tracks on. Where the road sets the
  /// map's scale meanwhile (a camera height), every one of them is returned in metres.
  std::vector<FramePose> posesOfWaitingFrames(Eigen::Isometry3d T_last_first, double keyframe_ms);
  /// Hands a request to mapping and waits for its outcome (deterministic mode, the initialisation).
  /// Throws std::runtime_error when mapping failed on it.
  MappingOutcome mapNow(MappingRequest request);
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
  /// The pose of a frame tracked against the keyframe (lost when the tracking failed; the prediction
  /// when `consistent` is false); a trusted frame goes to mapping.
  FramePose trackedPose(const std::shared_ptr<const OdometryFrame>& frame, const TrackingResult& result, bool consistent,
                        double tracking_ms);
  /// The frame's pose when no solution could be trusted: the prediction; lost after too many in a row.
  FramePose untrustedPose(const OdometryFrame& frame, FramePose pose);
  /// Parallel mode: takes what mapping made since the last frame (the newest keyframe to track
  /// against; a new keyframe's window correction moves the recent poses).
  void collectMapping();
  void trackAgainst(std::shared_ptr<const Keyframe> keyframe);
  /// Initial guesses for the frame, from the last pose and the frame intervals since it.
  std::vector<Eigen::Isometry3d> guesses(const Keyframe& keyframe, const OdometryFrame& frame) const;
  static FrameStamp stampOf(const OdometryFrame& frame) { return {frame.index, frame.time}; }
  /// A final pose: the motion model's, and its inlier ratio among the recent ones when trusted.
  void remember(const FramePose& pose);

  OdometryOptions options_;
  PinholeCamera camera_;
  Tracker tracker_;
  std::optional<LiveTuning> pending_tuning_;  ///< for mapping's next request
  std::shared_ptr<const Keyframe> keyframe_;  ///< tracked against: mapping's copy of its active keyframe
  TwoViewInitializer initializer_;
  std::shared_ptr<MappingLink> mapping_;
  bool parallel_ = false;
  int mapping_dropped_ = 0;  ///< requests mapping dropped from its full queue
  std::vector<std::shared_ptr<const KeyframeWindow>> new_windows_;
  OdometryState state_ = OdometryState::kInitializing;
  bool recovering_ = false;
  bool relocalizing_ = false;  ///< lost: each frame is tried against the map it had before a new initialisation's
  /// A frame since the initialisation started, with the initialiser's time on it (reported as its tracking time).
  struct WaitingFrame {
    std::shared_ptr<const OdometryFrame> frame;
    double ms = 0.0;
  };
  std::vector<WaitingFrame> waiting_;
  MotionModel motion_;  ///< the recent poses: predictions and initial guesses
  double speed_at_restart_ = 0.0;  ///< driving travel per frame interval (drivingMotion) when the map was given up: the next one's scale
  static constexpr std::size_t kRestartMotions = 10;   ///< the last second of driving: a new map's scale after a loss
  /// Photometric inlier ratios of the last tracked frames: how well the map explained them (relocalize).
  std::deque<double> recent_inlier_ratios_;
  static constexpr std::size_t kRecentInlierRatios = 10;
  double last_inlier_ratio_ = 1.0;  ///< photometric inlier ratio of the last tracked frame (1: none)
  int untrusted_in_a_row_ = 0;      ///< frames tracked but not trusted since the last trusted one
  ScaleState scale_ = ScaleState::kArbitrary;
  double scale_confidence_ = 0.0;
  bool map_scale_measured_ = false;  ///< the road set a map's scale once: metres since, measured or held
  /// Parallel mode: the last frame whose flow asked for a new keyframe, until mapping made it.
  struct KeyframeAsked {
    int frame_index = -1;
    std::shared_ptr<std::atomic<bool>> tracking_waits;  ///< its request's MappingRequest::tracking_waits
  };
  std::optional<KeyframeAsked> keyframe_asked_;
};

}  // namespace semantic_edge_vo
