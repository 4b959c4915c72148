#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace semantic_edge_vo {

/// A camera trajectory: poses T_world_cam (camera-to-world, metres) in frame order and, when the
/// source has them (TUM, a bag, KITTI with its times.txt), one time stamp per pose (seconds).
struct Trajectory {
  std::vector<Eigen::Isometry3d> poses;
  std::vector<double> stamps;  ///< empty, or one per pose, strictly increasing

  std::size_t size() const { return poses.size(); }
  bool hasStamps() const { return !stamps.empty(); }
};

/// Text formats of trajectory files (the conventions of the KITTI devkit, TUM RGB-D and evo).
enum class TrajectoryFormat {
  kKitti,  ///< 12 numbers a line: row-major 3x4 [R|t] of T_world_cam, no stamps
  kTum,    ///< 8 numbers a line: `timestamp tx ty tz qx qy qz qw` (seconds, metres, unit quaternion)
};
const char* toString(TrajectoryFormat format);
/// Parses "kitti" | "tum"; false on anything else.
bool parseTrajectoryFormat(const std::string& text, TrajectoryFormat* format);

/// Splits a line into whitespace-separated finite numbers; false with `error` naming the bad token.
bool parseNumbers(const std::string& line, std::vector<double>* numbers, std::string* error);

/// Called with the numbers of each data line; returns what is wrong with them, or "".
using RowHandler = std::function<std::string(const std::vector<double>& row)>;
/// Feeds every data line of `path` (blank and '#' lines skipped; each must have `columns` numbers)
/// to `handler`; returns "<path>:<line>: what is wrong", or "". A file without data lines is an
/// error unless `may_be_empty`.
std::string forEachRow(const std::string& path, std::size_t columns, const RowHandler& handler, bool may_be_empty = false);

// Readers skip blank lines and lines starting with '#' (as evo does), accept any whitespace between
// numbers and reject anything else. They return an empty string on success, otherwise
// "<path>:<line>: what is wrong"; on failure the output is left unchanged.

/// Reads a KITTI pose file. Rotation blocks must be orthonormal within 1e-3 with determinant +1;
/// they are kept as written (not re-orthonormalised) so that a written file reads back the same.
std::string readKittiPoses(const std::string& path, Trajectory* trajectory);
/// Reads a TUM trajectory file. Stamps must be strictly increasing; quaternions must have a norm
/// within 1e-2 of 1 and are normalised.
std::string readTumTrajectory(const std::string& path, Trajectory* trajectory);
/// Reads a KITTI times.txt: one strictly increasing time stamp (seconds) a line.
std::string readTimes(const std::string& path, std::vector<double>* stamps);
/// Reads the keyframes of a run: run_sequence's timing.txt (a '#' header line naming its columns,
/// `frame` first and a `keyframe` flag among them; words such as the state may stand in other
/// columns), or one frame number a line. Frame numbers, increasing.
std::string readKeyframeFrames(const std::string& path, std::vector<std::size_t>* frames);
/// Format of a trajectory file from the number of numbers on its first data line (12: KITTI, 8: TUM).
std::string detectTrajectoryFormat(const std::string& path, TrajectoryFormat* format);
/// Reads either format.
std::string readTrajectory(const std::string& path, TrajectoryFormat format, Trajectory* trajectory);

/// One KITTI line (no newline): 12 numbers, 10 significant digits, the devkit's `%e` style.
std::string kittiPoseLine(const Eigen::Isometry3d& T_world_cam);
/// One TUM line (no newline): stamp with 9 decimals (ns), position and quaternion (qw >= 0).
std::string tumPoseLine(double stamp, const Eigen::Isometry3d& T_world_cam);

// Writers return an empty string on success, otherwise what failed (naming the file).

std::string writeKittiPoses(const std::string& path, const Trajectory& trajectory);
/// Needs one stamp per pose.
std::string writeTumTrajectory(const std::string& path, const Trajectory& trajectory);
/// Writes `text` to `path` (replacing it).
std::string writeTextFile(const std::string& path, const std::string& text);
/// KITTI times.txt, fixed point with 9 decimals (ns), so that ROS epoch stamps keep their precision.
std::string writeTimes(const std::string& path, const std::vector<double>& stamps);

/// How far one pose of a trajectory file can be trusted.
struct PoseFlag {
  double stamp = 0.0;
  bool trusted = false;  ///< false: a prediction (lost, untrusted, waiting for the initialisation)
  std::string state;     ///< the odometry's state at the frame (one word)
};
/// The side file of a trajectory (poses_flags.txt): one line per pose of its KITTI and TUM files,
/// in the same order, `index stamp trusted state`, under a '#' header saying so.
std::string writePoseFlags(const std::string& path, const std::vector<PoseFlag>& flags);

}  // namespace semantic_edge_vo
