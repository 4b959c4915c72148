#pragma once
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "semantic_edge_vo/frontend/edge_registration.h"
#include "semantic_edge_vo/frontend/forward_motion_prior.h"
#include "semantic_edge_vo/backend/keyframe.h"

namespace semantic_edge_vo {

struct TrackerOptions {
  int levels = 4;                    ///< coarse-to-fine over levels-1 .. 0 (needs as many pyramid and field levels)
  int iterations_per_level = 10;
  double min_step = 1e-3;            ///< a level stops when an accepted step is this small (se(3) norm)
  double photometric_huber = 9.0;    ///< Huber threshold of gradient-magnitude residuals, gray levels / px
  double photometric_sigma = 4.0;    ///< their scale when weighed against edge residuals, gray levels / px
  double edge_huber = 1.5;           ///< Huber threshold of point-to-tangent residuals, px of the level
  double edge_sigma = 1.0;           ///< their scale, px of the level
  double edge_weight = 2.0;          ///< weight of edge residuals (paper III-C: more in tracking than in mapping)
  /// The constant-velocity guess is taken when its inlier ratio is at least this fraction of the
  /// previous frame's (the ratio itself varies from scene to scene: 0.6-0.9 on KITTI).
  double accept_inlier_ratio = 0.85;
  double min_inlier_ratio = 0.5;     ///< lost when fewer photometric residuals are inliers at level 0
  double min_points_in_view = 0.25;  ///< lost when fewer keyframe points project into the frame
  ForwardMotionOptions forward_motion;  ///< prior on the direction of travel (sigma 0: off)

  std::string validate() const;
};

struct TrackingResult {
  Eigen::Isometry3d T_cam_kf = Eigen::Isometry3d::Identity();  ///< maps keyframe points into the frame
  bool ok = false;                   ///< the pose can be trusted
  int guess = 0;                     ///< index of the initial guess that won
  int iterations = 0;
  int points = 0;                    ///< keyframe points with depth (level 0)
  int points_in_view = 0;
  int photometric_residuals = 0, photometric_inliers = 0;
  int edge_residuals = 0, edge_inliers = 0;
  double photometric_rmse = 0.0;     ///< inliers, gray levels / px
  double edge_rmse = 0.0;            ///< inliers, full-resolution px
  double mean_flow = 0.0;            ///< mean displacement of the keyframe points, full-resolution px
  /// Covariance of the solution, of xi in T_cam_kf = exp(xi) * T_cam_kf (camera axes): the level-0
  /// Gauss-Newton Hessian's inverse, scaled (solutionCovariance; docs/architecture.md). Zero where
  /// no tracking estimated the pose: a map's first frame, which defines it.
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Zero();

  /// Photometric inliers over photometric residuals (level 0).
  double inlierRatio() const { return static_cast<double>(photometric_inliers) / std::max(1, photometric_residuals); }
  /// The result in its map scaled by `scale` (the road set the map's metres after it was tracked):
  /// the translation and its variances.
  void scaleTranslation(double scale);
};

/// Which layers of a semantic field (SNNF) the keyframe's edge points are matched in.
enum class EdgeLayers {
  kOwn,       ///< each point's own (MapPoint::field_layers)
  kAllEdges,  ///< the all-edges layer, for every point: ANNF's association on the same field
};

/// Aligns frames to the active keyframe (paper III-C): photometric residuals on gradient magnitude
/// over a small pixel pattern for every point, plus point-to-tangent residuals against the frame's
/// nearest-neighbour field for edge points, Huber-weighted, Levenberg-Marquardt on SE(3),
/// coarse to fine, from the first initial guess (constant velocity) when it tracks well, else from
/// the one of several guesses that ends with the lowest cost.
class Tracker {
 public:
  explicit Tracker(const TrackerOptions& options) : options_(options) {}

  /// Precomputes what tracking against `keyframe` needs (reference patterns, edge points).
  void setKeyframe(std::shared_ptr<const Keyframe> keyframe);
  /// New options (live tuning); the keyframe's precomputation is made again with them.
  void setOptions(const TrackerOptions& options);
  const std::shared_ptr<const Keyframe>& keyframe() const { return keyframe_; }

