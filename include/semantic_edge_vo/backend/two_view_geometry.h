#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/types.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/frontend/forward_motion_prior.h"

namespace semantic_edge_vo {

/// The motion between two views up to scale, from pixel correspondences.
struct TwoViewMotion {
  Eigen::Matrix3d R_second_first = Eigen::Matrix3d::Identity();  ///< maps first-view directions into the second view
  Eigen::Vector3d t_second_first = Eigen::Vector3d::UnitZ();     ///< unit: x_second ~ R x_first + t
  std::vector<std::uint8_t> inliers;  ///< per correspondence, 1: consistent with the motion (and in front of both views)
  int inlier_count = 0;
};

/// Essential matrix (RANSAC, `threshold` px) of the correspondences first[i] <-> second[i] and the
/// motion it implies (the decomposition with the points in front of both views). False when the
/// essential matrix is degenerate or fewer than `min_inliers` correspondences agree with the motion.
bool estimateTwoViewMotion(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second,
                           const PinholeCamera& camera, double threshold, int min_inliers, TwoViewMotion* motion);

/// The motion of a camera on a vehicle, which travels along `forward.chord` of its rotation (no side
/// slip), forward or in reverse: only the rotation is fitted, to the Sampson errors of all
/// correspondences (Huber at `threshold` px, Gauss-Newton from `R_second_first_guess`, steps kept
/// while they lower the cost), then the sign of the travel that puts more agreeing correspondences
/// in front of both views. Parallel traffic moves along the same direction and fits it too; distant
/// corners cannot trade a yaw error for sideways travel. Inliers: within `threshold` px (in front of
/// both views or not: a distant corner's depth sign is noise). False when fewer than `min_inliers`.
bool estimateVehicleMotion(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second,
                           const PinholeCamera& camera, const ForwardMotionOptions& forward, double threshold, int min_inliers,
                           const Eigen::Matrix3d& R_second_first_guess, TwoViewMotion* motion);

}  // namespace semantic_edge_vo
