#include "semantic_edge_vo/frontend/odometry_frame.h"
#include "semantic_edge_vo/common/class_table.h"

namespace semantic_edge_vo {

std::vector<MapPoint> candidatesFrom(const EdgeSetView& edges, const std::vector<std::uint32_t>& sampled_edges,
                                     const std::vector<float>& support_u, const std::vector<float>& support_v) {
  std::vector<MapPoint> candidates;
  candidates.reserve(sampled_edges.size() + support_u.size());
  for (std::uint32_t i : sampled_edges) {
    MapPoint point;
    point.u = edges.u[i];
    point.v = edges.v[i];
    point.class_mask = point.field_layers = edges.class_mask[i];
    point.normal = Eigen::Vector2f(edges.normal_x[i], edges.normal_y[i]);
    candidates.push_back(point);
  }
  for (std::size_t i = 0; i < support_u.size(); ++i) {
    MapPoint point;
    point.u = support_u[i];
    point.v = support_v[i];
    candidates.push_back(point);
  }
  return candidates;
}

std::string FrameBuilderOptions::validate() const {
  std::string error = intake.validate();
  if (error.empty()) error = sampler.validate();
  if (error.empty()) error = field.validate();
  if (error.empty() && (pyramid_levels < 1 || pyramid_levels > 8)) error = "pyramid_levels must be in [1, 8]";
  return error;
}

FrameBuilder::FrameBuilder(const FrameBuilderOptions& options, const PinholeCamera& camera,
                           std::vector<std::string> class_names)
    : options_(options), camera_(camera), class_names_(std::move(class_names)), sampler_(options.sampler) {
  options_.field.pyramid_levels = std::max(options_.field.pyramid_levels, options_.pyramid_levels);
}

std::shared_ptr<const OdometryFrame> FrameBuilder::build(int index, double time, const cv::Mat& gray,
                                                         const ClassEvidence& classes, ExtractionError* error) const {
  EdgeSet edges;
  const SemanticEdgeExtractor extractor(options_.intake);
  // A frame without a class map yet (a live segmenter's first frames) has Canny edges of no class,
  // as the EdgeIntake nodelet makes them.
  const bool classes_known = options_.intake.mode == IntakeMode::kCanny || !classes.values.empty();
  if (!classes_known) {
    edges = extractor.cannyEdges(gray, 0u);
  } else {
    *error = extractor.extract(gray, classes, cv::Mat(), &edges);
    if (*error) return nullptr;
  }
  const PointSample sample = sampler_.sample(gray, edges.view());

  auto frame = std::make_shared<OdometryFrame>();
  frame->index = index;
  frame->time = time;
  frame->classes_known = classes_known;
  frame->pyramid = std::make_shared<ImagePyramid>(gray, camera_, options_.pyramid_levels);
  frame->candidates = candidatesFrom(edges.view(), sample.edge_indices, sample.support_u, sample.support_v);
  if (options_.use_field) {
    auto field = std::make_shared<NearestNeighborFieldData>(
        buildNearestNeighborField(edges.view(), gray.cols, gray.rows, classNames(), options_.field));
    frame->field = field->view();
    frame->field_storage = field;
    frame->has_field = true;
  }
  return frame;
}

std::vector<std::string> FrameBuilder::classNames() const {
  return options_.intake.mode == IntakeMode::kCanny ? ClassTable::singleEdgeClass().names() : class_names_;
}

}  // namespace semantic_edge_vo
