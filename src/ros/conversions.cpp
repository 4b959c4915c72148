#include "semantic_edge_vo/ros/conversions.h"

#include <algorithm>

#include <tf2_eigen/tf2_eigen.h>

namespace semantic_edge_vo {

sensor_msgs::CameraInfo cameraInfoOf(const PinholeCamera& camera, const std::string& frame_id) {
  sensor_msgs::CameraInfo info;
  info.header.frame_id = frame_id;
  info.width = static_cast<std::uint32_t>(camera.width);
  info.height = static_cast<std::uint32_t>(camera.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {camera.fx, 0.0, camera.cx, 0.0, 0.0, camera.fy, camera.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

PinholeCamera cameraFromInfo(const sensor_msgs::CameraInfo& info) {
  // A rectified image's intrinsics are P's left 3x3 (sensor_msgs/CameraInfo): K is the raw camera's,
  // and rectification (image_proc) moves the principal point and scales the focal length. Drivers
  // that leave P unset (all zero) give K.
  const bool has_projection = info.P[0] != 0.0 || info.P[5] != 0.0;
  // The calibration is of the full sensor; a binned image or a region of interest of it
  // (REP-104) scales and shifts the intrinsics as image_geometry's camera model does. Binning 0
  // means 1; an ROI without a width or a height, the full image (image_geometry: an all-zero one).
  const std::uint32_t bin_x = std::max(1u, info.binning_x), bin_y = std::max(1u, info.binning_y);
  const bool full = info.roi.width == 0 || info.roi.height == 0;
  const double x_offset = full ? 0.0 : info.roi.x_offset, y_offset = full ? 0.0 : info.roi.y_offset;
  PinholeCamera camera;
  camera.fx = (has_projection ? info.P[0] : info.K[0]) / bin_x;
  camera.fy = (has_projection ? info.P[5] : info.K[4]) / bin_y;
  camera.cx = ((has_projection ? info.P[2] : info.K[2]) - x_offset) / bin_x;
  camera.cy = ((has_projection ? info.P[6] : info.K[5]) - y_offset) / bin_y;
  camera.width = static_cast<int>((full ? info.width : info.roi.width) / bin_x);
  camera.height = static_cast<int>((full ? info.height : info.roi.height) / bin_y);
  return camera;
}

EdgeSetView edgeSetView(const SemanticEdgeFrame& frame) {
  return {frame.edge_u, frame.edge_v, frame.edge_normal_x, frame.edge_normal_y, frame.edge_strength,
          frame.edge_class_mask};
}

void moveEdgesInto(EdgeSet&& edges, SemanticEdgeFrame* frame) {
  frame->edge_u = std::move(edges.u);
  frame->edge_v = std::move(edges.v);
  frame->edge_normal_x = std::move(edges.normal_x);
  frame->edge_normal_y = std::move(edges.normal_y);
  frame->edge_strength = std::move(edges.strength);
  frame->edge_class_mask = std::move(edges.class_mask);
}

void moveFieldInto(NearestNeighborFieldData&& field, NearestNeighborField* msg) {
  msg->kind = toString(field.kind);
  msg->num_layers = static_cast<std::uint32_t>(field.num_layers);
  msg->orientation_bins = static_cast<std::uint32_t>(field.orientation_bins);
  msg->all_edges_layer = field.all_edges_layer;
  msg->layer_names = std::move(field.layer_names);
  msg->truncation_radius = field.truncation_radius;
  msg->levels.resize(field.levels.size());
  for (std::size_t l = 0; l < field.levels.size(); ++l) {
    FieldLevelData& from = field.levels[l];
    NearestNeighborFieldLevel& to = msg->levels[l];
    to.scale = from.scale;
    to.width = static_cast<std::uint32_t>(from.width);
    to.height = static_cast<std::uint32_t>(from.height);
    to.cell_size = static_cast<std::uint32_t>(from.cell_size);
    to.grid_cols = static_cast<std::uint32_t>(from.grid_cols);
    to.grid_rows = static_cast<std::uint32_t>(from.grid_rows);
    to.seed_u = std::move(from.seed_u);
    to.seed_v = std::move(from.seed_v);
    to.seed_normal_x = std::move(from.seed_normal_x);
    to.seed_normal_y = std::move(from.seed_normal_y);
    to.seed_edge = std::move(from.seed_edge);
    to.cell_start = std::move(from.cell_start);
    to.entry_seed = std::move(from.entry_seed);
  }
}

NearestNeighborFieldView fieldView(const NearestNeighborField& msg, std::string* error) {
  NearestNeighborFieldView view;
  if (!parseFieldKind(msg.kind, &view.kind)) *error = "unknown field kind '" + msg.kind + "'";
  view.num_layers = static_cast<int>(msg.num_layers);
  view.orientation_bins = static_cast<int>(msg.orientation_bins);
  view.all_edges_layer = msg.all_edges_layer;
  view.truncation_radius = msg.truncation_radius;
  for (const auto& level : msg.levels) {
    FieldLevelView v;
    v.scale = level.scale;
    v.width = static_cast<int>(level.width);
    v.height = static_cast<int>(level.height);
    v.cell_size = static_cast<int>(level.cell_size);
    v.grid_cols = static_cast<int>(level.grid_cols);
    v.grid_rows = static_cast<int>(level.grid_rows);
    v.seed_u = level.seed_u;
    v.seed_v = level.seed_v;
    v.seed_normal_x = level.seed_normal_x;
    v.seed_normal_y = level.seed_normal_y;
    v.seed_edge = level.seed_edge;
    v.cell_start = level.cell_start;
    v.entry_seed = level.entry_seed;
    view.levels.push_back(v);
  }
  return view;
}

std::shared_ptr<const OdometryFrame> odometryFrameFrom(const SemanticEdgeFrameConstPtr& frame,
                                                       const NearestNeighborFieldConstPtr& field, int index,
                                                       int pyramid_levels) {
  auto result = std::make_shared<OdometryFrame>();
  result->index = index;
  result->time = frame->header.stamp.toSec();
  const cv::Mat gray(static_cast<int>(frame->image.height), static_cast<int>(frame->image.width), CV_8UC1,
                     const_cast<std::uint8_t*>(frame->image.data.data()), frame->image.step);
  result->pyramid = std::make_shared<ImagePyramid>(gray, cameraFromInfo(frame->camera_info), pyramid_levels);
  result->candidates = candidatesFrom(edgeSetView(*frame), frame->sampled_edges, frame->support_u, frame->support_v);
  result->classes_known = frame->class_map_age >= 0.0f || frame->class_names.size() <= 1;
  if (field) {
    std::string error;
    result->field = fieldView(*field, &error);
    result->field_storage = std::shared_ptr<const void>(field.get(), [field](const void*) {});
    result->has_field = true;
  }
  return result;
}

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& pose) { return tf2::toMsg(pose); }

Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose) {
  Eigen::Isometry3d result;
  tf2::fromMsg(pose, result);
  return result;
}

}  // namespace semantic_edge_vo
