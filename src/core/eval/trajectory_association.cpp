#include "semantic_edge_vo/eval/trajectory_association.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace semantic_edge_vo {
namespace {

void addPair(const Trajectory& gt, std::size_t gt_index, const Trajectory& est, std::size_t est_index,
             PosePairs* pairs) {
  pairs->gt.push_back(gt.poses[gt_index]);
  pairs->est.push_back(est.poses[est_index]);
  pairs->gt_index.push_back(gt_index);
}

}  // namespace

PosePairs associateByIndex(const Trajectory& gt, const Trajectory& est) {
  PosePairs pairs;
  for (std::size_t i = 0; i < std::min(gt.size(), est.size()); ++i) addPair(gt, i, est, i, &pairs);
  return pairs;
}

std::string associateByStamps(const Trajectory& gt, const Trajectory& est, double max_time_difference,
                              PosePairs* pairs) {
  if (gt.stamps.size() != gt.size() || est.stamps.size() != est.size() || gt.size() == 0 || est.size() == 0)
    return "association by time stamps needs a stamp for every pose of both trajectories";
  if (!(max_time_difference >= 0.0)) return "the maximum time difference must be >= 0 s";
  PosePairs result;
  std::size_t next = 0;  // first estimate pose not yet used; stamps increase in both
  for (std::size_t i = 0; i < gt.size() && next < est.size(); ++i) {
    const double stamp = gt.stamps[i];
    // First estimate stamp >= the ground-truth stamp, then the nearer of it and its predecessor.
    std::size_t j = static_cast<std::size_t>(
        std::lower_bound(est.stamps.begin() + static_cast<std::ptrdiff_t>(next), est.stamps.end(), stamp) -
        est.stamps.begin());
    if (j == est.size() || (j > next && stamp - est.stamps[j - 1] < est.stamps[j] - stamp)) --j;
    if (std::abs(est.stamps[j] - stamp) > max_time_difference) continue;
    addPair(gt, i, est, j, &result);
    next = j + 1;
  }
  if (result.gt.empty()) {
    std::ostringstream error;
    error.precision(15);
    error << "no estimate stamp lies within " << max_time_difference << " s of a ground-truth stamp (ground truth "
          << gt.stamps.front() << " .. " << gt.stamps.back() << " s, estimate " << est.stamps.front() << " .. "
          << est.stamps.back() << " s)";
    return error.str();
  }
  *pairs = std::move(result);
  return "";
}

PosePairs fromGroundTruthFrame(const PosePairs& pairs, std::size_t first_frame) {
  PosePairs kept;
  for (std::size_t i = 0; i < pairs.gt.size(); ++i) {
    if (pairs.groundTruthFrame(i) < first_frame) continue;
    kept.gt.push_back(pairs.gt[i]);
    kept.est.push_back(pairs.est[i]);
    kept.gt_index.push_back(pairs.groundTruthFrame(i));
  }
  return kept;
}

}  // namespace semantic_edge_vo
