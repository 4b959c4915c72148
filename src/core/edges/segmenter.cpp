#include "semantic_edge_vo/edges/segmenter.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>

#include <opencv2/dnn.hpp>
#include <opencv2/imgproc.hpp>

namespace semantic_edge_vo {

struct Segmenter::Network {
  cv::dnn::Net net;
};

std::string SegmenterOptions::validate() const {
  std::ostringstream error;
  static const char* kFormats[] = {"torch", "onnx", "caffe", "tensorflow", "darknet"};
  if (std::find(std::begin(kFormats), std::end(kFormats), format) == std::end(kFormats))
    error << "format must be torch, onnx, caffe, tensorflow or darknet (got '" << format << "')";
  else if (input_width < 8 || input_height < 8) error << "input size must be at least 8x8 (got " << input_width << "x" << input_height << ")";
  else if (!(scale > 0.0)) error << "scale must be > 0 (got " << scale << ")";
  else if (backend != "cpu" && backend != "cuda" && backend != "opencl") error << "backend must be cpu, cuda or opencl (got '" << backend << "')";
  else
    for (int channel : output_channels)
      if (channel < 0) error << "output_channels must be >= 0 (got " << channel << ")";
  return error.str();
}

Segmenter::Segmenter(const SegmenterOptions& options, int classes)
    : options_(options), classes_(classes), network_(std::make_unique<Network>()) {
  error_ = options_.validate();
  if (error_.empty() && options_.model_path.empty()) error_ = "model_path is empty (set the network file)";
  if (error_.empty() && !std::filesystem::is_regular_file(options_.model_path))
    error_ = "model file '" + options_.model_path + "' does not exist";
  if (!error_.empty()) return;
  channels_ = options_.output_channels;
  if (channels_.empty())
    for (int c = 0; c < classes_; ++c) channels_.push_back(c + 1);
  if (static_cast<int>(channels_.size()) != classes_) {
    error_ = "output_channels names " + std::to_string(channels_.size()) + " channels for " + std::to_string(classes_) + " classes";
    return;
  }
  try {
    const std::string& model = options_.model_path;
    const std::string& config = options_.config_path;
    if (options_.format == "torch") network_->net = cv::dnn::readNetFromTorch(model);
    else if (options_.format == "onnx") network_->net = cv::dnn::readNetFromONNX(model);
    else if (options_.format == "caffe") network_->net = cv::dnn::readNetFromCaffe(config, model);
    else if (options_.format == "tensorflow") network_->net = cv::dnn::readNetFromTensorflow(model, config);
    else network_->net = cv::dnn::readNetFromDarknet(config, model);
  } catch (const cv::Exception& e) {
    error_ = "cannot load '" + options_.model_path + "' as " + options_.format + ": " + e.what();
    return;
  }
  if (network_->net.empty()) error_ = "'" + options_.model_path + "' holds no network";
  else chooseBackend();
}

void Segmenter::chooseBackend() {
  if (options_.backend == "cpu") return;
  const bool cuda = options_.backend == "cuda";
  const cv::dnn::Backend backend = cuda ? cv::dnn::DNN_BACKEND_CUDA : cv::dnn::DNN_BACKEND_OPENCV;
  const cv::dnn::Target target = cuda ? cv::dnn::DNN_TARGET_CUDA : cv::dnn::DNN_TARGET_OPENCL;
  const std::vector<cv::dnn::Target> targets = cv::dnn::getAvailableTargets(backend);
  if (std::find(targets.begin(), targets.end(), target) == targets.end()) {
    notice_ = "backend " + options_.backend + ": this OpenCV (" + CV_VERSION + ") has no " +
              (cuda ? "CUDA backend (built without CUDA and cuDNN)" : "OpenCL device") + "; the network runs on the CPU";
    return;
  }
  network_->net.setPreferableBackend(backend);
  network_->net.setPreferableTarget(target);
  device_ = options_.backend;
}

Segmenter::~Segmenter() = default;

std::vector<cv::Mat> Segmenter::classProbabilities(const cv::Mat& image) {
  CV_Assert(ok() && (image.type() == CV_8UC3 || image.type() == CV_8UC1));
  cv::Mat bgr = image;
  if (image.channels() == 1) cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  const cv::Size input(options_.input_width, options_.input_height);
  const cv::Scalar mean(options_.mean[0], options_.mean[1], options_.mean[2]);
  network_->net.setInput(cv::dnn::blobFromImage(bgr, options_.scale, input, mean, options_.swap_rb, false));
  const cv::Mat scores = network_->net.forward();  // 1 x outputs x h x w
  CV_Assert(scores.dims == 4 && scores.size[0] == 1);
  const int outputs = scores.size[1], h = scores.size[2], w = scores.size[3];
  for (int channel : channels_)
    if (channel >= outputs) CV_Error(cv::Error::StsOutOfRange, "output channel " + std::to_string(channel) +
                                                                   " beyond the model's " + std::to_string(outputs));
  // Softmax over the outputs, planes of h x w: subtract the per-pixel maximum for stability.
  std::vector<cv::Mat> planes(static_cast<std::size_t>(outputs));
  for (int k = 0; k < outputs; ++k)
    planes[static_cast<std::size_t>(k)] = cv::Mat(h, w, CV_32F, const_cast<float*>(scores.ptr<float>(0, k)));
  cv::Mat maximum = planes[0].clone(), sum(h, w, CV_32F, cv::Scalar(0));
  for (int k = 1; k < outputs; ++k) cv::max(maximum, planes[static_cast<std::size_t>(k)], maximum);
  std::vector<cv::Mat> exponentials(static_cast<std::size_t>(outputs));
  for (int k = 0; k < outputs; ++k) {
    cv::exp(planes[static_cast<std::size_t>(k)] - maximum, exponentials[static_cast<std::size_t>(k)]);
    sum += exponentials[static_cast<std::size_t>(k)];
  }
  const cv::Mat inverse_sum = 1.0 / sum;
  std::vector<cv::Mat> selected(static_cast<std::size_t>(classes_));
  for (int c = 0; c < classes_; ++c)
    selected[static_cast<std::size_t>(c)] = exponentials[static_cast<std::size_t>(channels_[static_cast<std::size_t>(c)])].mul(inverse_sum);
  return selected;
}

double Segmenter::segment(const cv::Mat& image, int depth, cv::Mat* probabilities) {
  CV_Assert(depth == CV_32F || depth == CV_8U);
  const auto start = std::chrono::steady_clock::now();
  std::vector<cv::Mat> selected = classProbabilities(image);
  for (cv::Mat& probability : selected) {
    cv::resize(probability, probability, image.size(), 0, 0, cv::INTER_LINEAR);
    if (depth == CV_8U) probability.convertTo(probability, CV_8U, 255.0);
  }
  probabilities->create(image.size(), CV_MAKETYPE(depth, classes_));
  cv::merge(selected, *probabilities);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double Segmenter::segmentLabels(const cv::Mat& image, cv::Mat* labels) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<cv::Mat> selected = classProbabilities(image);
  // The most probable class at the network's resolution, then nearest up to the image's: 19
  // interpolated planes would cost more than the labels are worth.
  const cv::Size size = selected.front().size();
  cv::Mat best(size, CV_8UC2);
  for (int y = 0; y < size.height; ++y) {
    cv::Vec2b* out = best.ptr<cv::Vec2b>(y);
    for (int x = 0; x < size.width; ++x) {
      int label = 0;
      float top = selected[0].ptr<float>(y)[x];
      for (int c = 1; c < classes_; ++c) {
        const float p = selected[static_cast<std::size_t>(c)].ptr<float>(y)[x];
        if (p > top) top = p, label = c;
      }
      out[x] = cv::Vec2b(static_cast<uchar>(label), cv::saturate_cast<uchar>(255.0f * top));
    }
  }
  labels->create(image.size(), CV_8UC2);
  cv::resize(best, *labels, image.size(), 0, 0, cv::INTER_NEAREST);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace semantic_edge_vo
