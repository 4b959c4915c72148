#include "semantic_edge_vo/ros/map_files.h"

#include <cstring>
#include <filesystem>
#include <fstream>

#include <sensor_msgs/point_cloud2_iterator.h>

namespace semantic_edge_vo {
namespace {

struct MapPoint3 {
  float x, y, z;
  std::uint32_t label;
  std::uint8_t r, g, b;
};

std::vector<MapPoint3> pointsOf(const sensor_msgs::PointCloud2& cloud) {
  std::vector<MapPoint3> points;
  points.reserve(static_cast<std::size_t>(cloud.width) * cloud.height);
  if (cloud.data.empty()) return points;
  sensor_msgs::PointCloud2ConstIterator<float> x(cloud, "x");
  sensor_msgs::PointCloud2ConstIterator<std::uint32_t> label(cloud, "label");
  sensor_msgs::PointCloud2ConstIterator<std::uint8_t> rgb(cloud, "rgb");  // packed b, g, r, a bytes
  for (; x != x.end(); ++x, ++label, ++rgb) points.push_back({x[0], x[1], x[2], *label, rgb[2], rgb[1], rgb[0]});
  return points;
}

std::string classComment(const char* prefix, const std::vector<std::string>& class_names) {
  std::string text = std::string(prefix) + " labels:";
  for (std::size_t i = 0; i < class_names.size(); ++i) text += " " + std::to_string(i) + "=" + class_names[i];
  return text + "\n";
}

std::string writePcd(const std::string& path, const std::vector<MapPoint3>& points, const std::vector<std::string>& class_names) {
  std::ofstream out(path);
  out << "# .PCD v0.7 - semantic edge map of semantic_edge_vo (odom frame)\n"
      << classComment("#", class_names) << "VERSION 0.7\nFIELDS x y z label rgb\nSIZE 4 4 4 4 4\nTYPE F F F U F\nCOUNT 1 1 1 1 1\n"
      << "WIDTH " << points.size() << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << points.size() << "\nDATA ascii\n";
  for (const MapPoint3& p : points) {
    // PCL's rgb: the packed 0x00RRGGBB bits read as a float, written with all its digits.
    const std::uint32_t packed = (static_cast<std::uint32_t>(p.r) << 16) | (static_cast<std::uint32_t>(p.g) << 8) | p.b;
    float rgb = 0.0f;
    std::memcpy(&rgb, &packed, sizeof(rgb));
    char line[128];
    std::snprintf(line, sizeof(line), "%.6g %.6g %.6g %u %.9g\n", p.x, p.y, p.z, p.label, static_cast<double>(rgb));
    out << line;
  }
  out.flush();
  return out ? "" : "cannot write " + path;
}

std::string writePly(const std::string& path, const std::vector<MapPoint3>& points, const std::vector<std::string>& class_names) {
  std::ofstream out(path);
  out << "ply\nformat ascii 1.0\ncomment semantic edge map of semantic_edge_vo (odom frame)\n" << classComment("comment", class_names)
      << "element vertex " << points.size() << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uint label\nend_header\n";
  for (const MapPoint3& p : points) {
    char line[128];
    std::snprintf(line, sizeof(line), "%.6g %.6g %.6g %u %u %u %u\n", p.x, p.y, p.z, p.r, p.g, p.b, p.label);
    out << line;
  }
  out.flush();
  return out ? "" : "cannot write " + path;
}

}  // namespace

std::string writeMapFiles(const sensor_msgs::PointCloud2& cloud, const std::vector<std::string>& class_names,
                          const std::string& directory, std::vector<std::string>* files) {
  const std::vector<MapPoint3> points = pointsOf(cloud);
  for (const auto& [name, write] : {std::make_pair(std::string("semantic_edge_map.pcd"), &writePcd),
                                    std::make_pair(std::string("semantic_edge_map.ply"), &writePly)}) {
    const std::string path = directory + "/" + name;
    if (const std::string error = write(path, points, class_names); !error.empty()) return error;
    files->push_back(path);
  }
  return "";
}

bool serveSaveFiles(const SaveFiles::Request& request, SaveFiles::Response* response,
                    const std::function<std::string(const std::string& directory, std::vector<std::string>* files)>& write) {
  std::error_code failure;
  const std::string directory = request.directory.empty() ? "." : request.directory;
  std::filesystem::create_directories(directory, failure);
  std::string error = failure ? "cannot create " + directory + ": " + failure.message() : "";
  if (error.empty()) error = write(std::filesystem::absolute(directory).string(), &response->files);
  response->success = error.empty();
  response->message = error.empty() ? "wrote " + std::to_string(response->files.size()) + " files into " + directory : error;
  return true;
}

}  // namespace semantic_edge_vo
