#include "semantic_edge_vo/synthetic/ego_motion.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "semantic_edge_vo/synthetic/noise.h"

namespace semantic_edge_vo {
namespace synthetic {

std::string EgoMotionOptions::validate() const {
  std::ostringstream error;
  if (!(min_speed > 0.0 && max_speed >= min_speed))
    error << "need 0 < min_speed <= max_speed, m/s (got " << min_speed << ", " << max_speed << ")";
  else if (!(speed_block > 0.0)) error << "speed_block must be > 0 m (got " << speed_block << ")";
  else if (!(max_lateral_acceleration > 0.0 && max_acceleration > 0.0 && max_deceleration > 0.0))
    error << "accelerations must be > 0 m/s^2";
  else if (!(camera_height > 0.0)) error << "camera_height must be > 0 m (got " << camera_height << ")";
  else if (!(frame_rate > 0.0)) error << "frame_rate must be > 0 Hz (got " << frame_rate << ")";
  else if (!(vibration >= 0.0 && pitch_per_acceleration >= 0.0 && roll_per_acceleration >= 0.0))
    error << "vibration and pitch/roll gains must be >= 0";
  else if (stop_at >= 0.0 && !(stop_duration > 0.0)) error << "stop_duration must be > 0 s (got " << stop_duration << ")";
  return error.str();
}

EgoTrajectory::EgoTrajectory(const EgoMotionOptions& options, Route* route, std::uint64_t seed)
    : options_(options), route_(route), seed_(seed) {}

double EgoTrajectory::targetSpeed(double s) {
  // Cruise speed: a random level per block, blended smoothly into the next block.
  const double block = s / options_.speed_block;
  const auto k = static_cast<std::uint64_t>(block);
  const double t = block - std::floor(block);
  const double blend = t * t * (3.0 - 2.0 * t);
  auto level = [&](std::uint64_t b) {
    return options_.min_speed + (options_.max_speed - options_.min_speed) *
                                    static_cast<double>(hashCombine(seed_, b) >> 11) * 0x1.0p-53;
  };
  double target = level(k) + blend * (level(k + 1) - level(k));
  // Slow enough for every curve ahead, braking at the comfortable deceleration.
  for (double ahead = 0.0; ahead <= 80.0; ahead += 2.0) {
    const double curvature = std::abs(route_->at(s + ahead).curvature);
    if (curvature < 1e-6) continue;
    const double curve_speed = std::sqrt(options_.max_lateral_acceleration / curvature);
    target = std::min(target, std::sqrt(curve_speed * curve_speed + 2.0 * 0.7 * options_.max_deceleration * ahead));
  }
  return target;
}

void EgoTrajectory::appendFrame() {
  EgoState state;
  if (states_.empty()) {
    state.speed = targetSpeed(0.0);
  } else {
    state = states_.back();
    const int substeps = 10;
    const double dt = 1.0 / (options_.frame_rate * substeps);
    const double start_speed = state.speed;
    const double start_time = state.time;
    for (int i = 0; i < substeps; ++i) {
      double acceleration = std::clamp(0.8 * (targetSpeed(state.s) - state.speed), -options_.max_deceleration,
                                       options_.max_acceleration);
      // A stop: brake at the deceleration that ends at stop_at once the comfortable one (70 % of the
      // most) would no longer do, at most the most (a stop too close for it is overshot), stand
      // stop_duration, then drive on as before.
      if (options_.stop_at >= 0.0 && !stop_done_) {
        const double to_stop = options_.stop_at - state.s, now = start_time + (i + 1) * dt;
        if (standing_since_ < 0.0 && to_stop < 1.0 && state.speed < 0.05) {
          standing_since_ = now;
          state.speed = 0.0;
        }
        if (standing_since_ >= 0.0) {
          stop_done_ = now - standing_since_ >= options_.stop_duration;
          if (!stop_done_) continue;  // standing: no motion this substep
        } else if (to_stop <= 0.0) {
          acceleration = -options_.max_deceleration;
        } else if (state.speed * state.speed >= 2.0 * 0.7 * options_.max_deceleration * to_stop) {
          acceleration = std::max(-options_.max_deceleration, -state.speed * state.speed / (2.0 * to_stop));
        }
      }
      state.s += dt * (state.speed + 0.5 * acceleration * dt);
      state.speed = std::max(0.0, state.speed + acceleration * dt);
    }
    state.time = static_cast<double>(states_.size()) / options_.frame_rate;
    state.acceleration = (state.speed - start_speed) * options_.frame_rate;
  }
  const RoutePoint road = route_->at(state.s);
  const auto seed32 = static_cast<std::uint32_t>(seed_);
  auto jitter = [&](std::uint32_t salt, double rate) {  // smooth noise in [-1, 1]
    return 2.0 * valueNoise1d(state.time * rate, seed32 ^ salt) - 1.0;
  };
  const double lane_wander = 0.15 * (2.0 * valueNoise1d(state.s / 40.0, seed32 ^ 0x1111u) - 1.0);
  const double lateral_acceleration = state.speed * state.speed * road.curvature;
  const double pitch = options_.pitch_per_acceleration * state.acceleration + options_.vibration * jitter(0x2222u, 7.0);
  const double roll = options_.roll_per_acceleration * lateral_acceleration + options_.vibration * jitter(0x3333u, 5.0);
  const double bounce = 0.004 * jitter(0x4444u, 6.0);
  state.T_map_cam.setIdentity();
  state.T_map_cam.translation() = road.position + (options_.lane_offset + lane_wander) * road.right +
                                  Eigen::Vector3d(0.0, -options_.camera_height + bounce, 0.0);
  state.T_map_cam.linear() = (Eigen::AngleAxisd(road.heading, Eigen::Vector3d::UnitY()) *
                              Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                              Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()))
                                 .toRotationMatrix();
  states_.push_back(state);
}

const EgoState& EgoTrajectory::frame(int i) {
  while (static_cast<int>(states_.size()) <= i) appendFrame();
  return states_[static_cast<std::size_t>(i)];
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
