#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/edges/segmenter.h"

namespace semantic_edge_vo {
namespace {

const std::string kModel = std::string(SEVO_SHARED_DIR) + "/models/enet_cityscapes/model-best.opencv.net";
const std::string kColorFrame = std::string(SEVO_SHARED_DIR) + "/data/kitti_odometry/color_frames/kitti06-12-color.png";

TEST(Segmenter, ReportsAMissingModelOrBadOptions) {
  SegmenterOptions options;
  options.model_path = "/nonexistent/model.net";
  EXPECT_NE(Segmenter(options, 19).error().find("does not exist"), std::string::npos);
  options.format = "keras";
  EXPECT_NE(Segmenter(options, 19).error().find("format"), std::string::npos);
}

TEST(Segmenter, EnetOnAKittiColourFrame) {
  if (!std::filesystem::exists(kModel) || !std::filesystem::exists(kColorFrame))
    GTEST_SKIP() << "ENet model or KITTI colour frame absent (" << kModel << ", " << kColorFrame << ")";
  SegmenterOptions options;
  options.model_path = kModel;
  const ClassTable classes = ClassTable::cityscapes();
  Segmenter segmenter(options, classes.size());
  ASSERT_TRUE(segmenter.ok()) << segmenter.error();
  const cv::Mat image = cv::imread(kColorFrame, cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());

  cv::Mat probabilities;
  const double ms = segmenter.segment(image, CV_32F, &probabilities);
  std::cout << "ENet " << options.input_width << "x" << options.input_height << " on " << image.cols << "x"
            << image.rows << ": " << ms << " ms\n";
  ASSERT_EQ(probabilities.type(), CV_32FC(19));
  ASSERT_EQ(probabilities.size(), image.size());
  double low, high;
  cv::minMaxLoc(probabilities.reshape(1), &low, &high);
  EXPECT_GE(low, 0.0);
  EXPECT_LE(high, 1.0 + 1e-5);
  // The road in front of the car, bottom centre of the frame.
  const float* p = probabilities.ptr<float>(image.rows - 20) + (image.cols / 2) * 19;
  EXPECT_EQ(std::max_element(p, p + 19) - p, classes.indexOf("road"));
  float sum = 0.0f;
  for (int c = 0; c < 19; ++c) sum += p[c];
  EXPECT_LE(sum, 1.0f + 1e-4f) << "Unlabeled dropped, not redistributed";

  // The 8-bit form written in place into a caller's buffer.
  std::vector<std::uint8_t> buffer(image.total() * 19);
  cv::Mat bytes(image.rows, image.cols, CV_8UC(19), buffer.data());
  segmenter.segment(image, CV_8U, &bytes);
  EXPECT_EQ(bytes.data, buffer.data()) << "written in place";
  EXPECT_NEAR(bytes.ptr<std::uint8_t>(image.rows - 20)[(image.cols / 2) * 19 + classes.indexOf("road")],
              255.0 * p[classes.indexOf("road")], 1.0);
}

TEST(Segmenter, LabelsAreTheMostProbableClassOfTheProbabilities) {
  if (!std::filesystem::exists(kModel) || !std::filesystem::exists(kColorFrame))
    GTEST_SKIP() << "ENet model or KITTI colour frame absent (" << kModel << ", " << kColorFrame << ")";
  SegmenterOptions options;
  options.model_path = kModel;
  Segmenter segmenter(options, 19);
  ASSERT_TRUE(segmenter.ok()) << segmenter.error();
  const cv::Mat image = cv::imread(kColorFrame, cv::IMREAD_COLOR);
  cv::Mat probabilities, labels;
  segmenter.segment(image, CV_32F, &probabilities);
  const double ms = segmenter.segmentLabels(image, &labels);
  std::cout << "ENet labels: " << ms << " ms\n";
  ASSERT_EQ(labels.type(), CV_8UC2);
  ASSERT_EQ(labels.size(), image.size());
  // Away from class boundaries (the two upsamplings put them a pixel apart) the label is the most
  // probable class of the interpolated probabilities, and its confidence about that class's
  // probability (nearest against bilinear interpolation).
  const auto bestAt = [&](int x, int y) {
    const float* p = probabilities.ptr<float>(y) + x * 19;
    return static_cast<int>(std::max_element(p, p + 19) - p);
  };
  int same = 0, compared = 0;
  double confidence_error = 0.0;
  for (int y = 3; y < image.rows - 3; y += 7)
    for (int x = 3; x < image.cols - 3; x += 7) {
      const int best = bestAt(x, y);
      if (bestAt(x - 3, y - 3) != best || bestAt(x + 3, y - 3) != best || bestAt(x - 3, y + 3) != best || bestAt(x + 3, y + 3) != best)
        continue;
      const cv::Vec2b label = labels.at<cv::Vec2b>(y, x);
      ++compared;
      same += label[0] == best;
      confidence_error += std::abs(label[1] - 255.0 * probabilities.ptr<float>(y)[x * 19 + best]);
    }
  ASSERT_GT(compared, 1000);
  std::cout << "labels agree at " << same << " of " << compared << " pixels away from boundaries; confidence off by "
            << confidence_error / compared << " / 255 on average\n";
  EXPECT_LT(confidence_error / compared, 8.0);
  EXPECT_GT(static_cast<double>(same) / compared, 0.99);
}

TEST(Segmenter, ABackendThisOpenCvLacksFallsBackToTheCpuAndSaysSo) {
  if (!std::filesystem::exists(kModel) || !std::filesystem::exists(kColorFrame))
    GTEST_SKIP() << "ENet model or KITTI colour frame absent (" << kModel << ", " << kColorFrame << ")";
  SegmenterOptions options;
  options.model_path = kModel;
  options.backend = "gpu";
  EXPECT_NE(Segmenter(options, 19).error().find("backend"), std::string::npos);
  const cv::Mat image = cv::imread(kColorFrame, cv::IMREAD_COLOR);
  for (const char* backend : {"cuda", "opencl"}) {
    options.backend = backend;
    Segmenter segmenter(options, 19);
    ASSERT_TRUE(segmenter.ok()) << segmenter.error();
    std::cout << "backend " << backend << ": runs on " << segmenter.device() << (segmenter.notice().empty() ? "" : " (" + segmenter.notice() + ")") << "\n";
    // Either the device asked for, or the CPU with a notice naming the backend.
    if (segmenter.device() == "cpu") EXPECT_NE(segmenter.notice().find(backend), std::string::npos);
    else EXPECT_EQ(segmenter.device(), backend);
    cv::Mat labels;
    segmenter.segmentLabels(image, &labels);
    EXPECT_EQ(labels.at<cv::Vec2b>(image.rows - 20, image.cols / 2)[0], ClassTable::cityscapes().indexOf("road"));
  }
}

}  // namespace
}  // namespace semantic_edge_vo
