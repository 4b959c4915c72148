#pragma once
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/backend/corner_tracks.h"

namespace semantic_edge_vo {

struct TwoViewMotion;

struct InitializerOptions {
  double min_parallax = 0.032;      ///< median displacement of the tracked points needed, fraction of the image width
                                    ///< (0.032: 40 px at 1241; shorter baselines give poor first depths)
  int max_frames = 12;              ///< give up (and restart from the newest frame) after this many frames
  int min_points = 80;              ///< tracked points and triangulated inliers needed
  double ransac_threshold = 0.75;   ///< essential-matrix RANSAC, px
  double min_triangulation_angle = 0.1;  ///< deg; points seen under less parallax get no depth
  double median_depth = 10.0;       ///< the map's scale: median depth of the first keyframe's points, map units
  double max_travel_off_axis = 60.0;  ///< deg; re-initialising after a loss, the travel must keep this close to the
                                      ///< vehicle's forward axis (farther: the consensus is traffic's, the rest is tried)

  std::string validate() const;
};

/// Two-view initialisation for forward driving: the first frame's points are tracked frame to frame
/// (pyramidal Lucas-Kanade with a forward-backward check); once they moved far enough, the relative
/// pose comes from the essential matrix (RANSAC) and the points' depths from triangulation. Works
/// within a few frames of forward motion, where DSO's random-depth initialisation often fails.
class TwoViewInitializer {
 public:
  enum class Status { kNeedMoreFrames, kReady, kFailed };

  TwoViewInitializer(const InitializerOptions& options, const PinholeCamera& camera) : options_(options), camera_(camera) {}

  /// Starts from a first frame and the pixels (full resolution) whose depths are wanted.
  /// @param expected_travel the direction the camera must travel in (its optical frame), zero when
  ///        any will do: a motion travelling more than max_travel_off_axis away from it is refused
  void reset(const cv::Mat& gray, const std::vector<Eigen::Vector2f>& pixels,
             const Eigen::Vector3d& expected_travel = Eigen::Vector3d::Zero());
  /// Adds the next frame (CV_8UC1).
  Status add(const cv::Mat& gray);

  // Valid after kReady:
  /// Pose of the first frame seen from the last one (maps first-frame points into it), map units.
  const Eigen::Isometry3d& T_last_first() const { return T_last_first_; }
  /// Inverse depth of each pixel given to reset() in the first frame, 0 where unknown.
  const std::vector<double>& inverseDepths() const { return inverse_depths_; }
  int framesAdded() const { return tracks_.framesTracked(); }

 private:
  bool solve();
  /// The two-view motion of the tracks that travels as expected: the largest consensus, or when it
  /// travels elsewhere (a truck alongside, overtaking, fills the view) the largest among the rest.
  bool estimateMotion(TwoViewMotion* motion) const;
  bool travelsAsExpected(const TwoViewMotion& motion) const;

  InitializerOptions options_;
  PinholeCamera camera_;
  CornerTracks tracks_;  ///< the reset() pixels, followed
  std::size_t pixel_count_ = 0;
  Eigen::Vector3d expected_travel_ = Eigen::Vector3d::Zero();
  Eigen::Isometry3d T_last_first_ = Eigen::Isometry3d::Identity();
  std::vector<double> inverse_depths_;
};

}  // namespace semantic_edge_vo
