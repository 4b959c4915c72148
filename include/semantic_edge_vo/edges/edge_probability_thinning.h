#pragma once
#include <string>

#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/edge_set.h"

namespace semantic_edge_vo {

struct EdgeThinningOptions {
  double threshold = 0.3;    ///< edge probability below which there is no edge, [0, 1]
  double blur_sigma = 1.0;   ///< Gaussian smoothing of the probability map before the ridge test, px (0: none)
  int border = 2;            ///< pixels at the image border that never hold edges

  std::string validate() const;
};

/// Thins a learned edge probability map (HED, SE, or the maximum of per-class CASENet/SEAL maps):
/// non-maximum suppression across the ridge, whose normal is the Hessian eigenvector of the most
/// negative eigenvalue of the smoothed map; subpixel peak by a parabola along that normal. Normals
/// are turned to point dark to bright in `gray` (the EdgeSet convention). Only pixels above the
/// threshold are examined, so the cost is one blur plus work proportional to the edge area.
/// @param[in] probability CV_32FC1 edge probability in [0, 1], same size as `gray`
/// @param[in] gray CV_8UC1 image the map belongs to
/// @return edges with strength = probability at the pixel and class_mask 0 (the caller assigns classes)
EdgeSet thinEdgeProbability(const cv::Mat& probability, const cv::Mat& gray, const EdgeThinningOptions& options);

}  // namespace semantic_edge_vo
