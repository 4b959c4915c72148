#include "semantic_edge_vo/common/trajectory_io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>

namespace semantic_edge_vo {
namespace {

constexpr double kRotationTolerance = 1e-3;    ///< max |R^T R - I| entry of a KITTI rotation block
constexpr double kQuaternionTolerance = 1e-2;  ///< max |norm - 1| of a TUM quaternion

std::string located(const std::string& path, int line_number, const std::string& message) {
  return path + ":" + std::to_string(line_number) + ": " + message;
}

bool isDataLine(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first != std::string::npos && line[first] != '#';
}


std::string checkIncreasing(const std::vector<double>& stamps, double stamp) {
  if (!stamps.empty() && stamp <= stamps.back()) {
    std::ostringstream error;
    error.precision(17);
    error << "time stamp " << stamp << " does not increase (previous " << stamps.back() << ")";
    return error.str();
  }
  return "";
}

/// Writes `count` lines, each made by `line(i)`, to `path`.
std::string writeLines(const std::string& path, std::size_t count, const std::function<std::string(std::size_t)>& line) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += line(i) + '\n';
  return writeTextFile(path, text);
}

}  // namespace

std::string forEachRow(const std::string& path, std::size_t columns, const RowHandler& handler, bool may_be_empty) {
  std::ifstream file(path);
  if (!file) return path + ": cannot open for reading";
  std::string line, error;
  std::vector<double> row;
  int line_number = 0, rows = 0;
  while (std::getline(file, line)) {
    ++line_number;
    if (!isDataLine(line)) continue;
    if (!parseNumbers(line, &row, &error)) return located(path, line_number, error);
    if (row.size() != columns)
      return located(path, line_number, "expected " + std::to_string(columns) + " numbers, found " +
                                            std::to_string(row.size()));
    error = handler(row);
    if (!error.empty()) return located(path, line_number, error);
    ++rows;
  }
  if (file.bad()) return path + ": read error";
  if (rows == 0 && !may_be_empty) return path + ": no data lines";
  return "";
}

bool parseNumbers(const std::string& line, std::vector<double>* numbers, std::string* error) {
  numbers->clear();
  std::istringstream tokens(line);
  std::string token;
  while (tokens >> token) {
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value)) {
      *error = "'" + token + "' is not a finite number";
      return false;
    }
    numbers->push_back(value);
  }
  return true;
}

const char* toString(TrajectoryFormat format) { return format == TrajectoryFormat::kKitti ? "kitti" : "tum"; }

bool parseTrajectoryFormat(const std::string& text, TrajectoryFormat* format) {
  if (text == "kitti") *format = TrajectoryFormat::kKitti;
  else if (text == "tum") *format = TrajectoryFormat::kTum;
  else return false;
  return true;
}

std::string readKittiPoses(const std::string& path, Trajectory* trajectory) {
  Trajectory result;
  const std::string error = forEachRow(path, 12, [&](const std::vector<double>& row) -> std::string {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) pose.matrix()(r, c) = row[static_cast<std::size_t>(4 * r + c)];
    const Eigen::Matrix3d rotation = pose.linear();
    const double orthonormality = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (orthonormality > kRotationTolerance || rotation.determinant() <= 0.0)
      return "the 3x3 block is not a rotation (|R^T R - I| = " + std::to_string(orthonormality) +
             ", det = " + std::to_string(rotation.determinant()) + ")";
    result.poses.push_back(pose);
    return "";
  });
  if (!error.empty()) return error;
  *trajectory = std::move(result);
  return "";
}

std::string readTumTrajectory(const std::string& path, Trajectory* trajectory) {
  Trajectory result;
  const std::string error = forEachRow(path, 8, [&](const std::vector<double>& row) -> std::string {
    const std::string order = checkIncreasing(result.stamps, row[0]);
    if (!order.empty()) return order;
    Eigen::Quaterniond orientation(row[7], row[4], row[5], row[6]);  // w, x, y, z
    if (std::abs(orientation.norm() - 1.0) > kQuaternionTolerance)
      return "quaternion norm " + std::to_string(orientation.norm()) + " is not 1";
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = orientation.normalized().toRotationMatrix();
    pose.translation() = Eigen::Vector3d(row[1], row[2], row[3]);
    result.stamps.push_back(row[0]);
    result.poses.push_back(pose);
    return "";
  });
  if (!error.empty()) return error;
  *trajectory = std::move(result);
  return "";
}

std::string readTimes(const std::string& path, std::vector<double>* stamps) {
  std::vector<double> result;
  const std::string error = forEachRow(path, 1, [&](const std::vector<double>& row) -> std::string {
    const std::string order = checkIncreasing(result, row[0]);
    if (order.empty()) result.push_back(row[0]);
    return order;
  });
  if (!error.empty()) return error;
  *stamps = std::move(result);
  return "";
}

