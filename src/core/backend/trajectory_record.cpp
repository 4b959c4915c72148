#include "semantic_edge_vo/backend/trajectory_record.h"

namespace semantic_edge_vo {

void TrajectoryRecord::add(const FramePose& pose, double stamp) {
  trajectory_.poses.push_back(pose.T_world_cam);
  trajectory_.stamps.push_back(stamp);
  flags_.push_back({stamp, pose.trusted, toString(pose.state)});
}

void TrajectoryRecord::clear() {
  trajectory_ = Trajectory();
  flags_.clear();
}

std::string TrajectoryRecord::write(const std::string& directory, std::vector<std::string>* files) const {
  const std::string kitti = directory + "/poses_kitti.txt", tum = directory + "/poses_tum.txt", flags = directory + "/poses_flags.txt";
  for (const std::string& error : {writeKittiPoses(kitti, trajectory_), writeTumTrajectory(tum, trajectory_), writePoseFlags(flags, flags_)})
    if (!error.empty()) return error;
  if (files) files->insert(files->end(), {kitti, tum, flags});
  return "";
}

}  // namespace semantic_edge_vo
