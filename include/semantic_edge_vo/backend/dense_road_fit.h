#pragma once
#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/road_plane.h"
#include "semantic_edge_vo/frontend/image_pyramid.h"

namespace semantic_edge_vo {

/// The road plane under a frame from its image and a neighbouring frame's: the pixels of the lane ahead
/// (RoadPlaneFinder::inLaneAhead) are carried into the other image by the plane's homography, and
/// the plane (its normal over its height, 3 parameters) and an affine brightness change are fitted
/// to their intensities, Huber-weighted Gauss-Newton from a search over heights at the coarsest
/// level, coarse to fine. Dense road texture measures the plane where the map's few points on the
/// road scatter (fast driving, a fresh map). Scale-free: the height comes out in the units of the
/// two images' relative translation.
class DenseRoadFitter {
 public:
  DenseRoadFitter(const RoadScaleOptions& options, const PinholeCamera& camera) : options_(options), finder_(options, camera) {}

  /// @param[in] reference the frame whose road plane is wanted (its optical frame)
  /// @param[in] other a neighbouring frame's pyramid (the odometry: the frame mapped before)
  /// @param[in] T_other_reference maps the reference's points into the other's optical frame
  /// @param[in] height_guess the plane's height to search around (map units; > 0)
  RoadFit fit(const ImagePyramid& reference, const ImagePyramid& other, const Eigen::Isometry3d& T_other_reference,
              double height_guess) const;

 private:
  RoadScaleOptions options_;
  RoadPlaneFinder finder_;
};

}  // namespace semantic_edge_vo