std::string readKeyframeFrames(const std::string& path, std::vector<std::size_t>* frames) {
  std::ifstream file(path);
  if (!file) return path + ": cannot open for reading";
  std::vector<std::size_t> result;
  std::size_t flag_column = 0;  // 0: one frame number a line
  std::string line;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    std::istringstream words(line);
    std::vector<std::string> columns;
    for (std::string word; words >> word;) columns.push_back(word);
    if (columns.empty()) continue;
    if (columns[0][0] == '#') {
      if (columns[0] == "#") columns.erase(columns.begin());
      else columns[0].erase(0, 1);
      for (std::size_t c = 0; c < columns.size(); ++c)
        if (columns[c] == "keyframe") flag_column = c;
      continue;
    }
    if (columns.size() <= flag_column) return located(path, line_number, "fewer columns than the header names");
    char* end = nullptr;
    const long frame = std::strtol(columns[0].c_str(), &end, 10);
    if (*end != '\0' || frame < 0) return located(path, line_number, "'" + columns[0] + "' is not a frame number");
    if (flag_column > 0 && columns[flag_column] != "1") continue;
    if (!result.empty() && static_cast<std::size_t>(frame) <= result.back()) return located(path, line_number, "frame numbers must increase");
    result.push_back(static_cast<std::size_t>(frame));
  }
  if (file.bad()) return path + ": read error";
  *frames = std::move(result);
  return "";
}

std::string detectTrajectoryFormat(const std::string& path, TrajectoryFormat* format) {
  std::ifstream file(path);
  if (!file) return path + ": cannot open for reading";
  std::string line, error;
  std::vector<double> row;
  for (int line_number = 1; std::getline(file, line); ++line_number) {
    if (!isDataLine(line)) continue;
    if (!parseNumbers(line, &row, &error)) return located(path, line_number, error);
    if (row.size() == 12) *format = TrajectoryFormat::kKitti;
    else if (row.size() == 8) *format = TrajectoryFormat::kTum;
    else
      return located(path, line_number, std::to_string(row.size()) +
                                            " numbers: neither KITTI (12) nor TUM (8); give --format");
    return "";
  }
  return path + ": no data lines";
}

std::string readTrajectory(const std::string& path, TrajectoryFormat format, Trajectory* trajectory) {
  return format == TrajectoryFormat::kKitti ? readKittiPoses(path, trajectory) : readTumTrajectory(path, trajectory);
}

std::string kittiPoseLine(const Eigen::Isometry3d& T_world_cam) {
  std::string line;
  char number[32];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      std::snprintf(number, sizeof(number), "%.9e", T_world_cam.matrix()(r, c));
      if (!line.empty()) line += ' ';
      line += number;
    }
  return line;
}

std::string tumPoseLine(double stamp, const Eigen::Isometry3d& T_world_cam) {
  Eigen::Quaterniond q(T_world_cam.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d& t = T_world_cam.translation();
  char line[256];
  std::snprintf(line, sizeof(line), "%.9f %.10g %.10g %.10g %.10g %.10g %.10g %.10g", stamp, t.x(), t.y(), t.z(),
                q.x(), q.y(), q.z(), q.w());
  return line;
}

std::string writeTextFile(const std::string& path, const std::string& text) {
  std::ofstream file(path);
  if (!file) return path + ": cannot open for writing";
  file << text;
  file.close();
  if (!file) return path + ": write error";
  return "";
}

std::string writeKittiPoses(const std::string& path, const Trajectory& trajectory) {
  return writeLines(path, trajectory.size(), [&](std::size_t i) { return kittiPoseLine(trajectory.poses[i]); });
}

std::string writeTumTrajectory(const std::string& path, const Trajectory& trajectory) {
  if (trajectory.stamps.size() != trajectory.poses.size())
    return path + ": a TUM file needs one time stamp per pose (" + std::to_string(trajectory.stamps.size()) +
           " stamps, " + std::to_string(trajectory.poses.size()) + " poses)";
  return writeLines(path, trajectory.size(),
                    [&](std::size_t i) { return tumPoseLine(trajectory.stamps[i], trajectory.poses[i]); });
}

std::string writeTimes(const std::string& path, const std::vector<double>& stamps) {
  return writeLines(path, stamps.size(), [&](std::size_t i) {
    char number[48];
    std::snprintf(number, sizeof(number), "%.9f", stamps[i]);
    return std::string(number);
  });
}

std::string writePoseFlags(const std::string& path, const std::vector<PoseFlag>& flags) {
  std::ostringstream text;
  text << "# one line per pose of the trajectory's KITTI and TUM files, in their order: index stamp trusted state\n"
          "# trusted 0: not estimated with confidence (a prediction: lost, untrusted, or waiting for the initialisation)\n";
  char stamp[48];
  for (std::size_t i = 0; i < flags.size(); ++i) {
    std::snprintf(stamp, sizeof(stamp), "%.9f", flags[i].stamp);
    text << i << ' ' << stamp << ' ' << (flags[i].trusted ? 1 : 0) << ' ' << flags[i].state << '\n';
  }
  return writeTextFile(path, text.str());
}

}  // namespace semantic_edge_vo
