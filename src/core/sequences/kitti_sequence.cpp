#include "semantic_edge_vo/sequences/kitti_sequence.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <Eigen/LU>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace fs = std::filesystem;

std::string KittiSequence::imagePath(std::size_t frame) const {
  return kittiFramePath((fs::path(directory) / ("image_" + std::to_string(camera))).string(), frame);
}

PinholeCamera KittiSequence::pinhole(int width, int height) const {
  PinholeCamera pinhole;
  pinhole.fx = projection(0, 0);
  pinhole.fy = projection(1, 1);
  pinhole.cx = projection(0, 2);
  pinhole.cy = projection(1, 2);
  pinhole.width = width;
  pinhole.height = height;
  return pinhole;
}

Eigen::Isometry3d KittiSequence::T_cam0_cam() const {
  // P = K [I | t] with t the origin of camera 0 in this camera's frame.
  const Eigen::Vector3d t = projection.leftCols<3>().inverse() * projection.col(3);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = -t;
  return T;
}

std::string readKittiProjection(const std::string& path, int camera, Eigen::Matrix<double, 3, 4>* projection) {
  std::ifstream file(path);
  if (!file) return path + ": cannot open for reading";
  const std::string key = "P" + std::to_string(camera) + ":";
  std::string line, error;
  std::vector<double> numbers;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    const auto start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line.compare(start, key.size(), key) != 0) continue;
    const std::string where = path + ":" + std::to_string(line_number) + ": " + key + " ";
    if (!parseNumbers(line.substr(start + key.size()), &numbers, &error)) return where + error;
    if (numbers.size() != 12) return where + "expected 12 numbers, found " + std::to_string(numbers.size());
    Eigen::Matrix<double, 3, 4> P;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) P(r, c) = numbers[static_cast<std::size_t>(4 * r + c)];
    const bool rectified = P(0, 0) > 0.0 && P(1, 1) > 0.0 && P(0, 1) == 0.0 && P(1, 0) == 0.0 && P(2, 0) == 0.0 &&
                           P(2, 1) == 0.0 && P(2, 2) == 1.0;
    if (!rectified)
      return where + "not a rectified projection (expected fx 0 cx tx 0 fy cy ty 0 0 1 tz with fx, fy > 0)";
    *projection = P;
    return "";
  }
  if (file.bad()) return path + ": read error";
  return path + ": no " + key + " row";
}

std::string openKittiSequence(const std::string& directory, int camera, KittiSequence* sequence) {
  if (camera != 0 && camera != 2) return "camera " + std::to_string(camera) + ": only 0 (grayscale) and 2 (colour)";
  if (!fs::is_directory(directory)) return directory + ": not a folder";
  KittiSequence result;
  result.directory = directory;
  result.camera = camera;
  const fs::path root(directory);
  std::string error = readKittiProjection((root / "calib.txt").string(), camera, &result.projection);
  if (error.empty()) error = readTimes((root / "times.txt").string(), &result.times);
  if (!error.empty()) return error;
  const fs::path images = root / ("image_" + std::to_string(camera));
  if (!fs::is_directory(images)) return images.string() + ": no such folder";
  *sequence = std::move(result);
  return "";
}

std::string kittiFramePath(const std::string& folder, std::size_t frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06zu.png", frame);
  return (fs::path(folder) / name).string();
}

std::string readKittiImage(const std::string& path, int camera, cv::Mat* image) {
  if (!fs::exists(path)) return path + ": no such file";
  const cv::Mat read = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (read.empty()) return path + ": not a readable image";
  const int expected = camera == 0 ? 1 : 3;
  if (read.depth() != CV_8U || read.channels() != expected)
    return path + ": expected an 8-bit " + (camera == 0 ? "grayscale" : "colour") + " image, found " +
           std::to_string(read.channels()) + " channel(s) of " + std::to_string(8 * read.elemSize1()) + " bits";
  *image = read;
  return "";
}

}  // namespace semantic_edge_vo
