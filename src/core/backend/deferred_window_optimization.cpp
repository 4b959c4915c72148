#include "semantic_edge_vo/backend/deferred_window_optimization.h"

#include <chrono>

namespace semantic_edge_vo {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

DeferredWindowOptimization::~DeferredWindowOptimization() {
  if (running()) outcome_.wait();
}

void DeferredWindowOptimization::start(const std::deque<std::shared_ptr<Keyframe>>& window) {
  std::vector<Keyframe> before;
  for (const auto& keyframe : window) before.push_back(*keyframe);
  outcome_ = std::async(std::launch::async, [this, before = std::move(before)]() {
    const auto start = std::chrono::steady_clock::now();
    std::deque<std::shared_ptr<Keyframe>> copy;
    for (const Keyframe& keyframe : before) copy.push_back(std::make_shared<Keyframe>(keyframe));
    Outcome outcome;
    outcome.result = optimizer_.optimize(copy);
    for (const auto& keyframe : copy) outcome.after.push_back(std::move(*keyframe));
    outcome.before = std::move(before);
    outcome.ms = msSince(start);
    return outcome;
  });
}

DeferredWindowOptimization::Merge DeferredWindowOptimization::finish(const std::deque<std::shared_ptr<Keyframe>>& window) {
  Merge merge;
  if (!running()) return merge;
  const auto start = std::chrono::steady_clock::now();
  const Outcome outcome = outcome_.get();
  merge.waited_ms = msSince(start);
  merge.result = outcome.result;
  merge.optimization_ms = outcome.ms;
  if (!outcome.result.solved) return merge;
  for (std::size_t k = 0; k < outcome.before.size(); ++k) {
    const Keyframe &before = outcome.before[k], &after = outcome.after[k];
    for (const auto& live : window) {
      if (live->id != before.id) continue;
      const Eigen::Isometry3d correction = after.T_world_cam * before.T_world_cam.inverse();
      merge.corrections[live->id] = correction;
      live->T_world_cam = correction * live->T_world_cam;
      for (std::size_t i = 0; i < live->points.size() && i < before.points.size(); ++i) {
        const double updated = live->points[i].inverse_depth + after.points[i].inverse_depth - before.points[i].inverse_depth;
        if (updated > 0.0) live->points[i].inverse_depth = updated;
      }
    }
  }
  return merge;
}

}  // namespace semantic_edge_vo
