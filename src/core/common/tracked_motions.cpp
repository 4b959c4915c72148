#include "semantic_edge_vo/common/tracked_motions.h"

#include <iomanip>
#include <sstream>

#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace {

constexpr std::size_t kColumns = 3 + 12 + 21;

bool isWholeNumber(double value) { return value >= 0.0 && value == static_cast<double>(static_cast<std::size_t>(value)); }

}  // namespace

std::string writeTrackedMotions(const std::string& path, const std::vector<TrackedMotion>& motions) {
  std::ostringstream text;
  text << "# frame keyframe_frame in_metres T_cam_kf(row-major 3x4, 12) covariance(upper triangle, 21; xi = (v, w) in "
          "T_cam_kf = exp(xi) * T_cam_kf, camera axes)\n"
       << std::setprecision(9);
  for (const TrackedMotion& motion : motions) {
    text << motion.frame << ' ' << motion.keyframe_frame << ' ' << motion.in_metres;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) text << ' ' << motion.T_cam_kf.matrix()(r, c);
    for (int r = 0; r < 6; ++r)
      for (int c = r; c < 6; ++c) text << ' ' << motion.covariance(r, c);
    text << '\n';
  }
  return writeTextFile(path, text.str());
}

std::string readTrackedMotions(const std::string& path, std::vector<TrackedMotion>* motions) {
  std::vector<TrackedMotion> result;
  const std::string error = forEachRow(path, kColumns, [&](const std::vector<double>& numbers) {
    if (!isWholeNumber(numbers[0]) || !isWholeNumber(numbers[1]) || (numbers[2] != 0.0 && numbers[2] != 1.0))
      return std::string("frame and keyframe_frame must be frame numbers, in_metres 0 or 1");
    TrackedMotion motion;
    motion.frame = static_cast<std::size_t>(numbers[0]);
    motion.keyframe_frame = static_cast<std::size_t>(numbers[1]);
    motion.in_metres = numbers[2] == 1.0;
    for (int r = 0, k = 3; r < 3; ++r)
      for (int c = 0; c < 4; ++c) motion.T_cam_kf.matrix()(r, c) = numbers[static_cast<std::size_t>(k++)];
    for (int r = 0, k = 15; r < 6; ++r)
      for (int c = r; c < 6; ++c) motion.covariance(r, c) = motion.covariance(c, r) = numbers[static_cast<std::size_t>(k++)];
    const Eigen::Matrix3d R = motion.T_cam_kf.linear();
    if (!(R.transpose() * R).isIdentity(1e-3) || R.determinant() < 0.0) return std::string("T_cam_kf's rotation is not orthonormal");
    result.push_back(motion);
    return std::string();
  }, /*may_be_empty=*/true);  // a run without a trusted tracked frame
  if (!error.empty()) return error;
  *motions = std::move(result);
  return "";
}

}  // namespace semantic_edge_vo
