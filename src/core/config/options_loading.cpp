#include "semantic_edge_vo/config/options_loading.h"

namespace semantic_edge_vo {

std::string loadCannyOptions(ParameterLoader* loader, CannyOptions* options) {
  loader->load("canny/blur_sigma", &options->blur_sigma, "px");
  loader->load("canny/low_threshold", &options->low_threshold, "Sobel gradient units");
  loader->load("canny/high_threshold", &options->high_threshold, "Sobel gradient units");
  loader->load("canny/border", &options->border, "px");
  return options->validate();
}

std::string loadPointSamplerOptions(ParameterLoader* loader, PointSamplerOptions* options) {
  loader->load("sampler/max_edge_points", &options->max_edge_points, "points");
  loader->load("sampler/min_support_points", &options->min_support_points, "points");
  loader->load("sampler/support_block_size", &options->support_block_size, "px");
  loader->load("sampler/support_threshold_offset", &options->support_threshold_offset, "gray levels/px");
  loader->load("sampler/support_min_distance", &options->support_min_distance, "px");
  return options->validate();
}

std::string loadFieldOptions(ParameterLoader* loader, FieldOptions* options) {
  std::string kind = toString(options->kind);
  loader->load("field/kind", &kind, "(annf | onnf | snnf)");
  if (!parseFieldKind(kind, &options->kind)) return "field/kind must be annf, onnf or snnf (got '" + kind + "')";
  loader->load("field/pyramid_levels", &options->pyramid_levels, "levels");
  loader->load("field/orientation_bins", &options->orientation_bins, "bins");
  loader->load("field/truncation_radius", &options->truncation_radius, "px of each level");
  loader->load("field/cell_size", &options->cell_size, "px");
  return options->validate();
}

std::string loadOdometryOptions(ParameterLoader* loader, OdometryOptions* options) {
  TrackerOptions& tracker = options->tracker;
  loader->load("tracker/levels", &tracker.levels, "levels");
  loader->load("tracker/iterations_per_level", &tracker.iterations_per_level, "iterations");
  loader->load("tracker/min_step", &tracker.min_step, "(se(3) step norm)");
  loader->load("tracker/photometric_huber", &tracker.photometric_huber, "gray levels/px");
  loader->load("tracker/edge_huber", &tracker.edge_huber, "px of each level");
  loader->load("tracker/edge_weight", &tracker.edge_weight, "");
  loader->load("tracker/accept_inlier_ratio", &tracker.accept_inlier_ratio, "");
  loader->load("tracker/min_inlier_ratio", &tracker.min_inlier_ratio, "");
  loader->load("tracker/forward_motion/sigma", &tracker.forward_motion.sigma_deg, "deg (0: off)");
  loader->load("tracker/forward_motion/pitch", &tracker.forward_motion.pitch_deg, "deg (+: down)");
  loader->load("tracker/forward_motion/yaw", &tracker.forward_motion.yaw_deg, "deg (+: right)");
  options->window_optimizer.forward_motion = tracker.forward_motion;  // one vehicle, one prior
  loader->load("initializer/min_parallax", &options->initializer.min_parallax, "image widths");
  loader->load("initializer/max_frames", &options->initializer.max_frames, "frames");
  loader->load("initializer/median_depth", &options->initializer.median_depth, "map units");
  loader->load("initializer/max_travel_off_axis", &options->initializer.max_travel_off_axis, "deg");
  loader->load("keyframe_flow", &options->keyframe_flow, "px");
  loader->load("keyframe_max_interval", &options->keyframe_max_interval, "frames");
  loader->load("keyframe_min_parallax", &options->keyframe_min_parallax, "px");
  loader->load("keyframe_min_inliers", &options->keyframe_min_inliers, "fraction");
  loader->load("window_size", &options->window_size, "keyframes");
  loader->load("optimize_window", &options->optimize_window);
  loader->load("mapping_queue", &options->mapping_queue, "frames (parallel mapping)");
  WindowOptimizerOptions& window = options->window_optimizer;
  loader->load("window_optimizer/keyframes", &window.keyframes, "keyframes");
  loader->load("window_optimizer/max_iterations", &window.max_iterations, "iterations");
  loader->load("window_optimizer/point_stride", &window.point_stride, "points");
  loader->load("window_optimizer/photometric_huber", &window.photometric_huber, "gray levels/px");
  loader->load("window_optimizer/edge_huber", &window.edge_huber, "px");
  loader->load("window_optimizer/edge_weight", &window.edge_weight, "");
  loader->load("window_optimizer/edge_radius", &window.edge_radius, "px");
  loader->load("window_optimizer/depth_prior_scale", &window.depth_prior_scale, "filtered sigmas");
  loader->load("window_optimizer/measured_rotation_sigma", &window.measured_rotation_sigma_deg, "deg (0: off)");
  loader->load("window_optimizer/measured_direction_sigma", &window.measured_direction_sigma_deg, "deg (0: off)");
  KeyframeMotionOptions& motion = options->keyframe_motion;
  loader->load("keyframe_motion/corners", &motion.corners, "corners (0: off)");
  loader->load("keyframe_motion/min_distance", &motion.min_distance, "px");
  loader->load("keyframe_motion/window", &motion.window, "px");
  loader->load("keyframe_motion/ransac_threshold", &motion.ransac_threshold, "px");
  loader->load("keyframe_motion/min_inliers", &motion.min_inliers, "corners");
  loader->load("keyframe_motion/min_parallax", &motion.min_parallax, "px");
  loader->load("keyframe_motion/max_chord_deviation", &motion.max_chord_deviation_deg, "deg (0: off)");
  motion.forward_motion = tracker.forward_motion;
  loader->load("keyframe_motion/reanchor_rotation", &motion.reanchor_rotation_deg, "deg");
  loader->load("keyframe_motion/reanchor_direction", &motion.reanchor_direction_deg, "deg");
  loader->load("keyframe_motion/reanchor_max_rotation", &motion.reanchor_max_rotation_deg, "deg");
  loader->load("keyframe_motion/reanchor_max_direction", &motion.reanchor_max_direction_deg, "deg");
  loader->load("class_reliability/min_agreement", &options->class_reliability.min_agreement, "(fraction; 0: every class relied on)");
  FrameConsistencyOptions& consistency = options->consistency;
  loader->load("consistency/max_motion_deviation", &consistency.max_motion_deviation, "(of the usual travel per frame)");
  loader->load("consistency/max_untrusted_frames", &consistency.max_untrusted_frames, "frames");
  loader->load("consistency/max_keyframe_scale_change", &consistency.max_keyframe_scale_change, "(fraction)");
  RoadScaleOptions& road = options->road;
  loader->load("camera_height", &road.camera_height, "m above the road (0: no metric scale)");
  loader->load("road/pitch", &road.pitch_deg, "deg (+: camera looking down)");
  loader->load("road/roll", &road.roll_deg, "deg (+: right side down)");
  loader->load("road/max_normal_deviation", &road.max_normal_deviation_deg, "deg");
  loader->load("road/min_ahead", &road.min_ahead, "camera heights");
  loader->load("road/max_ahead", &road.max_ahead, "camera heights");
  loader->load("road/half_width", &road.half_width, "camera heights");
  loader->load("road/lane_half_width", &road.lane_half_width, "camera heights");
  loader->load("road/inlier_band", &road.inlier_band, "(fraction of the height)");
  loader->load("road/min_inliers", &road.min_inliers, "points");
  loader->load("road/min_inlier_ratio", &road.min_inlier_ratio, "");
  loader->load("road/ransac_iterations", &road.ransac_iterations, "iterations");
  loader->load("road/height_sigma", &road.height_sigma, "(fraction, per keyframe)");
  loader->load("road/scale_sigma", &road.scale_sigma, "(fraction, per keyframe)");
  loader->load("road/max_height_change", &road.max_height_change, "(fraction of the height)");
  return options->validate();
}

std::string loadClassTable(ParameterLoader* loader, ClassTable* table) {
  std::vector<SemanticClass> classes = ClassTable::cityscapes().classes();
  loader->load("classes", &classes, "(name, id, rgb)");
  *table = ClassTable(std::move(classes));
  return table->validate();
}

}  // namespace semantic_edge_vo
