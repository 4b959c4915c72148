#include "semantic_edge_vo/config/live_options.h"

namespace semantic_edge_vo {

std::string IntakeStreamOptions::validate() const {
  if (queue_size < 1) return "queue_size must be >= 1";
  if (!(time_jump_back > 0.0)) return "time_jump_back must be > 0 s";
  if (!(camera_info_tolerance >= 0.0 && camera_info_wait > 0.0 && image_timeout > 0.0))
    return "camera_info_tolerance must be >= 0 s, camera_info_wait and image_timeout > 0 s";
  if (transport != "raw" && transport != "compressed") return "transport must be raw or compressed (got '" + transport + "')";
  if (class_format != "probabilities" && class_format != "labels" && class_format != "bitmask")
    return "class_format must be probabilities, labels or bitmask (got '" + class_format + "')";
  if (edge_source != "canny" && edge_source != "topic") return "edge_source must be canny or topic (got '" + edge_source + "')";
  if (on_missing_classes != "drop" && on_missing_classes != "canny")
    return "on_missing_classes must be drop or canny (got '" + on_missing_classes + "')";
  if (!(class_wait > 0.0 && max_pending >= 1)) return "need class_wait > 0 s and max_pending >= 1";
  if (class_maps != "same_frame" && class_maps != "newest") return "class_maps must be same_frame or newest (got '" + class_maps + "')";
  if (class_maps == "newest" && edge_source != "canny") return "class_maps newest needs edge_source canny (a learned edge map is not carried)";
  if (const std::string error = class_carry.validate(); !error.empty()) return "class_carry/" + error;
  return "";
}

std::string FrameNames::validate() const {
  if (odom_frame.empty() || base_frame.empty() || odom_frame == base_frame) return "odom_frame and base_frame must be non-empty and differ";
  return "";
}

std::string TfOptions::validate() const {
  if (const std::string error = frames.validate(); !error.empty()) return error;
  if (!(extrinsic_wait >= 0.0 && max_twist_gap > 0.0)) return "extrinsic_wait must be >= 0 s and max_twist_gap > 0 s";
  return "";
}

std::string LiveMappingOptions::validate() const {
  if (mapping_mode != "parallel" && mapping_mode != "deterministic")
    return "mapping_mode must be parallel or deterministic (got '" + mapping_mode + "')";
  return "";
}

std::string MapOutputOptions::validate() const {
  if (odom_frame.empty()) return "odom_frame must be non-empty";
  if (queue_size < 1 || max_map_points < 1 || max_path_poses < 1) return "queue_size, max_map_points and max_path_poses must be >= 1";
  if (!(voxel_size > 0.0)) return "voxel_size must be > 0";
  return "";
}

std::string SegmenterOutputOptions::validate() const {
  if (output_format != "probabilities" && output_format != "labels")
    return "output_format must be probabilities or labels (got '" + output_format + "')";
  if (output_bits != 32 && output_bits != 8) return "output_bits must be 32 or 8";
  if (log_every < 1) return "log_every must be >= 1";
  if (threads < 0) return "threads must be >= 0 (0: OpenCV's choice)";
  return "";
}

std::string loadIntakeStreamOptions(ParameterLoader* loader, IntakeStreamOptions* options) {
  loader->load("queue_size", &options->queue_size, "messages");
  loader->load("transport", &options->transport, "(raw | compressed)");
  loader->load("time_jump_back", &options->time_jump_back, "s");
  loader->load("camera_info_tolerance", &options->camera_info_tolerance, "s");
  loader->load("camera_info_wait", &options->camera_info_wait, "s (wall time)");
  loader->load("image_timeout", &options->image_timeout, "s (wall time)");
  loader->load("rectify", &options->rectify, "(undistort with camera_info's D, K, R, P)");
  loader->load("class_format", &options->class_format, "(probabilities | labels | bitmask)");
  loader->load("edge_source", &options->edge_source, "(canny | topic; fused)");
  loader->load("class_maps", &options->class_maps, "(same_frame | newest)");
  loader->load("class_carry/flow_scale", &options->class_carry.flow_scale, "of the image size");
  loader->load("class_carry/max_age", &options->class_carry.max_age, "s");
  loader->load("class_carry/remembered_images", &options->class_carry.remembered_images, "frames");
  loader->load("class_carry/max_loop_error", &options->class_carry.max_loop_error, "px");
  loader->load("class_wait", &options->class_wait, "s");
  loader->load("on_missing_classes", &options->on_missing_classes, "(drop | canny)");
  loader->load("max_pending", &options->max_pending, "frames");
  return options->validate();
}

namespace {

void loadFrameNames(ParameterLoader* loader, FrameNames* frames) {
  loader->load("odom_frame", &frames->odom_frame);
  loader->load("base_frame", &frames->base_frame);
}

}  // namespace

std::string loadTfOptions(ParameterLoader* loader, TfOptions* options) {
  loadFrameNames(loader, &options->frames);
  loader->load("camera_frame", &options->camera_frame, "(empty: each image's frame_id)");
  loader->load("publish_tf", &options->publish_tf);
  loader->load("publish_default_camera_tf", &options->publish_default_camera_tf);
  loader->load("extrinsic_wait", &options->extrinsic_wait, "s");
  loader->load("max_twist_gap", &options->max_twist_gap, "s");
  return options->validate();
}

std::string loadLiveMappingOptions(ParameterLoader* loader, LiveMappingOptions* options) {
  loader->load("mapping_mode", &options->mapping_mode, "(parallel | deterministic)");
  return options->validate();
}

std::string loadMapOutputOptions(ParameterLoader* loader, MapOutputOptions* options) {
  loader->load("odom_frame", &options->odom_frame, "(keep equal to tracking/odom_frame)");
  loader->load("queue_size", &options->queue_size, "messages");
  loader->load("voxel_size", &options->voxel_size, "map units (m up to the monocular scale)");
  loader->load("max_map_points", &options->max_map_points, "points");
  loader->load("max_path_poses", &options->max_path_poses, "poses");
  return options->validate();
}

std::string loadSegmenterOutputOptions(ParameterLoader* loader, SegmenterOutputOptions* options) {
  loader->load("output_format", &options->output_format, "(probabilities | labels: 8UC2 class, probability x 255)");
  loader->load("output_bits", &options->output_bits, "(32: 32FC<C> probabilities | 8: 8UC<C>, probability x 255)");
  loader->load("log_every", &options->log_every, "frames");
  loader->load("threads", &options->threads, "(OpenCV threads of the process; 0: OpenCV's choice)");
  return options->validate();
}

}  // namespace semantic_edge_vo
