#pragma once
#include <string>

#include "semantic_edge_vo/backend/epipolar_depth.h"
#include "semantic_edge_vo/backend/keyframe_motion.h"
#include "semantic_edge_vo/backend/road_plane.h"
#include "semantic_edge_vo/backend/two_view_initializer.h"
#include "semantic_edge_vo/backend/window_optimizer.h"
#include "semantic_edge_vo/frontend/class_reliability.h"
#include "semantic_edge_vo/frontend/frame_consistency.h"
#include "semantic_edge_vo/frontend/tracker.h"

namespace semantic_edge_vo {

/// How the odometry runs its mapping half (Mapper) against tracking.
enum class MappingMode {
  /// In the caller's thread, after each frame is tracked: tracking waits for mapping at every frame
  /// and the trajectory does not depend on timing (the offline runner; tests).
  kDeterministic,
  /// On its own thread: tracking hands each trusted frame over (a bounded queue, the oldest dropped
  /// when full) and tracks the next frames against the newest keyframe mapping has made.
  kParallel,
};
const char* toString(MappingMode mode);
/// "deterministic" | "parallel"; false for anything else.
bool parseMappingMode(const std::string& text, MappingMode* mode);

struct OdometryOptions {
  TrackerOptions tracker;
  InitializerOptions initializer;
  EpipolarSearchOptions epipolar;
  WindowOptimizerOptions window_optimizer;
  KeyframeMotionOptions keyframe_motion;
  ClassReliabilityOptions class_reliability;
  FrameConsistencyOptions consistency;
  /// Metric scale from the road (camera_height > 0): the first keyframe's depths in metres, then
  /// each window holds the keyframes' road points at the camera's height. The caller sets
  /// road.road_classes from its class table (roadClassBits).
  RoadScaleOptions road;
  bool optimize_window = true;         ///< run the windowed optimisation at each new keyframe
  double keyframe_flow = 60.0;         ///< new keyframe when the keyframe points moved this much on average, px
  double keyframe_min_in_view = 0.6;   ///< ... or fewer of them are in view (fraction)
  int keyframe_max_interval = 8;      ///< ... or this many frames passed
  /// ... or a frame's photometric inlier ratio fell below this fraction of the first frame's tracked
  /// against the keyframe: the view has changed more than the flow says (fast travel past near
  /// structure, a truck alongside), and tracking would soon be lost against this keyframe.
  double keyframe_min_inliers = 0.85;
  /// ... once the camera has travelled: the median flow of the keyframe points that the travel alone
  /// causes (their pixels minus where the rotation alone takes them) is at least this, px. A
  /// keyframe made without parallax measures no depth and would leave tracking without points (a
  /// car waiting at a light made one every keyframe_max_interval frames).
  double keyframe_min_parallax = 5.0;
  double depth_neighbour_radius = 30.0;  ///< new keyframe points take a prior depth from map points this near, px
  int window_size = 7;                 ///< keyframes kept (the map published to users)
  /// Parallel mapping: tracked frames waiting for the mapping thread at most; when full the oldest
  /// is dropped (its depth measurements are lost, the newest frame is the better keyframe).
  int mapping_queue = 4;

  std::string validate() const;
};

/// What users may change while an odometry runs (the Tracking nodelet's live parameters): the
/// tracker's robust widths and the keyframe thresholds. The rest is fixed for an odometry's life.
struct LiveTuning {
  double photometric_huber = 0.0, edge_huber = 0.0;
  double keyframe_flow = 0.0, keyframe_min_parallax = 0.0;
  int keyframe_max_interval = 0;

  static LiveTuning of(const OdometryOptions& options);
  void applyTo(OdometryOptions* options) const;
};

}  // namespace semantic_edge_vo
