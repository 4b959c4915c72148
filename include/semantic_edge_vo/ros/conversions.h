#pragma once
#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <sensor_msgs/CameraInfo.h>

#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/common/camera.h"
#include "semantic_edge_vo/common/edge_set.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"

namespace semantic_edge_vo {

/// A complete CameraInfo of a rectified pinhole camera (K, P, R identity, D zero, plumb_bob).
sensor_msgs::CameraInfo cameraInfoOf(const PinholeCamera& camera, const std::string& frame_id);

/// Intrinsics of a rectified image from its CameraInfo: P's, or K's when P is unset (all zero),
/// scaled by the binning and shifted by the region of interest (the image's size is the ROI's, or
/// the calibration's, divided by the binning). Check the result with validate().
PinholeCamera cameraFromInfo(const sensor_msgs::CameraInfo& info);

/// Views of the frame's edge arrays (no copy; the message must outlive the view).
EdgeSetView edgeSetView(const SemanticEdgeFrame& frame);
/// Moves the edge arrays into the message (no copy).
void moveEdgesInto(EdgeSet&& edges, SemanticEdgeFrame* frame);

/// Moves a built field into a message (no copy).
void moveFieldInto(NearestNeighborFieldData&& field, NearestNeighborField* msg);
/// View of a field message (no copy; the message must outlive the view). Check with validate();
/// an unknown kind leaves `error` non-empty.
NearestNeighborFieldView fieldView(const NearestNeighborField& msg, std::string* error);

/// The odometry's view of a frame and its field: the pyramid is computed from the frame's image,
/// the field and the candidate points are read from the messages, which the result keeps alive.
/// Check the field beforehand (fieldView + validate); `field` may be null (photometric only).
std::shared_ptr<const OdometryFrame> odometryFrameFrom(const SemanticEdgeFrameConstPtr& frame,
                                                       const NearestNeighborFieldConstPtr& field, int index,
                                                       int pyramid_levels);

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& pose);
Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& pose);

}  // namespace semantic_edge_vo
