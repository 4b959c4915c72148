#include "semantic_edge_vo/frontend/frame_consistency.h"

#include <sstream>

namespace semantic_edge_vo {

std::string FrameConsistencyOptions::validate() const {
  std::ostringstream error;
  if (!(max_motion_deviation > 0.0)) error << "max_motion_deviation must be > 0 (got " << max_motion_deviation << ")";
  else if (max_untrusted_frames < 0) error << "max_untrusted_frames must be >= 0 (got " << max_untrusted_frames << ")";
  else if (!(max_keyframe_scale_change > 0.0)) error << "max_keyframe_scale_change must be > 0 (got " << max_keyframe_scale_change << ")";
  return error.str();
}

FrameAgreement compareWithRecentFrames(double inlier_ratio, double usual_inlier_ratio, double min_inlier_fraction,
                                       const Eigen::Vector3d& travel, const Eigen::Vector3d& predicted_travel,
                                       double usual_travel, const FrameConsistencyOptions& options) {
  FrameAgreement agreement;
  agreement.inliers_ok = !(usual_inlier_ratio > 0.0) || inlier_ratio >= min_inlier_fraction * usual_inlier_ratio;
  if (usual_travel > 0.0) {
    agreement.motion_deviation = (travel - predicted_travel).norm() / usual_travel;
    agreement.motion_ok = agreement.motion_deviation <= options.max_motion_deviation;
  }
  return agreement;
}

}  // namespace semantic_edge_vo
