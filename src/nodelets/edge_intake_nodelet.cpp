// EdgeIntake: image + camera_info -> SemanticEdgeFrame (edges, classes, point sample).
#include <cstring>
#include <mutex>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/image_encodings.h>

#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/canny_edge_detector.h"
#include "semantic_edge_vo/class_table.h"
#include "semantic_edge_vo/point_sampler.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/options_loading.h"

namespace semantic_edge_vo {
namespace enc = sensor_msgs::image_encodings;

class EdgeIntakeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    rejections_ = std::make_unique<InputRejections>(getName());
    ParameterLoader loader(private_node);
    std::string mode = "canny";
    loader.load("mode", &mode, "(canny)");
    int queue_size = 5;
    loader.load("queue_size", &queue_size, "messages");
    std::string error = mode == "canny" ? "" : "mode '" + mode + "' is not available (supported: canny)";
    if (error.empty()) error = loadCannyOptions(&loader, &canny_options_);
    if (error.empty()) error = loadPointSamplerOptions(&loader, &sampler_options_);
    NODELET_INFO_STREAM("parameters:" << loader.summary());
    if (error.empty() && queue_size < 1) error = "queue_size must be >= 1";
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    classes_ = ClassTable::singleEdgeClass();
    tracer_.init(node, private_node, getName());
    frame_publisher_ = node.advertise<SemanticEdgeFrame>("edge_frame", 5);
    image_transport::ImageTransport transport(node);
    edge_image_publisher_ = transport.advertise("edge_image", 1);
    camera_subscriber_ = transport.subscribeCamera("image", static_cast<std::uint32_t>(queue_size),
                                                   &EdgeIntakeNodelet::onImage, this);
  }

  /// Empty when the pair can be used, else the reason's name; `detail` says what was expected.
  std::string check(const sensor_msgs::Image& image, const sensor_msgs::CameraInfo& info, std::string* detail) const {
    static const std::set<std::string> kEncodings = {enc::MONO8, enc::MONO16, enc::BGR8, enc::RGB8, enc::BGRA8, enc::RGBA8};
    if (image.width == 0 || image.height == 0 || image.data.empty()) {
      *detail = "image is " + std::to_string(image.width) + "x" + std::to_string(image.height) + " with " +
                std::to_string(image.data.size()) + " bytes";
      return "empty_image";
    }
    if (!kEncodings.count(image.encoding)) {
      *detail = "encoding '" + image.encoding + "' (expected mono8, mono16, bgr8, rgb8, bgra8 or rgba8)";
      return "unsupported_encoding";
    }
    if (image.data.size() < static_cast<std::size_t>(image.step) * image.height ||
        image.step < image.width * static_cast<std::uint32_t>(enc::numChannels(image.encoding) * enc::bitDepth(image.encoding) / 8)) {
      *detail = "step " + std::to_string(image.step) + " and " + std::to_string(image.data.size()) +
                " bytes do not hold a " + std::to_string(image.width) + "x" + std::to_string(image.height) + " " + image.encoding + " image";
      return "malformed_image";
    }
    if (info.width != image.width || info.height != image.height) {
      *detail = "camera_info is " + std::to_string(info.width) + "x" + std::to_string(info.height) + ", image is " +
                std::to_string(image.width) + "x" + std::to_string(image.height);
      return "size_mismatch";
    }
    const std::string camera_error = cameraFromInfo(info).validate();
    if (!camera_error.empty()) {
      *detail = "camera_info K: " + camera_error;
      return "invalid_camera_info";
    }
    if (!last_stamp_.isZero() && image.header.stamp <= last_stamp_) {
      std::ostringstream text;
      text << "stamp " << image.header.stamp << " is not after the previous frame's " << last_stamp_;
      *detail = text.str();
      return "stamp_not_increasing";
    }
    return {};
  }

  void onImage(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info) {
    std::string detail;
    const std::string reason = check(*image, *info, &detail);
    if (!reason.empty()) {
      rejections_->reject("image", reason, detail);
      return;
    }
    cv_bridge::CvImageConstPtr gray_input;
    try {
      gray_input = cv_bridge::toCvShare(image, enc::MONO8);
    } catch (const cv_bridge::Exception& e) {
      rejections_->reject("image", "conversion_failed", e.what());
      return;
    }
    last_stamp_ = image->header.stamp;

    auto frame = boost::make_shared<SemanticEdgeFrame>();
    frame->header = image->header;
    frame->camera_info = *info;
    frame->class_names = classes_.names();
    frame->intake_mode = "canny";
    // The frame owns its grayscale image; write it in place and run the detectors on that buffer.
    frame->image.header = image->header;
    frame->image.width = image->width;
    frame->image.height = image->height;
    frame->image.encoding = enc::MONO8;
    frame->image.step = image->width;
    frame->image.data.resize(static_cast<std::size_t>(image->width) * image->height);
    cv::Mat gray(static_cast<int>(image->height), static_cast<int>(image->width), CV_8UC1, frame->image.data.data());
    gray_input->image.copyTo(gray);

    EdgeSet edges = CannyEdgeDetector(canny_options_).detect(gray, 1u);
    PointSample sample = PointSampler(sampler_options_).sample(gray, edges.view());
    frame->sampled_edges = std::move(sample.edge_indices);
    frame->support_u = std::move(sample.support_u);
    frame->support_v = std::move(sample.support_v);
    moveEdgesInto(std::move(edges), frame.get());

    if (edge_image_publisher_.getNumSubscribers() > 0) publishEdgeImage(*frame, gray);
    frame_publisher_.publish(SemanticEdgeFrameConstPtr(frame));
    tracer_.published(frame_publisher_, frame.get(), frame->header.stamp);
  }

  /// The image dimmed, edges drawn in their class colour: what rviz shows as the edge image.
  void publishEdgeImage(const SemanticEdgeFrame& frame, const cv::Mat& gray) {
    cv_bridge::CvImage overlay(frame.header, enc::RGB8);
    cv::cvtColor(gray / 3, overlay.image, cv::COLOR_GRAY2RGB);
    for (std::size_t i = 0; i < frame.edge_u.size(); ++i) {
      const std::uint32_t mask = frame.edge_class_mask[i];
      const int c = mask ? __builtin_ctz(mask) : 0;
      const auto& rgb = c < classes_.size() ? classes_[c].rgb : classes_[0].rgb;
      overlay.image.at<cv::Vec3b>(static_cast<int>(frame.edge_v[i] + 0.5f), static_cast<int>(frame.edge_u[i] + 0.5f)) =
          cv::Vec3b(rgb[0], rgb[1], rgb[2]);
    }
    edge_image_publisher_.publish(overlay.toImageMsg());
  }

  CannyOptions canny_options_;
  PointSamplerOptions sampler_options_;
  ClassTable classes_;
  std::unique_ptr<InputRejections> rejections_;
  MessageTracer tracer_;
  ros::Publisher frame_publisher_;
  image_transport::Publisher edge_image_publisher_;
  image_transport::CameraSubscriber camera_subscriber_;
  ros::Time last_stamp_;  // stamp of the last accepted frame (the camera callback is serialized)
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::EdgeIntakeNodelet, nodelet::Nodelet)
