#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/synthetic/camera_effects.h"
#include "semantic_edge_vo/synthetic/network_noise.h"
#include "semantic_edge_vo/synthetic/scene_renderer.h"
#include "semantic_edge_vo/synthetic/semantic_channels.h"
#include "semantic_edge_vo/synthetic/world.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Everything that defines a synthetic sequence: the same options give the same frames.
struct SyntheticSequenceOptions {
  WorldOptions world;                       ///< scene type, seed, route, motion, traffic
  PinholeCamera camera = kittiCamera();     ///< KITTI geometry by default
  LightingOptions lighting;
  CameraEffectsOptions effects;
  NetworkNoiseOptions network_noise;        ///< errors of the simulated semantic edge network
  bool semantics = true;                    ///< compute the semantic network channels

  /// Defaults for a scene type and seed (the world's scene defaults, KITTI camera).
  static SyntheticSequenceOptions forScene(SceneType scene, std::uint64_t seed);
  std::string validate() const;
};

/// One frame with its exact ground truth.
struct SyntheticFrame {
  int index = 0;
  double time = 0.0;                                               ///< s since frame 0
  Eigen::Isometry3d T_world_cam = Eigen::Isometry3d::Identity();  ///< camera to world (world = camera 0)
  double speed = 0.0;                                              ///< m/s
  double exposure_gain = 0.0;                                      ///< radiance to gray levels
  cv::Mat gray;          ///< CV_8UC1
  cv::Mat color;         ///< CV_8UC3, BGR (same optical centre and calibration as gray)
  cv::Mat depth;         ///< CV_32FC1, z along the optical axis, m, exact; 0 on the sky
  cv::Mat class_id;      ///< CV_8UC1, ground-truth Cityscapes train id (sky included: 10)
  cv::Mat dynamic;       ///< CV_8UC1, 255 on moving vehicles (their points do not follow the camera poses)
  SemanticNetworkOutput semantics;  ///< simulated network output, with the configured noise
};

/// Renders the frames of a synthetic driving sequence. Frames can be asked in any order; going
/// forward is cheapest.
class SyntheticSequence {
 public:
  explicit SyntheticSequence(const SyntheticSequenceOptions& options);

  const SyntheticSequenceOptions& options() const { return options_; }
  const PinholeCamera& camera() const { return options_.camera; }
  /// Ground-truth pose and time of frame i (cheap: nothing is rendered).
  Eigen::Isometry3d pose(int i);
  double time(int i);
  /// Renders frame i with all its channels.
  SyntheticFrame frame(int i);

 private:
  SyntheticSequenceOptions options_;
  World world_;
  SceneRenderer renderer_;
  CameraEffects effects_;
  Eigen::Isometry3d T_cam0_map_;
  RenderedView view_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
