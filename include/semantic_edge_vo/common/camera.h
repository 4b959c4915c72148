#pragma once
#include <string>

#include <Eigen/Core>

namespace semantic_edge_vo {

/// Pinhole camera of a rectified image. Pixel centres are at integer coordinates, u right, v down;
/// the optical frame has z forward, x right, y down (REP-103 optical convention).
struct PinholeCamera {
  double fx = 0.0;  ///< focal length along u, pixels
  double fy = 0.0;  ///< focal length along v, pixels
  double cx = 0.0;  ///< principal point column, pixels
  double cy = 0.0;  ///< principal point row, pixels
  int width = 0;    ///< image width, pixels
  int height = 0;   ///< image height, pixels

  /// The camera of a pyramid level with `scale` level pixels per full-resolution pixel.
  PinholeCamera scaled(double scale) const;

  /// Empty when usable, otherwise what is wrong (named, with the offending values).
  std::string validate() const;

  /// Pixel of a point in the optical frame (z > 0 expected).
  Eigen::Vector2d project(const Eigen::Vector3d& point_camera) const {
    return {fx * point_camera.x() / point_camera.z() + cx, fy * point_camera.y() / point_camera.z() + cy};
  }
  /// Point of the optical frame at pixel (u, v) and depth z (metres).
  Eigen::Vector3d backProject(double u, double v, double z) const {
    return {(u - cx) / fx * z, (v - cy) / fy * z, z};
  }
  bool contains(double u, double v, double margin = 0.0) const {
    return u >= margin && v >= margin && u <= width - 1 - margin && v <= height - 1 - margin;
  }
};

/// KITTI odometry geometry (sequence 00-02 camera 0 intrinsics at 1241x376), the synthetic default.
PinholeCamera kittiCamera();

}  // namespace semantic_edge_vo
