#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

#include <cmath>
#include <sstream>

#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {
namespace synthetic {

SyntheticSequenceOptions SyntheticSequenceOptions::forScene(SceneType scene, std::uint64_t seed) {
  SyntheticSequenceOptions options;
  options.world = WorldOptions::forScene(scene);
  options.world.seed = seed;
  if (scene == SceneType::kHighway) options.lighting.fog_distance = 900.0;
  return options;
}

std::string SyntheticSequenceOptions::validate() const {
  std::ostringstream error;
  if (const std::string e = world.validate(); !e.empty()) error << "world: " << e;
  else if (const std::string e = camera.validate(); !e.empty()) error << "camera: " << e;
  else if (const std::string e = lighting.validate(); !e.empty()) error << "lighting: " << e;
  else if (const std::string e = effects.validate(); !e.empty()) error << "effects: " << e;
  else if (const std::string e = network_noise.validate(); !e.empty()) error << "network_noise: " << e;
  return error.str();
}

SyntheticSequence::SyntheticSequence(const SyntheticSequenceOptions& options)
    : options_(options),
      world_(options.world),
      renderer_(options.camera, world_.road(), options.lighting),
      effects_(options.effects, options.camera.width, options.camera.height, hashCombine(options.world.seed, 0x63616dULL)) {
  T_cam0_map_ = world_.ego(0).T_map_cam.inverse();
}

Eigen::Isometry3d SyntheticSequence::pose(int i) { return T_cam0_map_ * world_.ego(i).T_map_cam; }

double SyntheticSequence::time(int i) { return world_.ego(i).time; }

SyntheticFrame SyntheticSequence::frame(int i) {
  const EgoState ego = world_.ego(i);
  renderer_.render(world_.gather(i), ego.T_map_cam, &view_);
  SyntheticFrame frame;
  frame.index = i;
  frame.time = ego.time;
  frame.T_world_cam = T_cam0_map_ * ego.T_map_cam;
  frame.speed = ego.speed;
  frame.exposure_gain = effects_.exposureGain(ego.time);
  effects_.expose(view_.radiance, ego.time, i, &frame.color, &frame.gray);
  frame.depth = view_.depth.clone();
  frame.class_id = view_.class_id.clone();
  frame.dynamic = view_.dynamic.clone();
  if (options_.semantics) {
    // Texture edges come from the image without sensor noise or exposure drift, as a network would
    // see through them.
    cv::Mat clean_gray;
    cv::Mat luma;
    cv::cvtColor(view_.radiance, luma, cv::COLOR_BGR2GRAY);
    luma.convertTo(clean_gray, CV_8U, 255.0);
    frame.semantics = exactSemanticChannels(frame.class_id, clean_gray);
    if (options_.network_noise.any())
      applyNetworkNoise(options_.network_noise, hashCombine(options_.world.seed, 0x6e6e0000ULL + static_cast<std::uint64_t>(i)),
                        &frame.semantics);
  }
  return frame;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
