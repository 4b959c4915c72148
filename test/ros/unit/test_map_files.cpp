#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <unistd.h>

#include "semantic_edge_vo/ros/map_files.h"

namespace semantic_edge_vo {
namespace {

namespace fs = std::filesystem;

/// The Mapping nodelet's layout: x, y, z, label, rgb (packed b, g, r, a).
sensor_msgs::PointCloud2 twoPointMap() {
  sensor_msgs::PointCloud2 cloud;
  sensor_msgs::PointCloud2Modifier modifier(cloud);
  modifier.setPointCloud2Fields(5, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z", 1,
                                sensor_msgs::PointField::FLOAT32, "label", 1, sensor_msgs::PointField::UINT32, "rgb", 1,
                                sensor_msgs::PointField::FLOAT32);
  modifier.resize(2);
  sensor_msgs::PointCloud2Iterator<float> x(cloud, "x");
  sensor_msgs::PointCloud2Iterator<std::uint32_t> label(cloud, "label");
  sensor_msgs::PointCloud2Iterator<std::uint8_t> rgb(cloud, "rgb");
  const float positions[2][3] = {{1.5f, -2.0f, 0.25f}, {10.0f, 3.0f, -1.0f}};
  for (int i = 0; i < 2; ++i, ++x, ++label, ++rgb) {
    x[0] = positions[i][0];
    x[1] = positions[i][1];
    x[2] = positions[i][2];
    *label = static_cast<std::uint32_t>(i);
    rgb[0] = 30;   // b
    rgb[1] = 20;   // g
    rgb[2] = 200;  // r
    rgb[3] = 255;
  }
  return cloud;
}

std::vector<std::string> linesOf(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(MapFiles, PcdAndPlyHoldEveryPointWithItsLabelAndColour) {
  const fs::path dir = fs::temp_directory_path() / ("sevo_map_files_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::vector<std::string> files;
  ASSERT_EQ(writeMapFiles(twoPointMap(), {"road", "building"}, dir.string(), &files), "");
  ASSERT_EQ(files.size(), 2u);

  const std::vector<std::string> pcd = linesOf(dir / "semantic_edge_map.pcd");
  ASSERT_EQ(pcd.size(), 14u);  // 2 comments, 10 header lines, 2 points
  EXPECT_EQ(pcd[1], "# labels: 0=road 1=building");
  EXPECT_EQ(pcd[2], "VERSION 0.7");
  EXPECT_EQ(pcd[3], "FIELDS x y z label rgb");
  EXPECT_EQ(pcd[11], "DATA ascii");
  std::istringstream first(pcd[12]);
  float x, y, z, rgb;
  std::uint32_t label;
  first >> x >> y >> z >> label >> rgb;
  EXPECT_FLOAT_EQ(x, 1.5f);
  EXPECT_FLOAT_EQ(y, -2.0f);
  EXPECT_EQ(label, 0u);
  std::uint32_t packed;
  std::memcpy(&packed, &rgb, sizeof(packed));
  EXPECT_EQ(packed, (200u << 16) | (20u << 8) | 30u) << "PCL's packed rgb";

  const std::vector<std::string> ply = linesOf(dir / "semantic_edge_map.ply");
  ASSERT_EQ(ply.size(), 15u);  // 13 header lines, 2 points
  EXPECT_EQ(ply[3], "comment labels: 0=road 1=building");
  EXPECT_EQ(ply[4], "element vertex 2");
  EXPECT_EQ(ply[14], "10 3 -1 200 20 30 1");
  fs::remove_all(dir);
}

TEST(MapFiles, TheServiceSaysWhyNothingWasWritten) {
  SaveFiles::Request request;
  request.directory = "/proc/no_such_place/map";
  SaveFiles::Response response;
  serveSaveFiles(request, &response, [](const std::string&, std::vector<std::string>*) { return std::string(); });
  EXPECT_FALSE(response.success);
  EXPECT_NE(response.message.find("cannot create /proc/no_such_place/map"), std::string::npos) << response.message;
}

}  // namespace
}  // namespace semantic_edge_vo
