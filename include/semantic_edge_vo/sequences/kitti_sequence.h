#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"

namespace semantic_edge_vo {

/// A KITTI odometry sequence folder: `calib.txt` (rows `P0:` ... `P3:`, 12 numbers each, the
/// row-major 3x4 projection of each rectified camera), `times.txt` (seconds, one line per frame) and
/// `image_<camera>/%06d.png`. The synthetic sequences use the same layout.
struct KittiSequence {
  std::string directory;
  int camera = 0;                            ///< 0: left grayscale, 2: left colour
  Eigen::Matrix<double, 3, 4> projection;    ///< row P<camera> of calib.txt, pixels
  std::vector<double> times;                 ///< s, one per frame

  std::size_t size() const { return times.size(); }
  /// `directory/image_<camera>/%06d.png`.
  std::string imagePath(std::size_t frame) const;
  /// The rectified pinhole camera of the projection (K = its left 3x3) at the images' size.
  PinholeCamera pinhole(int width, int height) const;
  /// Pose of this camera in camera 0's optical frame: a pure translation, -K^-1 times the
  /// projection's fourth column (identity for camera 0).
  Eigen::Isometry3d T_cam0_cam() const;
};

/// Reads row `P<camera>:` of a KITTI calib.txt and checks it is a rectified projection
/// (K upper triangular with zero skew, positive focal lengths, third row 0 0 1 t). Returns "" or
/// "<path>[:<line>]: what is wrong".
std::string readKittiProjection(const std::string& path, int camera, Eigen::Matrix<double, 3, 4>* projection);

/// Reads calib.txt and times.txt of `directory` and checks that image_<camera>/ exists (camera 0 or
/// 2). Returns "" or what is wrong, naming the file (and line).
std::string openKittiSequence(const std::string& directory, int camera, KittiSequence* sequence);

/// `folder/%06d.png`, the KITTI name of frame `frame`.
std::string kittiFramePath(const std::string& folder, std::size_t frame);

/// Reads one image of camera `camera`: 8-bit grayscale (camera 0, CV_8UC1) or BGR (camera 2,
/// CV_8UC3). Returns "" or what is wrong, naming the file.
std::string readKittiImage(const std::string& path, int camera, cv::Mat* image);

}  // namespace semantic_edge_vo
