// Segmenter: image -> per-pixel class probabilities (sensor_msgs/Image 32FC<C> or 8UC<C>) from an
// OpenCV dnn model, for the EdgeIntake's fused mode; reports its time per frame.
#include <sys/resource.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <memory>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <opencv2/core/utility.hpp>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>
#include <std_msgs/Float32.h>

#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/edges/segmenter.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/nodelet_diagnostics.h"
#include "semantic_edge_vo/config/intake_options_loading.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"

namespace semantic_edge_vo {
namespace enc = sensor_msgs::image_encodings;

class SegmenterNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    diagnostics_ = std::make_unique<NodeletDiagnostics>(node, getName());
    rejections_ = std::make_unique<InputRejections>(getName(), [this](const std::string&) { diagnostics_->dropped(); });
    const RosParameterSource parameters(private_node);
    ParameterLoader loader(parameters);
    SegmenterOptions options;
    std::string error = loadSegmenterOptions(&loader, &options);
    if (error.empty()) error = loadSegmenterOutputOptions(&loader, &output_);
    ClassTable classes;
    if (error.empty()) error = loadClassTable(&loader, &classes);
    NODELET_INFO_STREAM("parameters:" << loader.summary() << "\n  classes = " << classes.size());
    warnUnknownParameters(loader, getName());
    if (error.empty()) error = parameters.error();
    if (error.empty()) {
      segmenter_ = std::make_unique<Segmenter>(options, classes.size());
      error = segmenter_->error();
    }
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    if (output_.threads > 0) cv::setNumThreads(output_.threads);
    niceSession();
    if (!segmenter_->notice().empty()) NODELET_WARN_STREAM(segmenter_->notice());
    NODELET_INFO_STREAM("the network runs on: " << segmenter_->device());
    classes_ = classes.size();
    probability_publisher_ = node.advertise<sensor_msgs::Image>("class_probabilities", 2);
    time_publisher_ = node.advertise<std_msgs::Float32>("segmentation_time", 10);
    image_transport::ImageTransport transport(node);
    // Queue 1: a slow network keeps up by skipping frames, never by falling behind.
    image_subscriber_ = transport.subscribe("image", 1, &SegmenterNodelet::onImage, this);
  }

  /// roslaunch starts each node in a session of its own, and with the kernel's autogroups a nice
  /// level only ranks a process within its session: the process's nice level (the launch file's
  /// `nice` prefix) is given to its session too, so the odometry's process goes first.
  void niceSession() {
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, 0);
    if (errno != 0 || nice <= 0) return;
    std::ofstream autogroup("/proc/self/autogroup");
    if (!autogroup) return;  // no autogroups: the nice level alone ranks the processes
    autogroup << nice << std::flush;
    if (autogroup) NODELET_INFO_STREAM("nice " << nice << " for this process and its session (autogroup)");
    else NODELET_WARN_STREAM("could not set the session's (autogroup's) nice level to " << nice << ": the network may slow the odometry");
  }

  void onImage(const sensor_msgs::ImageConstPtr& image) {
    diagnostics_->input();  // not counted by sequence: skipping images is how the network keeps up
    static const std::set<std::string> kEncodings = {enc::MONO8, enc::BGR8, enc::RGB8, enc::BGRA8, enc::RGBA8, enc::MONO16};
    if (!kEncodings.count(image->encoding)) {
      rejections_->reject("image", "unsupported_encoding",
                          "encoding '" + image->encoding + "' (expected mono8, mono16, bgr8, rgb8, bgra8 or rgba8)");
      return;
    }
    cv_bridge::CvImageConstPtr input;
    try {
      input = cv_bridge::toCvShare(image, image->encoding == enc::MONO8 ? enc::MONO8 : enc::BGR8);
    } catch (const cv_bridge::Exception& e) {
      rejections_->reject("image", "conversion_failed", e.what());
      return;
    }
    // Written in place into the outgoing message.
    auto out = boost::make_shared<sensor_msgs::Image>();
    out->header = image->header;
    out->width = image->width;
    out->height = image->height;
    const bool labels = output_.output_format == "labels";
    const int depth = !labels && output_.output_bits == 32 ? CV_32F : CV_8U;
    const int channels = labels ? 2 : classes_;
    out->encoding = (depth == CV_32F ? "32FC" : "8UC") + std::to_string(channels);
    out->step = image->width * static_cast<std::uint32_t>(channels * (depth == CV_32F ? 4 : 1));
    out->data.resize(static_cast<std::size_t>(out->step) * out->height);
    cv::Mat classes(static_cast<int>(out->height), static_cast<int>(out->width), CV_MAKETYPE(depth, channels), out->data.data());
    double ms = 0.0;
    try {
      ms = labels ? segmenter_->segmentLabels(input->image, &classes) : segmenter_->segment(input->image, depth, &classes);
    } catch (const cv::Exception& e) {
      rejections_->reject("image", "segmentation_failed", e.what());
      return;
    }
    probability_publisher_.publish(sensor_msgs::ImageConstPtr(out));
    std_msgs::Float32 time;
    time.data = static_cast<float>(ms);
    time_publisher_.publish(time);
    diagnostics_->processed(ms);
    times_.push_back(ms);
    if (static_cast<int>(times_.size()) >= output_.log_every) {
      std::nth_element(times_.begin(), times_.begin() + static_cast<std::ptrdiff_t>(times_.size() / 2), times_.end());
      NODELET_INFO_STREAM("segmentation: median " << times_[times_.size() / 2] << " ms per frame over the last "
                                                  << times_.size() << " frames");
      times_.clear();
    }
  }

  std::unique_ptr<Segmenter> segmenter_;
  std::unique_ptr<NodeletDiagnostics> diagnostics_;
  std::unique_ptr<InputRejections> rejections_;
  int classes_ = 0;
  SegmenterOutputOptions output_;
  std::vector<double> times_;  // ms of the frames since the last log (the image callback is serialized)
  ros::Publisher probability_publisher_, time_publisher_;
  image_transport::Subscriber image_subscriber_;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::SegmenterNodelet, nodelet::Nodelet)
