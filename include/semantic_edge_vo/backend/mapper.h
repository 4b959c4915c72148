#pragma once
#include <atomic>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/keyframe_depths.h"
#include "semantic_edge_vo/backend/odometry_options.h"

namespace semantic_edge_vo {

/// What tracking hands to mapping: a frame tracked and trusted, or a new map from an initialisation.
struct MappingRequest {
  std::shared_ptr<const OdometryFrame> frame;
  /// A new map: `frame` at `T_world_cam` is its first keyframe, its candidates' inverse depths
  /// `inverse_depths` (0: none; one per candidate). The fields below it are unused.
  bool new_map = false;
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  std::vector<double> inverse_depths;
  int keyframe_id = -1;  ///< the keyframe it was tracked against (tracking.T_cam_kf is relative to it)
  TrackingResult tracking;
  /// A frame that waited for the initialisation: it refines the first keyframe's depths and follows
  /// its corners; class reliability and keyframe decisions start after these frames.
  bool waited_for_initialization = false;
  /// New live parameters (Odometry::tune), taken before this request is mapped.
  std::optional<LiveTuning> tuning;
  /// Set (by tracking, to true) once tracking waits for this frame's outcome (it asked for a
  /// keyframe): a window still being solved for an earlier frame then ends at its next iteration,
  /// as ORB-SLAM aborts its local bundle adjustment when a keyframe arrives. Null: nobody waits.
  std::shared_ptr<std::atomic<bool>> tracking_waits;
};

/// The keyframes of the window as they were when a keyframe was made: copies, never changed again.
struct KeyframeWindow {
  int frame_index = -1;  ///< the frame the newest keyframe was made from
  std::vector<std::shared_ptr<const Keyframe>> keyframes;  ///< oldest first
};

/// What mapping did with one request.
struct MappingOutcome {
  int frame_index = -1;
  bool dropped = false;  ///< dropped unmapped from a full queue (parallel mapping); nothing else is set
  std::string error;     ///< what mapping failed with on the request (dropped); empty when it did not
  /// The request was tracked against a keyframe that has left the window (parallel mode: mapping
  /// made new ones meanwhile); nothing was done.
  bool stale = false;
  /// The active keyframe after the request (its depths refined; a new keyframe when one was made),
  /// a copy tracking may use while mapping goes on.
  std::shared_ptr<const Keyframe> active;
  bool keyframe = false;  ///< the frame became a keyframe
  /// `active` is a new keyframe whose window has not run yet: its pose as tracked, its points with
  /// the map's depths (parallel mapping hands it to tracking at once; the settled one follows with
  /// keyframe set).
  bool provisional = false;
  bool refused = false;   ///< it was to become one, but its depths disagreed with the map's scale
  double keyframe_scale = 1.0;  ///< the scale of its points against the map's (1: no keyframe attempted)
  /// The frame's pose once the window settled it (a keyframe's; else where the window has the
  /// keyframe it was tracked against) and how the window moved it (identity without a keyframe).
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d window_correction = Eigen::Isometry3d::Identity();
  /// The window's keyframe poses afterwards, by id: where tracking's keyframes are now.
  std::map<int, Eigen::Isometry3d> keyframe_poses;
  std::shared_ptr<const KeyframeWindow> window;  ///< the window after a new keyframe or a new map (else null)
  /// Metric scale (a camera height): the keyframes of the window it solved, and how many of them
  /// had their road plane found.
  int window_keyframes = 0, road_keyframes = 0;
  /// The first road a map showed set its scale: the map was scaled by this about `rescaled_about`
  /// (the new keyframe's tracked position) before the window ran; 1: not rescaled.
  double map_rescale = 1.0;
  Eigen::Vector3d rescaled_about = Eigen::Vector3d::Zero();
  double mapping_ms = 0.0;  ///< all of it, the windowed optimisation included
  double window_ms = 0.0;   ///< the windowed optimisation
};

/// The mapping half of the odometry, ROS-free and single-threaded (the caller picks the thread,
/// MappingThread): the active keyframe's depths refined by each tracked frame (epipolar search and
/// filter), corners followed for the keyframes' measured motion, the drive's class reliability,
/// keyframe decisions, new keyframes with their points triangulated, and the windowed optimisation.
class Mapper {
 public:
  Mapper(const OdometryOptions& options, const PinholeCamera& camera);

  /// A new map: starts it (outcome.active is its first keyframe). A tracked frame: refines the
  /// active keyframe with it, and makes the frame a keyframe when it should be one (flow, points in
  /// view, interval with parallax) and its depths agree with the map.
  MappingOutcome map(const MappingRequest& request);

