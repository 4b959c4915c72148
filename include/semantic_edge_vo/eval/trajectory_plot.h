#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

struct TopDownPlotOptions {
  int width_px = 1000, height_px = 900;
  std::string title = "Trajectory, top-down view";
  std::string gt_label = "ground truth";
  std::string est_label = "estimate";

  std::string validate() const;
};

/// Top-down plot of two trajectories in the x-z plane of the KITTI camera frame (x right, z forward;
/// drawn x to the right, z up): equal aspect, axes with ticks and grid in metres, a legend, a dot at
/// each start. `est` must already be in the ground-truth frame (e.g. Sim(3)-aligned); either may be
/// empty. Returns an 8-bit BGR image.
cv::Mat renderTopDownPlot(const std::vector<Eigen::Vector3d>& gt, const std::vector<Eigen::Vector3d>& est,
                          const TopDownPlotOptions& options);

}  // namespace semantic_edge_vo
