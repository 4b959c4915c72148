// The core must stay ROS-free: no header under include/semantic_edge_vo/ (outside ros/) may include
// a ROS, PCL or message header.
#include <filesystem>
#include <fstream>
#include <regex>

#include <gtest/gtest.h>

namespace fs = std::filesystem;

TEST(CoreHeaders, IncludeNoRosPclOrMessageHeader) {
  const fs::path root = fs::path(SEVO_SOURCE_DIR) / "include" / "semantic_edge_vo";
  ASSERT_TRUE(fs::is_directory(root)) << root;
  // ROS client libraries, message packages, PCL and the package's own generated messages (CamelCase .h).
  const std::regex forbidden(
      R"(#\s*include\s*[<"](ros/|nodelet/|pluginlib/|rosbag/|tf2|tf2_ros/|cv_bridge/|image_transport/|message_filters/|)"
      R"(pcl/|pcl_ros/|pcl_conversions/|std_msgs/|sensor_msgs/|geometry_msgs/|nav_msgs/|visualization_msgs/|)"
      R"(semantic_edge_vo/[A-Z]))");
  int checked = 0;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), root);
    if (*relative.begin() == "ros") continue;  // the ROS layer's own headers
    std::ifstream file(entry.path());
    std::string line;
    for (int number = 1; std::getline(file, line); ++number)
      EXPECT_FALSE(std::regex_search(line, forbidden)) << entry.path() << ":" << number << ": " << line;
    ++checked;
  }
  EXPECT_GT(checked, 5) << "expected the core headers under " << root;
}
