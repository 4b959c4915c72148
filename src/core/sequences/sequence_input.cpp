#include "semantic_edge_vo/sequences/sequence_input.h"

#include <filesystem>

#include "semantic_edge_vo/sequences/semantic_map_files.h"

namespace semantic_edge_vo {

std::string SequenceInput::open(const std::string& directory, IntakeMode mode, const SegmenterOptions& segmenter,
                                int classes) {
  mode_ = mode;
  classes_ = classes;
  std::string error = openKittiSequence(directory, 0, &sequence_);
  if (!error.empty()) return error;
  if (sequence_.size() == 0) return directory + "/times.txt: no frame";
  cv::Mat first;
  error = readKittiImage(sequence_.imagePath(0), 0, &first);
  if (!error.empty()) return error;
  camera_ = sequence_.pinhole(first.cols, first.rows);
  has_colour_ = std::filesystem::is_directory(directory + "/image_2");
  const auto need = [&](const char* folder) {
    return std::filesystem::is_directory(directory + "/" + folder) ? std::string()
                                                                   : directory + "/" + folder + "/: missing (needed by this intake mode)";
  };
  if (mode == IntakeMode::kFused && segmenter.model_path.empty()) return need("class_probability");
  if (mode == IntakeMode::kSemanticEdges) return need("edge_bitmask");
  if (mode == IntakeMode::kFused) {
    segmenter_ = std::make_unique<Segmenter>(segmenter, classes);
    if (!segmenter_->ok()) return segmenter.model_path + ": " + segmenter_->error();
  }
  return {};
}

std::string SequenceInput::read(std::size_t frame, cv::Mat* gray, ClassEvidence* evidence) {
  std::string error = readKittiImage(sequence_.imagePath(frame), 0, gray);
  if (!error.empty() || mode_ == IntakeMode::kCanny) return error;
  evidence->classes = classes_;
  if (mode_ == IntakeMode::kSemanticEdges) {
    evidence->form = ClassEvidenceForm::kBitmask;
    return readEdgeBitmaskPng(kittiFramePath(sequence_.directory + "/edge_bitmask", frame), &evidence->values);
  }
  if (!segmenter_) {
    evidence->form = ClassEvidenceForm::kLabels;
    return readClassLabelsPng(kittiFramePath(sequence_.directory + "/class_probability", frame), &evidence->values);
  }
  cv::Mat image = *gray;
  if (has_colour_) {
    error = readKittiImage(kittiFramePath(sequence_.directory + "/image_2", frame), 2, &image);
    if (!error.empty()) return error;
  }
  evidence->form = ClassEvidenceForm::kProbabilities;
  segmenter_ms_ = segmenter_->segment(image, CV_8U, &evidence->values);
  return {};
}

}  // namespace semantic_edge_vo
