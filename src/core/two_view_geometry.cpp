#include "semantic_edge_vo/two_view_geometry.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace semantic_edge_vo {

bool estimateTwoViewMotion(const std::vector<cv::Point2f>& first, const std::vector<cv::Point2f>& second,
                           const PinholeCamera& camera, double threshold, int min_inliers, TwoViewMotion* motion) {
  if (static_cast<int>(first.size()) < std::max(min_inliers, 5)) return false;
  const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
  cv::Mat inliers;
  const cv::Mat E = cv::findEssentialMat(first, second, K, cv::RANSAC, 0.999, threshold, inliers);
  if (E.rows != 3 || E.cols != 3) return false;  // degenerate (several solutions stacked, or none)
  cv::Mat R, t;
  motion->inlier_count = cv::recoverPose(E, first, second, K, R, t, inliers);
  if (motion->inlier_count < min_inliers) return false;
  cv::cv2eigen(R, motion->R_second_first);
  cv::cv2eigen(t, motion->t_second_first);
  motion->inliers.assign(inliers.begin<std::uint8_t>(), inliers.end<std::uint8_t>());
  return true;
}

}  // namespace semantic_edge_vo
