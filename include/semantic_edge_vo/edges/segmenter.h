#pragma once
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace semantic_edge_vo {

struct SegmenterOptions {
  std::string model_path;           ///< network file (weights)
  std::string config_path;          ///< second file some formats need (caffe prototxt, tensorflow pbtxt, darknet cfg)
  std::string format = "torch";     ///< torch | onnx | caffe | tensorflow | darknet
  int input_width = 1024;           ///< network input, px (ENet: a multiple of 32)
  int input_height = 320;           ///< network input, px
  std::array<double, 3> mean{{0.0, 0.0, 0.0}};  ///< subtracted from each channel before scaling, gray levels
  double scale = 1.0 / 255.0;       ///< multiplies (pixel - mean): 1/255 gives [0, 1]
  bool swap_rb = true;              ///< feed RGB (OpenCV images are BGR)
  /// Model output channel of each class of the class table, in table order; empty: class c reads
  /// output c + 1 (ENet's layout, output 0 = Unlabeled).
  std::vector<int> output_channels;
  /// cpu | cuda (OpenCV dnn's CUDA backend) | opencl (its OpenCL target): where this OpenCV lacks
  /// the one asked for, the network runs on the CPU and notice() says so.
  std::string backend = "cpu";

  std::string validate() const;
};

/// Per-pixel class probabilities from an OpenCV dnn segmentation network: softmax over all model
/// outputs at network resolution, the classes of the table picked by `output_channels` (so the
/// probabilities of dropped outputs such as Unlabeled are not redistributed), then upsampled
/// bilinearly to the image resolution.
class Segmenter {
 public:
  /// Loads the network. Check ok() / error().
  Segmenter(const SegmenterOptions& options, int classes);
  ~Segmenter();
  Segmenter(const Segmenter&) = delete;
  Segmenter& operator=(const Segmenter&) = delete;

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  /// What the network runs on ("cpu", "cuda", "opencl"), and why not on the backend asked for.
  const std::string& device() const { return device_; }
  const std::string& notice() const { return notice_; }

  /// @param[in] image CV_8UC3 (BGR) or CV_8UC1 (replicated to 3 channels)
  /// @param[in] depth CV_32F (probability) or CV_8U (probability x 255)
  /// @param[out] probabilities image-sized, `classes` interleaved channels of `depth`; written in
  ///             place when it already has that size and type (e.g. wrapping a message buffer)
  /// @return wall time of the whole call, ms
  double segment(const cv::Mat& image, int depth, cv::Mat* probabilities);
  /// The compact form (ClassEvidenceForm::kLabels): CV_8UC2 image-sized, (most probable class,
  /// its probability x 255), taken at the network's resolution and scaled up (nearest).
  /// @return wall time of the whole call, ms
  double segmentLabels(const cv::Mat& image, cv::Mat* labels);

 private:
  struct Network;
  void chooseBackend();
  /// Per class of the table, CV_32F at the network's output resolution.
  std::vector<cv::Mat> classProbabilities(const cv::Mat& image);
  SegmenterOptions options_;
  int classes_;
  std::vector<int> channels_;
  std::unique_ptr<Network> network_;
  std::string error_;
  std::string device_ = "cpu", notice_;
};

}  // namespace semantic_edge_vo
