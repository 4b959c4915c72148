// scripts/live_latency.py, the analysis of scripts/benchmark_live, on bags written here with known
// receipt times: a graph that keeps up, one that falls behind by a known time a frame, one that
// drops a frame.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <sensor_msgs/CameraInfo.h>

namespace {
namespace fs = std::filesystem;

constexpr int kFrames = 30;
constexpr double kPeriod = 0.1;  // s between frames, in the stamps and (at rate 1) in receipt times

/// Writes a "recorded" bag: frame i's camera_info received at 100 + i * period, its pose
/// `latency(i)` s later (none where latency < 0).
template <typename Latency>
void writeRecording(const fs::path& path, Latency latency) {
  rosbag::Bag bag(path.string(), rosbag::bagmode::Write);
  for (int i = 0; i < kFrames; ++i) {
    const ros::Time stamp(1600000000.0 + i * kPeriod), played(100.0 + i * kPeriod);
    sensor_msgs::CameraInfo info;
    info.header.stamp = stamp;
    bag.write("/camera/camera_info", played, info);
    const double lag = latency(i);
    if (lag < 0.0) continue;
    nav_msgs::Odometry odometry;
    odometry.header.stamp = stamp;
    bag.write("/odometry", played + ros::Duration(lag), odometry);
  }
}

/// Runs the script on `bag` (rate 1, steady state from frame 5) and returns its JSON output.
std::string analyse(const fs::path& bag) {
  const fs::path json = fs::path(bag).replace_extension(".json");
  const std::string command = "/usr/bin/python3 " + std::string(SEVO_SOURCE_DIR) + "/scripts/live_latency.py " + bag.string() +
                              " --rate 1 --skip 5 --json " + json.string() + " > /dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream file(json);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The number after "key": in the JSON text (enough for the flat figures checked here).
double number(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\":");
  if (at == std::string::npos) return -1e9;
  return std::stod(json.substr(at + key.size() + 3));
}
bool flag(const std::string& json, const std::string& key) { return json.find("\"" + key + "\": true") != std::string::npos; }

class LiveLatency : public ::testing::Test {
 protected:
  fs::path bag(const std::string& name) const {
    return fs::temp_directory_path() / ("sevo_live_latency_" + name + "_" + std::to_string(::getpid()) + ".bag");
  }
  void TearDown() override {
    for (const char* name : {"steady", "behind", "dropped"})
      for (const char* extension : {".bag", ".json"}) fs::remove(fs::path(bag(name)).replace_extension(extension));
  }
};

TEST_F(LiveLatency, ASteadyLatencyKeepsUp) {
  writeRecording(bag("steady"), [](int i) { return 0.08 + (i % 3 == 0 ? 0.05 : 0.0); });  // keyframes cost more
  const std::string json = analyse(bag("steady"));
  EXPECT_EQ(number(json, "poses"), kFrames) << json;
  EXPECT_EQ(number(json, "frames_without_pose"), 0) << json;
  EXPECT_NEAR(number(json, "played_hz"), 10.0, 1e-6) << json;
  EXPECT_NEAR(number(json, "latency_median_ms"), 80.0, 1e-3) << json;
  EXPECT_NEAR(number(json, "latency_trend_ms_per_frame"), 0.0, 1.0) << json;
  EXPECT_TRUE(flag(json, "keeps_up")) << json;
  EXPECT_NE(json.find("\"sustained_hz\": null"), std::string::npos) << json;
}

TEST_F(LiveLatency, AGrowingLatencyFallsBehindAtTheRateItSustains) {
  writeRecording(bag("behind"), [](int i) { return 0.08 + 0.025 * i; });  // 25 ms behind each frame
  const std::string json = analyse(bag("behind"));
  EXPECT_EQ(number(json, "frames_without_pose"), 0) << json;
  EXPECT_NEAR(number(json, "latency_trend_ms_per_frame"), 25.0, 1e-3) << json;
  EXPECT_NEAR(number(json, "sustained_hz"), 1000.0 / 125.0, 1e-3) << json;  // 100 ms + 25 ms a frame
  EXPECT_FALSE(flag(json, "keeps_up")) << json;
}

TEST_F(LiveLatency, AFrameWithoutAPoseIsNotKeepingUp) {
  writeRecording(bag("dropped"), [](int i) { return i == 20 ? -1.0 : 0.08; });
  const std::string json = analyse(bag("dropped"));
  EXPECT_EQ(number(json, "poses"), kFrames - 1) << json;
  EXPECT_EQ(number(json, "frames_without_pose"), 1) << json;
  EXPECT_FALSE(flag(json, "keeps_up")) << json;
  EXPECT_NE(json.find("\"sustained_hz\": null"), std::string::npos) << "no trend, so no sustained rate: " << json;
}

}  // namespace
