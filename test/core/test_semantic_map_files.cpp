#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/sequences/semantic_map_files.h"

namespace semantic_edge_vo {
namespace {

TEST(SemanticMapFiles, ClassLabelsWrittenFromProbabilitiesReadBackAsTheLabelsForm) {
  // Three pixels of four classes: a clear winner, a tie (the lower class wins), all zero.
  cv::Mat probabilities(1, 3, CV_8UC(4), cv::Scalar::all(0));
  std::uint8_t* p = probabilities.ptr<std::uint8_t>(0);
  const std::uint8_t values[12] = {10, 200, 40, 5, /**/ 90, 30, 90, 60, /**/ 0, 0, 0, 0};
  std::copy(values, values + 12, p);
  const std::string path = ::testing::TempDir() + "/labels.png";
  ASSERT_EQ(writeClassLabelsPng(path, probabilities), "");

  cv::Mat labels;
  ASSERT_EQ(readClassLabelsPng(path, &labels), "");
  ASSERT_EQ(labels.type(), CV_8UC2);
  EXPECT_EQ(labels.at<cv::Vec2b>(0, 0), cv::Vec2b(1, 200)) << "most probable class and its probability";
  EXPECT_EQ(labels.at<cv::Vec2b>(0, 1), cv::Vec2b(0, 90)) << "a tie goes to the lower class";
  EXPECT_EQ(labels.at<cv::Vec2b>(0, 2), cv::Vec2b(0, 0));
  std::filesystem::remove(path);
}

TEST(SemanticMapFiles, TheSyntheticFourChannelLayoutStillReads) {
  cv::Mat top_two(2, 2, CV_8UC4, cv::Scalar(13, 240, 0, 10));
  const std::string path = ::testing::TempDir() + "/labels4.png";
  ASSERT_TRUE(cv::imwrite(path, top_two));
  cv::Mat labels;
  ASSERT_EQ(readClassLabelsPng(path, &labels), "");
  ASSERT_EQ(labels.type(), CV_8UC2);
  EXPECT_EQ(labels.at<cv::Vec2b>(1, 1), cv::Vec2b(13, 240));
  std::filesystem::remove(path);
}

TEST(SemanticMapFiles, WritingNeedsEightBitProbabilities) {
  EXPECT_NE(writeClassLabelsPng(::testing::TempDir() + "/float.png", cv::Mat(2, 2, CV_32FC(3), cv::Scalar::all(0.5))), "");
}

}  // namespace
}  // namespace semantic_edge_vo
