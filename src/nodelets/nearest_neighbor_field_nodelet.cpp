// NearestNeighborField: SemanticEdgeFrame -> NearestNeighborField (ANNF, ONNF or SNNF, all levels).
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include <mutex>

#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/NearestNeighborFieldConfig.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/live_parameters.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/nodelet_diagnostics.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"

namespace semantic_edge_vo {

class NearestNeighborFieldNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    const RosParameterSource parameters(getPrivateNodeHandle());
    ParameterLoader loader(parameters);
    std::string error = loadFieldOptions(&loader, &options_);
    tracer_.init(node, &loader, getName());
    NODELET_INFO_STREAM("parameters:" << loader.summary());
    warnUnknownParameters(loader, getName());
    if (error.empty()) error = parameters.error();
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    diagnostics_ = std::make_unique<NodeletDiagnostics>(node, getName());
    rejections_ = std::make_unique<InputRejections>(getName(), [this](const std::string&) { diagnostics_->dropped(); });
    NearestNeighborFieldConfig live;
    live.kind = toString(options_.kind);
    live.truncation_radius = options_.truncation_radius;
    live_ = std::make_unique<LiveParameters<NearestNeighborFieldConfig>>(
        getPrivateNodeHandle(), live, [this](const NearestNeighborFieldConfig& config) {
          std::lock_guard<std::mutex> lock(options_mutex_);
          FieldOptions changed = options_;
          changed.truncation_radius = config.truncation_radius;
          if (!parseFieldKind(config.kind, &changed.kind) || !changed.validate().empty()) {
            NODELET_ERROR_STREAM("live parameters refused: field kind '" << config.kind << "', truncation radius " << config.truncation_radius);
            return;
          }
          if (changed.kind != options_.kind) NODELET_INFO_STREAM("field kind now " << config.kind << ": tracking starts a new map");
          options_ = changed;
        });
    field_publisher_ = node.advertise<NearestNeighborField>("nn_field", 5);
    frame_subscriber_ = node.subscribe("edge_frame", 5, &NearestNeighborFieldNodelet::onFrame, this);
  }

  void onFrame(const SemanticEdgeFrameConstPtr& frame) {
    const ros::WallTime start = ros::WallTime::now();
    diagnostics_->input(frame->header.seq);
    build(frame);
    diagnostics_->processed((ros::WallTime::now() - start).toSec() * 1e3);
  }

  void build(const SemanticEdgeFrameConstPtr& frame) {
    tracer_.received(frame_subscriber_.getTopic(), frame.get(), frame->header.stamp);
    const EdgeSetView edges = edgeSetView(*frame);
    if (!edges.consistent()) {
      rejections_->reject("edge frame", "inconsistent_edge_arrays", "the edge arrays differ in length");
      return;
    }
    if (frame->class_names.size() > 32) {
      rejections_->reject("edge frame", "too_many_classes",
                          std::to_string(frame->class_names.size()) + " classes, a class mask holds 32");
      return;
    }
    FieldOptions options;
    {
      std::lock_guard<std::mutex> lock(options_mutex_);
      options = options_;
    }
    auto field = boost::make_shared<NearestNeighborField>();
    field->header = frame->header;
    moveFieldInto(buildNearestNeighborField(edges, static_cast<int>(frame->image.width),
                                            static_cast<int>(frame->image.height), frame->class_names, options),
                  field.get());
    field_publisher_.publish(NearestNeighborFieldConstPtr(field));
    tracer_.published(field_publisher_, field.get(), field->header.stamp);
  }

  std::mutex options_mutex_;  // guards options_ (live parameters change them)
  FieldOptions options_;
  std::unique_ptr<LiveParameters<NearestNeighborFieldConfig>> live_;
  std::unique_ptr<NodeletDiagnostics> diagnostics_;
  std::unique_ptr<InputRejections> rejections_;
  MessageTracer tracer_;
  ros::Publisher field_publisher_;
  ros::Subscriber frame_subscriber_;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::NearestNeighborFieldNodelet, nodelet::Nodelet)