  /// Called (on the mapping thread) with each new keyframe before the windowed optimisation
  /// settles it (outcome.provisional): its pose as tracked, and only its points the map's measured
  /// points fall on, with their depths (KeyframeDepths::triangulate's map_depths). Tracking can use it
  /// 100 ms sooner.
  void onProvisionalKeyframe(std::function<void(MappingOutcome)> callback) { on_provisional_ = std::move(callback); }
  /// Asked (on the mapping thread) after each iteration of the windowed optimisation: true ends it
  /// there (from its first iteration on), with the last solution the solver accepted. Unset: every
  /// window runs in full.
  void stopWindowWhen(std::function<bool()> stop) { stop_window_ = std::move(stop); }
 private:
  void startMap(const MappingRequest& request);
  /// Refines the active keyframe with a tracked frame and makes the frame a keyframe when it should
  /// be one (`outcome` gets what was done). False, nothing done, when the keyframe it was tracked
  /// against has left the window.
  bool refineWith(const MappingRequest& request, MappingOutcome* outcome);
  /// A copy of the window.
  std::shared_ptr<const KeyframeWindow> window() const;
  /// The keyframe of the window with this id; null when it has left the window.
  const Keyframe* keyframeWithId(int id) const;
  std::map<int, Eigen::Isometry3d> keyframePoses() const;
  /// `first_against_active`: the frame is the first tracked against the active keyframe (its
  /// inlier ratio is the one later frames are held against).
  bool wantsKeyframe(const MappingRequest& request, bool first_against_active) const;
  /// Median flow of the active keyframe's measured points between where the frame's rotation alone
  /// and its whole motion take them, px: the parallax a keyframe made from the frame would triangulate with.
  double travelParallax(const Eigen::Isometry3d& T_frame_kf) const;
  /// Makes the frame a keyframe when its points, triangulated from the tracked pose, agree with the
  /// map's scale (FrameConsistencyOptions::max_keyframe_scale_change): it joins the window, the
  /// windowed optimisation settles its pose (`outcome` gets it), then its points are triangulated
  /// from there. It keeps `frame_edges` for the next keyframe's epipolar search. Refused
  /// (outcome->refused) when the scale disagrees: nothing changed.
  void makeKeyframe(const MappingRequest& request, const Eigen::Isometry3d& T_world_cam,
                    std::shared_ptr<const SharedClassEdgeTest> frame_edges, const RoadFit& road, MappingOutcome* outcome);
  /// The keyframe's points from its frame's candidates, their depths triangulated against the
  /// previous keyframe (KeyframeDepths::triangulate, whose scale it returns; `map_depths` as there).
  double triangulatePoints(Keyframe* keyframe, const Keyframe& previous, std::vector<MapPoint>* map_depths = nullptr) const;
  /// The keyframe's points from its frame's candidates, each matched in the SNNF layers the drive's
  /// class reliability gives its classes.
  void takeCandidates(Keyframe* keyframe) const;
  void setActiveKeyframe(std::shared_ptr<Keyframe> keyframe);
  /// With a camera height, until a map's scale is measured: when kMinRoadFits of the planes under
  /// its keyframes and its other frames since it started agree (max_height_change), scales the map
  /// to metres about `about` (the median of those planes' heights). Returns the scale applied (1: none).
  double measureMapScale(const Eigen::Vector3d& about);
  /// With a camera height: the road plane under a frame at its tracked pose, fitted densely against
  /// the frame mapped before it.
  RoadFit measureRoad(const OdometryFrame& frame, const Eigen::Isometry3d& T_world_frame) const;

  OdometryOptions options_;
  PinholeCamera camera_;
  KeyframeDepths depths_;  ///< of the keyframes' points
  WindowOptimizer window_optimizer_;
  KeyframeMotion keyframe_motion_;  ///< corners from the active keyframe
  ClassReliability class_reliability_;
  std::deque<std::shared_ptr<Keyframe>> keyframes_;
  std::shared_ptr<Keyframe> active_;
  int next_keyframe_id_ = 0;
  int frames_since_keyframe_ = 0;
  /// Photometric inlier ratio of the first frame tracked against the active keyframe: what later
  /// frames' ratios are held against (keyframe_min_inliers).
  std::optional<double> first_inlier_ratio_;
  int keyframes_left_ = 0;  ///< keyframes that have left the window
  bool scale_measured_ = false;  ///< the map's scale was set from the road (camera height given)
  std::shared_ptr<const OdometryFrame> previous_frame_;  ///< the frame mapped last, and its pose as tracked
  Eigen::Isometry3d previous_T_world_cam_ = Eigen::Isometry3d::Identity();
  /// Planes measured under frames that did not become keyframes, until the map's scale is set.
  std::vector<double> frame_road_heights_;
  static constexpr int kMinRoadFits = 3;
  /// The allocator gives its free pages back to the system each time this many more have left it.
  static constexpr int kKeyframesBetweenTrims = 20;
  std::function<void(MappingOutcome)> on_provisional_;
  std::function<bool()> stop_window_;
};

}  // namespace semantic_edge_vo
