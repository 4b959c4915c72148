#pragma once
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/epipolar_depth.h"
#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {

/// A measured inverse depth at a pixel of the keyframe that receives it.
struct DepthSample {
  Eigen::Vector2d pixel;
  double inverse_depth;
};

/// The inverse depths of a keyframe's points: priors from measured points near them, then epipolar
/// searches against other frames fused into each point's filter (edge points only where the other
/// frame has an edge of their classes).
class KeyframeDepths {
 public:
  /// @param neighbour_radius a point takes a prior from the measured points this near, px
  /// @param default_inverse_depth the prior when no point is measured at all (the map's scale)
  KeyframeDepths(const EpipolarSearchOptions& epipolar, const PinholeCamera& camera, double neighbour_radius, double default_inverse_depth)
      : epipolar_(epipolar), camera_(camera), neighbour_radius_(neighbour_radius), default_inverse_depth_(default_inverse_depth) {}

  /// Points without a measurement take the median of the samples within the neighbour radius, or of
  /// all samples, as a prior with a wide variance; the epipolar search then measures them.
  void propagate(const std::vector<DepthSample>& samples, std::vector<MapPoint>* points) const;
  /// The points of a new keyframe (already taken from its frame's candidates): prior depths from the
  /// previous keyframe's measured points, then an epipolar search against the previous keyframe.
  /// @return the scale of the new depths against the map's: the median of the map's inverse depths
  ///         over the measured ones, where both are known (1 when too few are)
  /// @param map_depths if not null, gets the points as the map alone sees them, nothing measured
  ///        anew: each takes the depth and variance of the previous keyframe's measured point that falls
  ///        within 2 px of it (the nearest), as measured; the others have no depth
  double triangulate(Keyframe* keyframe, const Keyframe& previous, std::vector<MapPoint>* map_depths = nullptr) const;
  /// Refines the keyframe's depths with a frame tracked at T_frame_kf. Returns the frame's edge test
  /// (null without a field), which the frame keeps if it becomes a keyframe.
  std::shared_ptr<const SharedClassEdgeTest> refine(Keyframe* keyframe, const OdometryFrame& frame, const Eigen::Isometry3d& T_frame_kf) const;

 private:
  /// Epipolar search of each point of the host in the target, fused into its depth filter.
  void measure(const PyramidLevel& host, const EpipolarTarget& target, std::vector<MapPoint>* points) const;

  EpipolarSearchOptions epipolar_;
  PinholeCamera camera_;
  double neighbour_radius_, default_inverse_depth_;
};

}  // namespace semantic_edge_vo
