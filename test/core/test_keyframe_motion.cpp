// Corner tracks and the two-view motion they measure between keyframes.
#include <gtest/gtest.h>

#include <random>

#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/corner_tracks.h"
#include "semantic_edge_vo/two_view_geometry.h"

namespace semantic_edge_vo {
namespace {

double degrees(double radians) { return radians * 180.0 / M_PI; }

TEST(TwoViewMotion, RecoversRotationAndDirectionDespiteOutliers) {
  const PinholeCamera camera = kittiCamera();
  // Forward travel 3 degrees to the right of the axis, with a 1 degree turn: a car on a bend.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d centre = 1.5 * Eigen::Vector3d(std::sin(3.0 * M_PI / 180.0), 0.0, std::cos(3.0 * M_PI / 180.0));
  const Eigen::Vector3d t = -R * centre;  // x_second = R x_first + t
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(0.0, camera.width), v(0.0, camera.height), depth(5.0, 60.0);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<cv::Point2f> first, second;
  std::vector<bool> outlier;
  while (first.size() < 300) {
    const Eigen::Vector3d p = camera.backProject(u(random), v(random), depth(random));
    const Eigen::Vector3d q = R * p + t;
    const Eigen::Vector2d a = camera.project(p), b = camera.project(q);
    if (q.z() <= 0.0 || !camera.contains(b.x(), b.y())) continue;
    // A fifth of the tracks slid 8 px across their epipolar line (along it, no two views can tell).
    const bool wrong = first.size() % 5 == 0;
    const Eigen::Vector2d along = (b - camera.project(-t)).normalized();
    const Eigen::Vector2d slid = b + (wrong ? 8.0 : 0.0) * Eigen::Vector2d(-along.y(), along.x());
    first.emplace_back(static_cast<float>(a.x()), static_cast<float>(a.y()));
    second.emplace_back(static_cast<float>(slid.x() + noise(random)), static_cast<float>(slid.y() + noise(random)));
    outlier.push_back(wrong);
  }
  TwoViewMotion motion;
  ASSERT_TRUE(estimateTwoViewMotion(first, second, camera, 0.5, 50, &motion));
  EXPECT_LT(degrees(Eigen::AngleAxisd(motion.R_second_first.transpose() * R).angle()), 0.05);
  EXPECT_LT(degrees(std::acos(std::min(1.0, motion.t_second_first.dot(t.normalized())))), 0.5);
  int outliers_kept = 0;
  for (std::size_t i = 0; i < outlier.size(); ++i) outliers_kept += outlier[i] && motion.inliers[i];
  EXPECT_EQ(outliers_kept, 0);
  EXPECT_GE(motion.inlier_count, 200);
  // Too few agreeing correspondences: no motion.
  EXPECT_FALSE(estimateTwoViewMotion(first, second, camera, 0.5, 290, &motion));
}

TEST(CornerTracks, FollowsAShiftedImageAndStartsAtCorners) {
  cv::Mat texture(240, 320, CV_8UC1);
  cv::RNG(3).fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 2.0);
  cv::normalize(texture, texture, 0, 255, cv::NORM_MINMAX);
  const cv::Point2f shift(3.5f, -2.25f);
  const cv::Mat to = (cv::Mat_<double>(2, 3) << 1, 0, shift.x, 0, 1, shift.y);
  cv::Mat moved;
  cv::warpAffine(texture, moved, to, texture.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);

  const std::vector<cv::Point2f> corners = detectCorners(texture, 100, 10.0);
  ASSERT_GE(corners.size(), 50u);
  for (const cv::Point2f& corner : corners) {
    EXPECT_TRUE(corner.x >= 0 && corner.y >= 0 && corner.x < texture.cols && corner.y < texture.rows);
  }
  CornerTracks tracks(15);
  tracks.reset(texture, corners);
  const std::size_t kept = tracks.track(moved);
  EXPECT_GE(kept, corners.size() * 8 / 10);  // only those near the border may go
  EXPECT_EQ(tracks.framesTracked(), 1);
  const cv::Rect interior(20, 20, texture.cols - 40, texture.rows - 40);  // the warp reflects at the border
  for (std::size_t i = 0; i < kept; ++i) {
    EXPECT_EQ(tracks.first()[i], corners[static_cast<std::size_t>(tracks.ids()[i])]);
    if (!interior.contains(tracks.first()[i])) continue;
    EXPECT_LT(cv::norm(tracks.current()[i] - tracks.first()[i] - shift), 0.1) << "track " << i;
  }
  tracks.reset(texture, {});
  EXPECT_EQ(tracks.track(moved), 0u);  // nothing to follow, and no throw
}

}  // namespace
}  // namespace semantic_edge_vo
