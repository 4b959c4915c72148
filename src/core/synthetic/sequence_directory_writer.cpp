#include "semantic_edge_vo/synthetic/sequence_directory_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <ostream>


namespace semantic_edge_vo {
namespace synthetic {
namespace {

namespace fs = std::filesystem;

const char* const kImageFolders[] = {"image_0", "image_2", "depth", "semantic", "semantic_rgb", "dynamic"};
const char* const kSemanticFolders[] = {"edge_bitmask", "class_probability"};

void writeProjection(std::ostream& out, const char* name, const PinholeCamera& c) {
  out << name << std::scientific << std::setprecision(12) << ' ' << c.fx << ' ' << 0.0 << ' ' << c.cx << ' ' << 0.0 << ' '
      << 0.0 << ' ' << c.fy << ' ' << c.cy << ' ' << 0.0 << ' ' << 0.0 << ' ' << 0.0 << ' ' << 1.0 << ' ' << 0.0 << '\n';
}

void writeMetadata(std::ostream& out, const SyntheticSequenceOptions& options, int frames, const ClassTable& classes) {
  const NetworkNoiseOptions& noise = options.network_noise;
  out << "# Synthetic driving sequence (semantic_edge_vo make_synthetic_sequence); formats: docs/synthetic_sequences.md\n"
      << "format_version: 1\n"
      << "scene: " << toString(options.world.scene) << "\n"
      << "seed: " << options.world.seed << "\n"
      << "frames: " << frames << "\n"
      << "frame_rate: " << options.world.ego.frame_rate << "  # Hz\n"
      << "camera: {width: " << options.camera.width << ", height: " << options.camera.height << ", fx: " << options.camera.fx
      << ", fy: " << options.camera.fy << ", cx: " << options.camera.cx << ", cy: " << options.camera.cy << "}\n"
      << "camera_height: " << options.world.ego.camera_height << "  # m above the road\n"
      << "vibration: " << options.world.ego.vibration * 180.0 / M_PI << "  # pitch and roll jitter amplitude, deg\n";
  if (options.world.ego.stop_at >= 0.0)
    out << "stop: {at: " << options.world.ego.stop_at << ", duration: " << options.world.ego.stop_duration
        << "}  # the car brakes to a stop this far along its route, m, and stands this long, s\n";
  out << "depth_scale: " << kDepthScale << "  # depth PNG value / depth_scale = metres; 0 = sky or >= "
      << kMaxEncodedDepth << " m\n"
      << "semantics: " << (options.semantics ? "true" : "false") << "\n"
      << "network_noise: {label_confusion: " << noise.label_confusion << ", edge_blur: " << noise.edge_blur
      << ", missed_edges: " << noise.missed_edges << ", spurious_edges: " << noise.spurious_edges << "}\n"
      << "classes:  # index = Cityscapes train id = bit of the edge class masks; rgb of semantic_rgb\n";
  for (const SemanticClass& c : classes.classes())
    out << "  - {name: \"" << c.name << "\", rgb: [" << int(c.rgb[0]) << ", " << int(c.rgb[1]) << ", " << int(c.rgb[2])
        << "]}\n";
}

}  // namespace

SequenceDirectoryWriter::SequenceDirectoryWriter(const std::string& directory, const SyntheticSequenceOptions& options,
                                                 int frames)
    : directory_(directory), semantics_(options.semantics), classes_(ClassTable::cityscapes()) {
  std::error_code code;
  fs::create_directories(directory_, code);
  for (const char* folder : kImageFolders) fs::create_directories(fs::path(directory_) / folder, code);
  if (semantics_)
    for (const char* folder : kSemanticFolders) fs::create_directories(fs::path(directory_) / folder, code);
  if (code) {
    error_ = "cannot create " + directory_ + ": " + code.message();
    return;
  }
  std::ofstream calib(fs::path(directory_) / "calib.txt");
  writeProjection(calib, "P0:", options.camera);
  writeProjection(calib, "P2:", options.camera);  // the colour image shares the optical centre
  std::ofstream metadata(fs::path(directory_) / "synthetic.yaml");
  writeMetadata(metadata, options, frames, classes_);
  times_.open(fs::path(directory_) / "times.txt");
  poses_.open(fs::path(directory_) / "poses.txt");
  if (!calib || !metadata || !times_ || !poses_) error_ = "cannot write the text files in " + directory_;
}

bool SequenceDirectoryWriter::write(const SyntheticFrame& frame) {
  return write(frame, encodeFrame(frame, semantics_, classes_));
}

bool SequenceDirectoryWriter::write(const SyntheticFrame& frame, const EncodedFrame& files) {
  if (!error_.empty()) return false;
  char name[16];
  std::snprintf(name, sizeof(name), "%06d.png", frame.index);
  for (const auto& [folder, bytes] : files.files) {
    const fs::path path = fs::path(directory_) / folder / name;
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!file) {
      error_ = "cannot write " + path.string();
      return false;
    }
  }
  times_ << std::scientific << std::setprecision(6) << frame.time << '\n';
  const Eigen::Matrix<double, 3, 4> pose = frame.T_world_cam.matrix().topRows<3>();
  poses_ << std::scientific << std::setprecision(9);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) poses_ << pose(r, c) << (r == 2 && c == 3 ? '\n' : ' ');
  times_.flush();
  poses_.flush();
  if (!times_ || !poses_) error_ = "cannot append to times.txt or poses.txt in " + directory_;
  return error_.empty();
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
