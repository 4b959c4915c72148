#include "semantic_edge_vo/robust_statistics.h"
#include "semantic_edge_vo/two_view_initializer.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/video/tracking.hpp>

namespace semantic_edge_vo {
namespace {

const cv::Size kWindow(21, 21);
constexpr int kMaxLevel = 3;

/// KLT's image pyramid with derivatives, built once per frame and used in both directions.
std::vector<cv::Mat> kltPyramid(const cv::Mat& gray) {
  std::vector<cv::Mat> pyramid;
  cv::buildOpticalFlowPyramid(gray, pyramid, kWindow, kMaxLevel, true);
  return pyramid;
}

}  // namespace

std::string InitializerOptions::validate() const {
  std::ostringstream error;
  if (!(min_parallax > 0 && min_parallax < 1)) error << "min_parallax must be in (0, 1) (a fraction of the image width)";
  else if (max_frames < 1 || min_points < 8) error << "need max_frames >= 1 and min_points >= 8";
  else if (!(ransac_threshold > 0 && min_triangulation_angle >= 0 && median_depth > 0))
    error << "ransac_threshold and median_depth must be > 0, min_triangulation_angle >= 0";
  return error.str();
}

void TwoViewInitializer::reset(const cv::Mat& gray, const std::vector<Eigen::Vector2f>& pixels) {
  previous_ = kltPyramid(gray);
  first_.clear();
  alive_.clear();
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    first_.emplace_back(pixels[i].x(), pixels[i].y());
    alive_.push_back(static_cast<int>(i));
  }
  current_ = first_;
  pixel_count_ = pixels.size();
  frames_ = 0;
  inverse_depths_.clear();
}

TwoViewInitializer::Status TwoViewInitializer::add(const cv::Mat& gray) {
  ++frames_;
  // Nothing to follow (a frame without candidates: all of it movable, say); OpenCV's KLT throws on an
  // empty point set.
  if (static_cast<int>(current_.size()) < options_.min_points) return Status::kFailed;
  std::vector<cv::Point2f> next, back;
  std::vector<std::uint8_t> status, back_status;
  std::vector<float> error;
  std::vector<cv::Mat> pyramid = kltPyramid(gray);
  cv::calcOpticalFlowPyrLK(previous_, pyramid, current_, next, status, error, kWindow, kMaxLevel);
  cv::calcOpticalFlowPyrLK(pyramid, previous_, next, back, back_status, error, kWindow, kMaxLevel);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < current_.size(); ++i) {
    const bool inside = next[i].x >= 0 && next[i].y >= 0 && next[i].x < gray.cols && next[i].y < gray.rows;
    if (!status[i] || !back_status[i] || !inside || cv::norm(back[i] - current_[i]) > 0.5) continue;
    first_[kept] = first_[i];
    current_[kept] = next[i];
    alive_[kept] = alive_[i];
    ++kept;
  }
  first_.resize(kept);
  current_.resize(kept);
  alive_.resize(kept);
  previous_ = std::move(pyramid);
  if (static_cast<int>(kept) < options_.min_points) return Status::kFailed;

  std::vector<double> flow;
  for (std::size_t i = 0; i < kept; ++i) flow.push_back(cv::norm(current_[i] - first_[i]));
  const bool last_chance = frames_ >= options_.max_frames;
  if (median(flow) < options_.min_parallax * camera_.width && !last_chance) return Status::kNeedMoreFrames;
  if (solve()) return Status::kReady;
  return last_chance ? Status::kFailed : Status::kNeedMoreFrames;
}

bool TwoViewInitializer::solve() {
  const cv::Matx33d K(camera_.fx, 0, camera_.cx, 0, camera_.fy, camera_.cy, 0, 0, 1);
  cv::Mat inliers;
  const cv::Mat E = cv::findEssentialMat(first_, current_, K, cv::RANSAC, 0.999, options_.ransac_threshold, inliers);
  if (E.rows != 3 || E.cols != 3) return false;  // degenerate (several solutions stacked, or none)
  cv::Mat R_cv, t_cv;
  if (cv::recoverPose(E, first_, current_, K, R_cv, t_cv, inliers) < options_.min_points) return false;
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  cv::cv2eigen(R_cv, R);
  cv::cv2eigen(t_cv, t);

  // Depth d of each inlier in the first frame: the ray d * r0, moved by (R, t), must lie on the ray
  // through the pixel in the last frame: [x1]_x (d R r0 + t) = 0, solved in the least-squares sense.
  std::vector<double> depths(first_.size(), 0.0), valid;
  const double min_angle = options_.min_triangulation_angle * M_PI / 180.0;
  for (std::size_t i = 0; i < first_.size(); ++i) {
    if (!inliers.at<std::uint8_t>(static_cast<int>(i))) continue;
    const Eigen::Vector3d r0 = camera_.backProject(first_[i].x, first_[i].y, 1.0);
    const Eigen::Vector3d x1 = camera_.backProject(current_[i].x, current_[i].y, 1.0);
    const Eigen::Vector3d a = x1.cross(R * r0), b = x1.cross(t);
    const double d = -a.dot(b) / a.squaredNorm();
    if (!(d > 0.0) || !std::isfinite(d)) continue;
    const Eigen::Vector3d seen_from_last = d * (R * r0) + t;  // the point in the last frame
    const double angle = std::acos(std::clamp(seen_from_last.normalized().dot((R * r0).normalized()), -1.0, 1.0));
    if (seen_from_last.z() <= 0.0 || angle < min_angle) continue;
    depths[i] = d;
    valid.push_back(d);
  }
  if (static_cast<int>(valid.size()) < options_.min_points) return false;
  const double scale = options_.median_depth / median(valid);
  inverse_depths_.assign(pixel_count_, 0.0);
  for (std::size_t i = 0; i < first_.size(); ++i)
    if (depths[i] > 0.0) inverse_depths_[static_cast<std::size_t>(alive_[i])] = 1.0 / (depths[i] * scale);
  T_last_first_ = Eigen::Isometry3d::Identity();
  T_last_first_.linear() = R;
  T_last_first_.translation() = t * scale;
  return true;
}

}  // namespace semantic_edge_vo
