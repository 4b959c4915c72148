// The KITTI-style folder of a synthetic sequence and its compact channel formats.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/synthetic/sequence_directory_writer.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"

namespace semantic_edge_vo {
namespace synthetic {
namespace {

namespace fs = std::filesystem;

TEST(SyntheticOutput, DepthAndMasksSurviveTheirPngFormats) {
  cv::Mat depth(4, 5, CV_32FC1);
  cv::randu(depth, 0.5, 250.0);
  depth.at<float>(0, 0) = 0.0f;     // sky
  depth.at<float>(1, 1) = 300.0f;   // beyond the encodable range
  std::vector<std::uint8_t> png;
  cv::imencode(".png", encodeDepth(depth), png);
  const cv::Mat decoded = decodeDepth(cv::imdecode(png, cv::IMREAD_UNCHANGED));
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 5; ++x) {
      const float truth = depth.at<float>(y, x);
      const float expected = truth > kMaxEncodedDepth ? 0.0f : truth;
      EXPECT_NEAR(decoded.at<float>(y, x), expected, 0.5 / kDepthScale + 1e-6);
    }
  SemanticNetworkOutput semantics;
  semantics.edge_classes.create(3, 3, CV_32SC1);
  cv::randu(semantics.edge_classes, 0, 1 << 19);
  semantics.edge_classes.at<std::int32_t>(2, 2) = (1 << 18) | 1;
  semantics.edge_strength.create(3, 3, CV_8UC1);
  cv::randu(semantics.edge_strength, 0, 256);
  png = encodePng(packEdgeBitmask(semantics));
  cv::Mat strength, classes;
  unpackEdgeBitmask(cv::imdecode(png, cv::IMREAD_UNCHANGED), &strength, &classes);
  EXPECT_EQ(cv::norm(classes, semantics.edge_classes, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(strength, semantics.edge_strength, cv::NORM_INF), 0.0);
}

TEST(SyntheticOutput, WritesTheKittiLayout) {
  const fs::path directory = fs::temp_directory_path() / ("sevo_synthetic_" + std::to_string(::getpid()));
  SyntheticSequenceOptions options = SyntheticSequenceOptions::forScene(SceneType::kHighway, 2);
  options.camera = kittiCamera().scaled(0.25);
  SyntheticSequence sequence(options);
  {
    SequenceDirectoryWriter writer(directory.string(), options, 3);
    ASSERT_EQ(writer.error(), "");
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(writer.write(sequence.frame(i))) << writer.error();
  }
  for (const char* folder :
       {"image_0", "image_2", "depth", "semantic", "semantic_rgb", "dynamic", "edge_bitmask", "class_probability"})
    EXPECT_TRUE(fs::exists(directory / folder / "000002.png")) << folder;
  const cv::Mat gray = cv::imread((directory / "image_0" / "000001.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(gray.type(), CV_8UC1);
  EXPECT_EQ(gray.cols, options.camera.width);

  std::ifstream calib(directory / "calib.txt");
  std::string name;
  double p[12];
  calib >> name;
  for (double& value : p) calib >> value;
  EXPECT_EQ(name, "P0:");
  EXPECT_NEAR(p[0], options.camera.fx, 1e-9);
  EXPECT_NEAR(p[2], options.camera.cx, 1e-9);
  EXPECT_NEAR(p[6], options.camera.cy, 1e-9);

  std::ifstream poses(directory / "poses.txt");
  std::string line;
  int lines = 0;
  while (std::getline(poses, line)) {
    std::istringstream numbers(line);
    Eigen::Matrix<double, 3, 4> pose;
    int count = 0;
    for (double value; numbers >> value; ++count) pose(count / 4, count % 4) = value;
    ASSERT_EQ(count, 12);
    EXPECT_TRUE(pose.isApprox(sequence.pose(lines).matrix().topRows<3>(), 1e-8));
    ++lines;
  }
  EXPECT_EQ(lines, 3);
  std::ifstream times(directory / "times.txt");
  double t0 = -1, t1 = -1;
  times >> t0 >> t1;
  EXPECT_DOUBLE_EQ(t0, 0.0);
  EXPECT_NEAR(t1, 0.1, 1e-9);
  fs::remove_all(directory);
}

}  // namespace
}  // namespace synthetic
}  // namespace semantic_edge_vo
