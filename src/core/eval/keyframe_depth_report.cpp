#include "semantic_edge_vo/eval/keyframe_depth_report.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "semantic_edge_vo/sequences/kitti_sequence.h"
#include "semantic_edge_vo/common/robust_statistics.h"
#include "semantic_edge_vo/synthetic/sequence_formats.h"

namespace semantic_edge_vo {

std::string KeyframeDepthReport::update(const std::shared_ptr<const Keyframe>& active,
                                        const std::vector<std::shared_ptr<const KeyframeWindow>>& windows) {
  if (!active) return "";
  if (newest_ && newest_->id == active->id) {
    newest_ = active;  // refined by the frames since
    return "";
  }
  // A new keyframe: the one before it has had all its frames, and the window the new one made.
  if (newest_ && !windows.empty())
    for (const auto& keyframe : windows.back()->keyframes)
      if (keyframe->id == newest_->id) newest_ = keyframe;
  finish(nullptr);
  const std::string error = load(*active, &newest_depth_);
  if (!error.empty()) return error;
  newest_ = active;
  check(*newest_, newest_depth_, false);
  return "";
}

void KeyframeDepthReport::finish(const std::shared_ptr<const Keyframe>& active) {
  if (active && newest_ && active->id == newest_->id) newest_ = active;
  if (!newest_) return;
  check(*newest_, newest_depth_, true);
  newest_.reset();
}

std::string KeyframeDepthReport::load(const Keyframe& keyframe, cv::Mat* depth) const {
  const std::string path = kittiFramePath(depth_folder_, static_cast<std::size_t>(keyframe.frame->index));
  if (!std::filesystem::exists(path)) return path + ": no such depth file";
  const cv::Mat encoded = cv::imread(path, cv::IMREAD_UNCHANGED);
  if (encoded.empty() || encoded.type() != CV_16UC1) return path + ": not a 16-bit depth PNG";
  if (keyframe.frame->pyramid) {
    const PinholeCamera& camera = keyframe.frame->pyramid->level(0).camera;
    if (encoded.cols != camera.width || encoded.rows != camera.height)
      return path + ": " + std::to_string(encoded.cols) + "x" + std::to_string(encoded.rows) + ", the images are " +
             std::to_string(camera.width) + "x" + std::to_string(camera.height);
  }
  *depth = synthetic::decodeDepth(encoded);
  return "";
}

void KeyframeDepthReport::check(const Keyframe& keyframe, const cv::Mat& depth, bool retired) {
  rows_.push_back({keyframe.frame->index, retired, checkDepths(keyframe.points, depth, tolerance_)});
}

std::string KeyframeDepthReport::table() const {
  std::ostringstream out;
  out << "# keyframe depths against the true depths, after dividing by the map scale (median estimated / true\n"
         "# depth of the edge points); wrong: below the lowest true depth around the pixel (3x3) / "
      << 1.0 + tolerance_ << " or above the highest x " << 1.0 + tolerance_
      << "\n# frame stage edges edges_wrong support support_wrong scale median_error\n";
  for (const Row& row : rows_)
    out << row.frame << ' ' << (row.retired ? "retired" : "new") << ' ' << row.check.edges << ' ' << row.check.edges_wrong
        << ' ' << row.check.support << ' ' << row.check.support_wrong << ' ' << row.check.scale << ' '
        << row.check.median_error << '\n';
  return out.str();
}

std::string KeyframeDepthReport::summary() const {
  std::ostringstream out;
  for (const bool retired : {false, true}) {
    std::vector<double> edges, support, errors;
    for (const Row& row : rows_) {
      if (row.retired != retired) continue;
      if (row.check.edges) edges.push_back(row.check.edgesWrongFraction());
      if (row.check.support) support.push_back(row.check.supportWrongFraction());
      if (row.check.edges + row.check.support) errors.push_back(row.check.median_error);
    }
    if (errors.empty()) continue;
    char line[200];
    std::snprintf(line, sizeof(line), "%s%s %zu: %.0f %% of edge and %.0f %% of supportive points wrong, median error %.1f %%",
                  out.tellp() > 0 ? "; " : "", retired ? "retired" : "new", errors.size(),
                  edges.empty() ? 0.0 : 100.0 * median(edges), support.empty() ? 0.0 : 100.0 * median(support),
                  100.0 * median(errors));
    out << line;
  }
  return out.str();
}

}  // namespace semantic_edge_vo
