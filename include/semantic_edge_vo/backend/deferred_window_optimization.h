#pragma once
#include <deque>
#include <future>
#include <map>
#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "semantic_edge_vo/backend/keyframe.h"
#include "semantic_edge_vo/backend/window_optimizer.h"

namespace semantic_edge_vo {

/// The windowed optimisation on its own thread (DSO's mapping thread): it optimises a copy of the
/// window while tracking goes on. The caller merges the result at a frame it fixed in advance,
/// waiting if the thread is not done, so the trajectory does not depend on timing.
class DeferredWindowOptimization {
 public:
  struct Merge {
    std::map<int, Eigen::Isometry3d> corrections;  ///< per keyframe id: T_world_cam(new) * T_world_cam(old)^-1
    WindowOptimizerResult result;
    double optimization_ms = 0.0;  ///< time the thread spent optimising
    double waited_ms = 0.0;        ///< time finish() waited for it
  };

  /// @param[in] optimizer used from the thread (optimize() is const); must outlive this object
  explicit DeferredWindowOptimization(const WindowOptimizer& optimizer) : optimizer_(optimizer) {}
  ~DeferredWindowOptimization();
  DeferredWindowOptimization(const DeferredWindowOptimization&) = delete;
  DeferredWindowOptimization& operator=(const DeferredWindowOptimization&) = delete;

  bool running() const { return outcome_.valid(); }
  /// Starts optimising a copy of `window` (poses and point depths). Only when not running().
  void start(const std::deque<std::shared_ptr<Keyframe>>& window);
  /// Waits for the running optimisation and merges it into the keyframes of `window` with the same
  /// ids: their new poses, and the change of each point's inverse depth added to its current value
  /// (tracking kept refining the newest keyframe's depths meanwhile).
  Merge finish(const std::deque<std::shared_ptr<Keyframe>>& window);

 private:
  struct Outcome {
    std::vector<Keyframe> before, after;
    WindowOptimizerResult result;
    double ms = 0.0;
  };

  const WindowOptimizer& optimizer_;
  std::future<Outcome> outcome_;
};

}  // namespace semantic_edge_vo
