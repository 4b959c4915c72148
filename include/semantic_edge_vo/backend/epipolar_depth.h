#pragma once
#include <string>

#include <Eigen/Geometry>

#include "semantic_edge_vo/frontend/image_pyramid.h"
#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/fields/shared_class_edge_test.h"

namespace semantic_edge_vo {

struct EpipolarSearchOptions {
  double min_inverse_depth = 0.002;  ///< search range, 1/m (map units)
  double max_inverse_depth = 2.0;
  double sigma_range = 2.5;          ///< search the prior inverse depth +- this many sigmas
  double min_epipolar_length = 1.5;  ///< px; shorter: the frame adds no depth information
  double max_epipolar_length = 120.0;
  double max_pattern_error = 12.0;   ///< rms of the zero-mean 8-pixel intensity pattern at the best match, gray levels
  double min_gradient_alignment = 0.4;  ///< |cos| between the image gradient and the epipolar line, at least
  double min_second_best_ratio = 1.3;  ///< second-best error over best error (a unique match)
  double edge_radius = 1.5;          ///< edge points: a candidate needs an edge of a shared class this near, px
  double pixel_sigma = 0.7;          ///< uncertainty of the matched position along the line, px

  std::string validate() const;
};

/// A depth measurement of a host point in another frame.
struct DepthMeasurement {
  double inverse_depth = 0.0;   ///< 1/m
  double variance = 0.0;        ///< 1/m^2
};

/// Searches a host keyframe point along its epipolar line in a target frame (zero-mean intensity
/// pattern warped by the candidate depth, as DSO's immature points do; only where the image gradient
/// crosses the line; edge points only where `target_edges`, when given, finds an edge of a class the
/// point has, or any edge where no position on the line has one of its classes; built with
/// options.edge_radius from the target's field) and returns the inverse depth of the best,
/// unique match with its variance. The point needs a prior (inverse_depth > 0 with its variance) that
/// bounds the search. False when the frame adds no information or no unique match.
bool searchEpipolar(const MapPoint& point, const PyramidLevel& host, const PyramidLevel& target,
                    const SharedClassEdgeTest* target_edges, const Eigen::Isometry3d& T_target_host,
                    const EpipolarSearchOptions& options, DepthMeasurement* measurement);

/// A frame a host's points are searched in, with its pose relative to the host.
struct EpipolarTarget {
  const PyramidLevel* level = nullptr;
  const SharedClassEdgeTest* edges = nullptr;  ///< null: no edge gating
  Eigen::Isometry3d T_target_host = Eigen::Isometry3d::Identity();
};

/// Fuses a measurement into the point's inverse-depth estimate (1-D Kalman filter). The first
/// measurement replaces a propagated prior; one more than 3 sigmas away replaces a single earlier
/// measurement (either may be the outlier) and is refused (false) by two or more agreeing ones.
bool fuseDepth(const DepthMeasurement& measurement, MapPoint* point);

}  // namespace semantic_edge_vo
