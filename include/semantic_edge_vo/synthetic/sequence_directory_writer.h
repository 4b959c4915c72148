#pragma once
#include <fstream>
#include <string>

#include "semantic_edge_vo/synthetic/sequence_formats.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace synthetic {

/// Writes a synthetic sequence in the KITTI odometry layout plus the ground-truth and semantic
/// channels (docs/synthetic_sequences.md describes every file).
class SequenceDirectoryWriter {
 public:
  /// Creates `directory` and its sub-folders, writes calib.txt and synthetic.yaml. Check error().
  SequenceDirectoryWriter(const std::string& directory, const SyntheticSequenceOptions& options, int frames);

  /// Empty when fine, otherwise what failed (the writer then does nothing more).
  const std::string& error() const { return error_; }
  /// Writes the frame's files and appends to times.txt and poses.txt. Frames must come in order.
  bool write(const SyntheticFrame& frame);
  /// The same with the frame's PNG files encoded already (encodeFrame()).
  bool write(const SyntheticFrame& frame, const EncodedFrame& files);

 private:
  std::string directory_;
  bool semantics_;
  ClassTable classes_;
  std::ofstream times_, poses_;
  std::string error_;
};

}  // namespace synthetic
}  // namespace semantic_edge_vo
