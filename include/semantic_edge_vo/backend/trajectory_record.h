#pragma once
#include <string>
#include <vector>

#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {

/// Every frame's pose as the odometry gave it, trusted or not, for the trajectory files: camera
/// poses in the odometry's world (KITTI and TUM) and which of them to trust (poses_flags.txt).
class TrajectoryRecord {
 public:
  /// Frames in order; `stamp` in seconds, increasing.
  void add(const FramePose& pose, double stamp);
  void clear();
  std::size_t size() const { return trajectory_.size(); }

  /// Writes `<directory>/poses_kitti.txt`, `poses_tum.txt` and `poses_flags.txt`; returns the first
  /// error (empty: all written). `files`, when given, gets the paths written.
  std::string write(const std::string& directory, std::vector<std::string>* files = nullptr) const;

 private:
  Trajectory trajectory_;
  std::vector<PoseFlag> flags_;
};

}  // namespace semantic_edge_vo
