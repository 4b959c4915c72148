#include "semantic_edge_vo/common/tracked_motions.h"

#include <fstream>
#include <iomanip>
#include <sstream>

#include "semantic_edge_vo/common/trajectory_io.h"

namespace semantic_edge_vo {
namespace {

constexpr std::size_t kColumns = 3 + 12 + 21;

std::string located(const std::string& path, int line, const std::string& what) {
  return path + ":" + std::to_string(line) + ": " + what;
}

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
  std::ifstream file(path);
  if (!file) return path + ": cannot open for reading";
  std::vector<TrackedMotion> result;
  std::string line, error;
  std::vector<double> numbers;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    if (!parseNumbers(line, &numbers, &error)) return located(path, line_number, error);
    if (numbers.size() != kColumns)
      return located(path, line_number, std::to_string(numbers.size()) + " numbers, expected " + std::to_string(kColumns));
    if (!isWholeNumber(numbers[0]) || !isWholeNumber(numbers[1]) || (numbers[2] != 0.0 && numbers[2] != 1.0))
      return located(path, line_number, "frame and keyframe_frame must be frame numbers, in_metres 0 or 1");
    TrackedMotion motion;
    motion.frame = static_cast<std::size_t>(numbers[0]);
    motion.keyframe_frame = static_cast<std::size_t>(numbers[1]);
    motion.in_metres = numbers[2] == 1.0;
    for (int r = 0, k = 3; r < 3; ++r)
      for (int c = 0; c < 4; ++c) motion.T_cam_kf.matrix()(r, c) = numbers[static_cast<std::size_t>(k++)];
    for (int r = 0, k = 15; r < 6; ++r)
      for (int c = r; c < 6; ++c) motion.covariance(r, c) = motion.covariance(c, r) = numbers[static_cast<std::size_t>(k++)];
    const Eigen::Matrix3d R = motion.T_cam_kf.linear();
    if (!(R.transpose() * R).isIdentity(1e-3) || R.determinant() < 0.0)
      return located(path, line_number, "T_cam_kf's rotation is not orthonormal");
    result.push_back(motion);
  }
  if (file.bad()) return path + ": read error";
  *motions = std::move(result);
  return "";
}

}  // namespace semantic_edge_vo
