#include "semantic_edge_vo/experiments/edge_repeatability.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "semantic_edge_vo/support/json_text.h"
#include "semantic_edge_vo/fields/nearest_neighbor_field.h"

namespace semantic_edge_vo {
namespace {

/// A frame-i edge pixel that should reappear, and where it lands in frame j.
struct Candidate {
  std::uint32_t edge;
  float u, v;
};

/// Nearest (`nearest`) or farthest valid depth in the 3x3 neighbourhood of (x, y); 0 when none.
float neighbourhoodDepth(const cv::Mat& depth, int x, int y, bool nearest) {
  float best = 0.0f;
  for (int yy = std::max(0, y - 1); yy <= std::min(depth.rows - 1, y + 1); ++yy)
    for (int xx = std::max(0, x - 1); xx <= std::min(depth.cols - 1, x + 1); ++xx) {
      const float d = depth.at<float>(yy, xx);
      if (d > 0.0f && (best == 0.0f || (nearest ? d < best : d > best))) best = d;
    }
  return best;
}

bool dynamicNear(const cv::Mat& dynamic, int x, int y) {
  if (dynamic.empty()) return false;
  for (int yy = std::max(0, y - 1); yy <= std::min(dynamic.rows - 1, y + 1); ++yy)
    for (int xx = std::max(0, x - 1); xx <= std::min(dynamic.cols - 1, x + 1); ++xx)
      if (dynamic.at<std::uint8_t>(yy, xx)) return true;
  return false;
}

std::vector<Candidate> eligibleEdges(const PinholeCamera& camera, const RepeatabilityFrame& first,
                                     const RepeatabilityFrame& second, const RepeatabilityOptions& options) {
  const Eigen::Isometry3d T_second_first = second.T_world_cam.inverse() * first.T_world_cam;
  const auto min_depth = static_cast<float>(options.min_depth);
  std::vector<Candidate> out;
  for (std::uint32_t i = 0; i < first.edges.size(); ++i) {
    const int x = static_cast<int>(std::lround(first.edges.u[i])), y = static_cast<int>(std::lround(first.edges.v[i]));
    if (!camera.contains(x, y) || dynamicNear(first.dynamic, x, y)) continue;
    const float depth = neighbourhoodDepth(first.depth, x, y, true);
    if (depth < min_depth) continue;
    const Eigen::Vector3d point = T_second_first * camera.backProject(first.edges.u[i], first.edges.v[i], depth);
    if (point.z() < options.min_depth) continue;
    const Eigen::Vector2d pixel = camera.project(point);
    if (!camera.contains(pixel.x(), pixel.y(), options.border)) continue;
    const float visible = neighbourhoodDepth(second.depth, static_cast<int>(std::lround(pixel.x())),
                                             static_cast<int>(std::lround(pixel.y())), false);
    if (visible < (1.0 - options.occlusion_tolerance) * point.z()) continue;  // occluded (or nothing there)
    out.push_back({i, static_cast<float>(pixel.x()), static_cast<float>(pixel.y())});
  }
  return out;
}

/// Number of SNNF layers the class masks need (the highest set bit + 1, at least 1).
int classLayers(const EdgeSetView& edges) {
  std::uint32_t all = 0;
  for (std::uint32_t mask : edges.class_mask) all |= mask;
  int layers = 1;
  while (layers < 32 && (all >> layers)) ++layers;
  return layers;
}

}  // namespace

std::string RepeatabilityOptions::validate() const {
  std::ostringstream error;
  if (sample_size < 1) error << "sample_size must be >= 1 (got " << sample_size << ")";
  else if (!(radius > 0.0 && radius <= 10.0)) error << "radius must be in (0, 10] px (got " << radius << ")";
  else if (!(min_depth > 0.0)) error << "min_depth must be > 0 m (got " << min_depth << ")";
  else if (!(occlusion_tolerance >= 0.0 && occlusion_tolerance < 1.0))
    error << "occlusion_tolerance must be in [0, 1) (got " << occlusion_tolerance << ")";
  else if (border < 0) error << "border must be >= 0 px (got " << border << ")";
  return error.str();
}

RepeatabilityCount& RepeatabilityCount::operator+=(const RepeatabilityCount& other) {
  edges += other.edges;
  eligible += other.eligible;
  sampled += other.sampled;
  repeated += other.repeated;
  same_class += other.same_class;
  return *this;
}

RepeatabilityCount measureRepeatability(const PinholeCamera& camera, const RepeatabilityFrame& first,
                                        const RepeatabilityFrame& second, const RepeatabilityOptions& options) {
  CV_Assert(first.depth.type() == CV_32FC1 && second.depth.type() == CV_32FC1);
  CV_Assert(first.depth.cols == camera.width && first.depth.rows == camera.height && second.depth.size() == first.depth.size());
  RepeatabilityCount count;
  count.edges = first.edges.size();
  std::vector<Candidate> candidates = eligibleEdges(camera, first, second, options);
  count.eligible = candidates.size();
  // A uniform random sample without replacement: the first `sampled` of a partial Fisher-Yates shuffle.
  std::mt19937_64 rng(options.seed);
  count.sampled = std::min(candidates.size(), static_cast<std::size_t>(options.sample_size));
  for (std::size_t k = 0; k < count.sampled; ++k)
    std::swap(candidates[k], candidates[std::uniform_int_distribution<std::size_t>(k, candidates.size() - 1)(rng)]);
  candidates.resize(count.sampled);

  FieldOptions field_options;
  field_options.pyramid_levels = 1;
  field_options.truncation_radius = static_cast<float>(options.radius);
  field_options.kind = FieldKind::kAnnf;
  const NearestNeighborFieldData any = buildNearestNeighborField(second.edges, camera.width, camera.height, {}, field_options);
  field_options.kind = FieldKind::kSnnf;
  const int layers = classLayers(second.edges);
  const NearestNeighborFieldData by_class = buildNearestNeighborField(
      second.edges, camera.width, camera.height, std::vector<std::string>(static_cast<std::size_t>(layers)), field_options);
  const NearestNeighborFieldView any_view = any.view(), class_view = by_class.view();

  FieldMatch match;
  for (const Candidate& c : candidates) {
    if (!any_view.nearest(0, 0, c.u, c.v, &match)) continue;
    ++count.repeated;
    const std::uint32_t mask = first.edges.class_mask[c.edge];
    for (int k = 0; k < layers; ++k)
      if ((mask >> k) & 1u && class_view.nearest(0, k, c.u, c.v, &match)) {
        ++count.same_class;
        break;
      }
  }
  return count;
}

std::string repeatabilityJson(const std::vector<RepeatabilityResult>& results, const RepeatabilityOptions& options,
                              const std::string& description) {
  std::ostringstream json;
  json.precision(6);
  json << "{\n  \"description\": " << jsonString(description) << ",\n  \"radius_px\": " << options.radius
       << ",\n  \"sample_size\": " << options.sample_size << ",\n  \"results\": [";
  for (std::size_t r = 0; r < results.size(); ++r) {
    const RepeatabilityResult& row = results[r];
    const RepeatabilityCount& c = row.count;
    json << (r ? ",\n" : "\n") << "    {\"scene\": " << jsonString(row.scene) << ", \"detector\": " << jsonString(row.detector)
         << ", \"frame_gap\": " << row.frame_gap << ", \"pairs\": " << row.pairs << ", \"edges_per_frame\": "
         << (row.pairs ? static_cast<double>(c.edges) / row.pairs : 0.0) << ", \"eligible\": " << c.eligible
         << ", \"sampled\": " << c.sampled << ", \"repeated\": " << c.repeated << ", \"repeatability\": " << c.rate()
         << ", \"same_class_repeatability\": ";
    if (row.semantic) json << c.classRate();
    else json << "null";
    json << "}";
  }
  json << "\n  ]\n}\n";
  return json.str();
}

}  // namespace semantic_edge_vo