  /// @param[in] frame pyramid of the frame
  /// @param[in] field its nearest-neighbour field, or nullptr for photometric-only tracking
  /// @param[in] guesses initial T_cam_kf candidates (constant velocity first)
  /// @param[in] previous_inlier_ratio photometric inlier ratio of the previous frame (1: none)
  /// @param[in] layers the SNNF layers edge points are matched in (kAllEdges: the field must have an
  ///            all-edges layer, see hasAllEdgesLayer)
  TrackingResult track(const ImagePyramid& frame, const NearestNeighborFieldView* field,
                       const std::vector<Eigen::Isometry3d>& guesses, double previous_inlier_ratio = 1.0,
                       EdgeLayers layers = EdgeLayers::kOwn) const;
  /// Whether the keyframe's field is semantic with an all-edges layer (EdgeLayers::kAllEdges differs from kOwn).
  bool hasAllEdgesLayer() const { return !all_layer_edges_.empty(); }

 private:
  struct Normal {
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Vector6d b = Vector6d::Zero();
  };
  struct LevelReference {
    std::vector<Eigen::Vector3f> pattern_points;  ///< per point, kPattern points in the keyframe frame
    std::vector<float> pattern_values;            ///< gradient magnitude of the keyframe there
    std::vector<int> point_index;                 ///< keyframe point of each pattern block
  };
  /// The points tracking aligns: the keyframe's photometric patterns and its edges as matched.
  struct TrackedPoints {
    const std::vector<LevelReference>& references;  ///< per level
    const std::vector<ReferenceEdge>& edges;
  };
  /// Sums over a slice of the residuals of a level: cost, counts and normal equations.
  struct LevelSums {
    double cost = 0.0, inlier_squares = 0.0, edge_squares = 0.0;
    int residuals = 0, inliers = 0, in_view = 0, edge_residuals = 0, edge_inliers = 0;
    Normal normal;
    LevelSums& operator+=(const LevelSums& other);
  };
  /// Cost of the level at a pose; fills the normal equations and `result`'s counts when asked. The
  /// residuals are evaluated in slices on both cores.
  double evaluate(const TrackedPoints& points, int level, const Eigen::Isometry3d& T_cam_kf, const ImagePyramid& frame,
                  const NearestNeighborFieldView* field, const ForwardMotionPrior& prior, Normal* normal,
                  TrackingResult* result) const;
  /// Photometric residuals of reference blocks [begin, end).
  void addPhotometric(const LevelReference& reference, const Eigen::Isometry3d& T_cam_kf, const PyramidLevel& target,
                      std::size_t begin, std::size_t end, bool with_normal, LevelSums* sums) const;
  /// Edge residuals of edges[begin, end).
  void addEdges(const std::vector<ReferenceEdge>& edges, int level, const Eigen::Isometry3d& T_cam_kf,
                const NearestNeighborFieldView& field, std::size_t begin, std::size_t end, bool with_normal,
                LevelSums* sums) const;
  /// Levenberg-Marquardt at one level from `T`; returns the final cost. When asked, also the normal
  /// equations and `result`'s counts at the final `T`, as evaluate() gives them (no second evaluation).
  double optimizeLevel(const TrackedPoints& points, int level, const ImagePyramid& frame, const NearestNeighborFieldView* field,
                       const ForwardMotionPrior& prior, Eigen::Isometry3d* T, int* iterations, Normal* final_normal = nullptr,
                       TrackingResult* final_counts = nullptr) const;
  void setReferences();

  TrackerOptions options_;
  std::shared_ptr<const Keyframe> keyframe_;
  std::vector<LevelReference> references_;      ///< per level, the points with depth
  std::vector<ReferenceEdge> edges_;            ///< the edge points with depth, in their own layers
  std::vector<ReferenceEdge> all_layer_edges_;  ///< the same in the all-edges layer (empty: the field has none)
  std::vector<EdgeRegistration> edge_residuals_; ///< per level
};

}  // namespace semantic_edge_vo
