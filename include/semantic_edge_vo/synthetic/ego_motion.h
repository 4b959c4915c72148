#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/synthetic/route.h"

namespace semantic_edge_vo {
namespace synthetic {

/// How the camera car drives along the route.
struct EgoMotionOptions {
  double min_speed = 5.0;                  ///< slowest cruise speed, m/s
  double max_speed = 12.0;                 ///< fastest cruise speed, m/s
  double speed_block = 150.0;              ///< the cruise speed changes every this many metres
  double max_lateral_acceleration = 2.0;   ///< slows down for turns to stay below, m/s^2
  double max_acceleration = 1.5;           ///< m/s^2
  double max_deceleration = 2.5;           ///< m/s^2
  double lane_offset = 1.75;               ///< lane centre to the right of the centreline, m
  double camera_height = 1.65;             ///< optical centre above the road, m
  double frame_rate = 10.0;                ///< Hz
  double pitch_per_acceleration = 0.004;   ///< nose-down pitch when braking, rad per m/s^2
  double roll_per_acceleration = 0.003;    ///< body roll in turns, rad per m/s^2 of lateral acceleration
  double vibration = 0.0015;               ///< pitch and roll jitter amplitude, rad
  double stop_at = -1.0;                   ///< route position where the car brakes to a stop (a red light), m; < 0: none
  double stop_duration = 5.0;              ///< time it stands there, s

  std::string validate() const;
};

/// The camera car at one frame.
struct EgoState {
  double time = 0.0;          ///< s since frame 0
  double s = 0.0;             ///< arc length along the route, m
  double speed = 0.0;         ///< m/s
  double acceleration = 0.0;  ///< m/s^2
  Eigen::Isometry3d T_map_cam = Eigen::Isometry3d::Identity();  ///< camera optical frame to map
};

/// Speed profile and camera poses, computed frame by frame on demand (deterministic for a seed).
class EgoTrajectory {
 public:
  EgoTrajectory(const EgoMotionOptions& options, Route* route, std::uint64_t seed);

  /// State at frame i >= 0.
  const EgoState& frame(int i);

 private:
  double targetSpeed(double s);
  void appendFrame();

  EgoMotionOptions options_;
  Route* route_;
  std::uint64_t seed_;
  std::vector<EgoState> states_;
  double standing_since_ = -1.0;  ///< time the car came to its stop; < 0: not yet
  bool stop_done_ = false;        ///< it stood its time and drives on
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
