#pragma once
#include <string>

#include "semantic_edge_vo/config/parameter_loader.h"
#include "semantic_edge_vo/edges/class_map_carrier.h"

namespace semantic_edge_vo {

// Options that only the live graph uses (subscriptions, tf, outputs). They live in the core, with
// the rest, so that each default is written once and the offline tools read a config file's blocks
// whole and can name a key that nothing reads.

/// The EdgeIntake nodelet's input streams.
struct IntakeStreamOptions {
  int queue_size = 5;                            ///< image/camera_info subscription queue, messages
  std::string transport = "raw";                 ///< raw | compressed
  double time_jump_back = 1.0;                   ///< s: a stamp this far back starts the graph over
  double camera_info_tolerance = 0.005;          ///< s between an image's stamp and its camera_info's
  double camera_info_wait = 0.5;                 ///< s an image waits for its camera_info (wall time)
  double image_timeout = 3.0;                    ///< s without an image before the watchdog reports an error
  bool rectify = false;                          ///< undistort with camera_info first
  std::string class_format = "probabilities";    ///< probabilities | labels | bitmask
  std::string edge_source = "canny";             ///< fused: canny | topic
  /// same_frame: an image waits up to class_wait for its own class map | newest: it takes the
  /// newest map at once, carried to it (class_carry): a segmenter slower than the camera
  std::string class_maps = "same_frame";
  ClassMapCarrierOptions class_carry;            ///< class_maps: newest
  double class_wait = 0.5;                       ///< s an image waits for its class map (same_frame)
  std::string on_missing_classes = "canny";      ///< drop | canny
  int max_pending = 10;                          ///< images waiting for class maps, frames

  std::string validate() const;
};

/// The frames the Tracking nodelet publishes in (REP-105).
struct FrameNames {
  std::string odom_frame = "odom", base_frame = "base_link";

  std::string validate() const;
};

/// The Tracking nodelet's frames on tf.
struct TfOptions {
  FrameNames frames;
  std::string camera_frame;               ///< the camera's optical frame (empty: each image's frame_id)
  bool publish_tf = true;                 ///< false: nav_msgs/Odometry only, nothing on tf
  bool publish_default_camera_tf = true;  ///< without base_link -> camera on tf, publish the optical-rotation default
  double extrinsic_wait = 0.5;            ///< s the first frame waits for base_link -> camera on tf
  double max_twist_gap = 1.0;             ///< s between two published poses beyond which the twist is unknown

  std::string validate() const;
};

/// How the Tracking nodelet runs the odometry's mapping half.
struct LiveMappingOptions {
  /// deterministic: after each frame, the trajectory run_sequence gives | parallel: on its own
  /// thread, tracking never waits (not yet as accurate: docs/evaluation.md)
  std::string mapping_mode = "deterministic";

  std::string validate() const;
};

/// The Mapping nodelet's map and path.
struct MapOutputOptions {
  std::string odom_frame = FrameNames().odom_frame;  ///< of the map and the path: Tracking's
  int queue_size = 20;           ///< messages in front of the mapping thread
  double voxel_size = 0.1;       ///< map units
  int max_map_points = 200000;
  int max_path_poses = 10000;

  std::string validate() const;
};

/// The Segmenter nodelet's output.
struct SegmenterOutputOptions {
  /// probabilities: every class's (output_bits) | labels: 8UC2 (most probable class, its
  /// probability x 255), 2 bytes a pixel instead of 19 or 76, for the intake's class_format labels
  std::string output_format = "probabilities";
  int output_bits = 32;  ///< probabilities: 32 (32FC<C>) | 8 (8UC<C>, probability x 255)
  int log_every = 100;   ///< frames between logs of the median time
  /// OpenCV threads of the Segmenter's process (cv::setNumThreads: process-wide, so it applies to
  /// every nodelet of the manager it is loaded in; the launch file runs it standalone); 0: OpenCV's
  /// choice. 1 leaves the other core of two to the odometry.
  int threads = 1;

  std::string validate() const;
};

// Loaders under the nodelets' parameter names; each returns the validation error.
std::string loadIntakeStreamOptions(ParameterLoader* loader, IntakeStreamOptions* options);
std::string loadTfOptions(ParameterLoader* loader, TfOptions* options);
std::string loadLiveMappingOptions(ParameterLoader* loader, LiveMappingOptions* options);
std::string loadMapOutputOptions(ParameterLoader* loader, MapOutputOptions* options);
std::string loadSegmenterOutputOptions(ParameterLoader* loader, SegmenterOutputOptions* options);

}  // namespace semantic_edge_vo
