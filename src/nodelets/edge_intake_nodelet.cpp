// EdgeIntake: image + camera_info (+ class map, + edge map) -> SemanticEdgeFrame (edges, classes,
// point sample). Raw images through image_transport, or sensor_msgs/CompressedImage decoded here.
#include <cstring>
#include <iomanip>
#include <mutex>

#include <cv_bridge/cv_bridge.h>
#include <image_transport/camera_common.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <opencv2/imgproc.hpp>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/image_encodings.h>

#include "semantic_edge_vo/EdgeIntakeConfig.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/frontend/point_sampler.h"
#include "semantic_edge_vo/edges/class_map_carrier.h"
#include "semantic_edge_vo/edges/semantic_edge_extractor.h"
#include "semantic_edge_vo/ros/camera_info_pairing.h"
#include "semantic_edge_vo/ros/class_input.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/frame_pairing.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/live_parameters.h"
#include "semantic_edge_vo/config/intake_options_loading.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/nodelet_diagnostics.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/rectifier.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"
#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {
namespace enc = sensor_msgs::image_encodings;

class EdgeIntakeNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    diagnostics_ = std::make_unique<NodeletDiagnostics>(node, getName());
    rejections_ = std::make_unique<InputRejections>(getName(), [this](const std::string& reason) { onRejected(reason); });
    const RosParameterSource parameters(private_node);
    ParameterLoader loader(parameters);
    IntakeStreamOptions stream;
    std::string error = loadIntakeStreamOptions(&loader, &stream);
    if (error.empty()) error = loadSemanticEdgeOptions(&loader, &options_);
    if (error.empty()) error = loadClassTable(&loader, &classes_);
    if (options_.mode == IntakeMode::kCanny) classes_ = ClassTable::singleEdgeClass();
    if (error.empty()) error = loadPointSamplerOptions(&loader, &sampler_options_);
    sampler_ = PointSampler(sampler_options_);
    tracer_.init(node, &loader, getName());
    NODELET_INFO_STREAM("parameters:" << loader.summary() << "\n  classes = " << classes_.size());
    warnUnknownParameters(loader, getName());
    if (error.empty()) error = parameters.error();
    if (error.empty()) parseClassEvidenceForm(stream.class_format, &class_form_);  // validated by the loader
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    rectify_ = stream.rectify;
    time_jump_back_ = stream.time_jump_back;
    fallback_to_canny_ = stream.on_missing_classes == "canny";
    carry_classes_ = options_.mode != IntakeMode::kCanny && stream.class_maps == "newest";
    carrier_ = ClassMapCarrier(stream.class_carry);
    stamp_order_ = StampOrder(time_jump_back_);
    const bool need_edges = options_.mode == IntakeMode::kFused && stream.edge_source == "topic";
    EdgeIntakeConfig live;
    live.max_edge_points = sampler_options_.max_edge_points;
    live.min_support_points = sampler_options_.min_support_points;
    live_ = std::make_unique<LiveParameters<EdgeIntakeConfig>>(private_node, live, [this](const EdgeIntakeConfig& config) {
      std::lock_guard<std::mutex> lock(mutex_);
      sampler_options_.max_edge_points = config.max_edge_points;
      sampler_options_.min_support_points = config.min_support_points;
      sampler_ = PointSampler(sampler_options_);
    });
    info_pairing_ = std::make_unique<CameraInfoPairing>(stream.camera_info_tolerance, stream.camera_info_wait,
                                                        static_cast<std::size_t>(stream.queue_size));
    image_timeout_ = stream.image_timeout;
    started_ = ros::WallTime::now();
    diagnostics_->beforePublishing([this] { watch(); });
    pairing_ = std::make_unique<FramePairing>(need_edges, stream.class_wait, static_cast<std::size_t>(stream.max_pending));
    frame_publisher_ = node.advertise<SemanticEdgeFrame>("edge_frame", 5);
    image_transport::ImageTransport image_transport(node);
    edge_image_publisher_ = image_transport.advertise("edge_image", 1);
    const auto queue = static_cast<std::uint32_t>(stream.queue_size);
    // camera_info beside the resolved (remapped) image topic, as image_transport names it.
    image_topic_ = node.resolveName("image");
    info_subscriber_ = node.subscribe(image_transport::getCameraInfoTopic(image_topic_), queue, &EdgeIntakeNodelet::onInfo, this);
    if (stream.transport == "raw")
      image_subscriber_ = image_transport.subscribe("image", queue, &EdgeIntakeNodelet::onRawImage, this);
    else
      compressed_subscriber_ = node.subscribe(image_topic_ + "/compressed", queue, &EdgeIntakeNodelet::onCompressedImage, this);
    pairing_timer_ = node.createWallTimer(ros::WallDuration(std::min(0.05, stream.camera_info_wait / 4)), &EdgeIntakeNodelet::onPairingTimer, this);
    if (options_.mode == IntakeMode::kCanny) return;
    const char* class_topic = options_.mode == IntakeMode::kFused ? "class_probabilities" : "class_edge_probabilities";
    class_subscriber_ = node.subscribe(class_topic, queue, &EdgeIntakeNodelet::onClasses, this);
    if (need_edges) edge_subscriber_ = node.subscribe("edge_probability", queue, &EdgeIntakeNodelet::onEdges, this);
    expiry_timer_ = node.createWallTimer(ros::WallDuration(std::min(0.05, stream.class_wait / 4)), &EdgeIntakeNodelet::onTimer, this);
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
    const PinholeCamera camera = cameraFromInfo(info);
    if (camera.width != static_cast<int>(image.width) || camera.height != static_cast<int>(image.height)) {
      *detail = "camera_info describes a " + std::to_string(camera.width) + "x" + std::to_string(camera.height) + " image (" +
                std::to_string(info.width) + "x" + std::to_string(info.height) + ", roi " + std::to_string(info.roi.width) + "x" +
                std::to_string(info.roi.height) + ", binning " + std::to_string(info.binning_x) + "x" + std::to_string(info.binning_y) +
                "), image is " + std::to_string(image.width) + "x" + std::to_string(image.height);
      return "size_mismatch";
    }
    const std::string camera_error = camera.validate();
    if (!camera_error.empty()) {
      *detail = "camera_info intrinsics (P, or K where P is unset): " + camera_error;
      return "invalid_camera_info";
    }
    return {};
  }

  void onCompressedImage(const sensor_msgs::CompressedImageConstPtr& compressed) {
    sensor_msgs::ImagePtr image;
    std::string detail;
    diagnostics_->input(compressed->header.seq);
    std::lock_guard<std::mutex> lock(mutex_);
    last_image_ = ros::WallTime::now();
    const std::string reason = decodeCompressedImage(*compressed, &image, &detail);
    if (!reason.empty()) {
      rejections_->reject("compressed image", reason, detail);
      return;
    }
    pair(info_pairing_->addImage(image, last_image_));
  }

  void onRawImage(const sensor_msgs::ImageConstPtr& image) {
    diagnostics_->input(image->header.seq);
    std::lock_guard<std::mutex> lock(mutex_);
    last_image_ = ros::WallTime::now();
    pair(info_pairing_->addImage(image, last_image_));
  }

  void onInfo(const sensor_msgs::CameraInfoConstPtr& info) {
    std::lock_guard<std::mutex> lock(mutex_);
    pair(info_pairing_->addInfo(info, ros::WallTime::now()));
  }

  void onPairingTimer(const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(mutex_);
    pair(info_pairing_->expire(ros::WallTime::now()));
  }

  /// Images leaving the camera_info pairing: with their camera_info on to the frame, without it dropped.
  void pair(const std::vector<CameraInfoPairing::Pair>& pairs) {
    for (const CameraInfoPairing::Pair& pair : pairs) {
      if (pair.info) {
        onImage(pair.image, pair.info);
        continue;
      }
      std::ostringstream detail;
      detail << "no camera_info on " << image_transport::getCameraInfoTopic(image_topic_)
             << " within camera_info_tolerance of the image's stamp " << pair.image->header.stamp << " (nor within camera_info_wait)";
      rejections_->reject("image", "no_camera_info", detail.str());
    }
  }

  /// Called with mutex_ held.
  void onImage(const sensor_msgs::ImageConstPtr& image, const sensor_msgs::CameraInfoConstPtr& info) {
    std::string detail;
    const std::string reason = check(*image, *info, &detail);
    if (!reason.empty()) {
      rejections_->reject("image", reason, detail);
      return;
    }
    if (rectify_) {
      if (const std::string problem = rectifier_.prepare(*info); !problem.empty()) {
        rejections_->reject("image", "invalid_camera_info", "cannot rectify: " + problem);
        return;
      }
    }
    const ros::Time previous = stamp_order_.last();
    switch (stamp_order_.accept(image->header.stamp)) {
      case StampOrder::Verdict::kNext: break;
      case StampOrder::Verdict::kNotIncreasing: {
        std::ostringstream text;
        text << "stamp " << image->header.stamp << " is not after the previous frame's " << previous << " (nor more than "
             << time_jump_back_ << " s before it, which would start the graph over)";
        rejections_->reject("image", "stamp_not_increasing", text.str());
        return;
      }
      case StampOrder::Verdict::kRestart: {
        // Frames still waiting for their class maps belong to the old pass: after the new one's they
        // would go out of stamp order.
        const std::size_t dropped = pairing_->clear();
        carrier_.clear();
        NODELET_WARN_STREAM("the input's stamps jumped back by " << (previous - image->header.stamp).toSec() << " s (from "
                            << previous << " to " << image->header.stamp << "; a bag played again?): the graph starts over"
                            << (dropped ? " (" + std::to_string(dropped) + " frames waiting for class maps dropped)" : ""));
        break;
      }
    }
    if (options_.mode == IntakeMode::kCanny || carry_classes_) {
      process(FramePairing::Frame{image, info, nullptr, nullptr, options_.mode == IntakeMode::kCanny});
      return;
    }
    handle(pairing_->addImage(image, info, ros::WallTime::now()));
  }

  void onClasses(const sensor_msgs::ImageConstPtr& classes) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (carry_classes_) takeClassMap(*classes);
    else handle(pairing_->addClasses(classes, ros::WallTime::now()));
  }

  /// class_maps newest: the map goes to the carrier, which takes it to the frames after its image.
  void takeClassMap(const sensor_msgs::Image& classes) {
    std::string detail;
    ClassEvidence evidence;
    if (const std::string reason = classEvidenceFromImage(classes, class_form_, classes_.size(), &evidence, &detail); !reason.empty()) {
      rejections_->reject("class map", reason, detail);
      return;
    }
    if (rectify_) {
      if (!rectifier_.ready()) {
        rejections_->reject("class map", "no_calibration", "a class map came before any image: it cannot be rectified yet");
        return;
      }
      cv::Mat rectified;
      rectifier_.rectify(evidence.values, &rectified, evidence.form != ClassEvidenceForm::kProbabilities);
      evidence.values = rectified;
    }
    if (!carrier_.setClassMap(classes.header.stamp.toSec(), evidence))
      NODELET_WARN_STREAM_THROTTLE(5.0, "the class map of " << classes.header.stamp << " is not of a recent image, or older than "
                                        "the newest map (class_carry/remembered_images): not used");
  }
  void onEdges(const sensor_msgs::ImageConstPtr& edges) {
    std::lock_guard<std::mutex> lock(mutex_);
    handle(pairing_->addEdges(edges, ros::WallTime::now()));
  }
  void onTimer(const ros::WallTimerEvent&) {
    std::lock_guard<std::mutex> lock(mutex_);
    handle(pairing_->expire(ros::WallTime::now()));
  }

  /// Frames leaving the pairing: complete ones are processed, the others dropped or made with Canny.
  void handle(const std::vector<FramePairing::Frame>& frames) {
    for (const FramePairing::Frame& frame : frames) {
      if (!frame.complete)
        NODELET_WARN_STREAM_THROTTLE(5.0, "no " << (frame.classes ? "edge map" : "class map") << " for the image of "
                                                << frame.image->header.stamp << " within class_wait: "
                                                << (fallback_to_canny_ ? "made with Canny, no class" : "dropped"));
      if (frame.complete || fallback_to_canny_) process(frame);
    }
  }

  void process(const FramePairing::Frame& input) {
    const ros::WallTime start = ros::WallTime::now();
    try {
      makeFrame(input);
      diagnostics_->processed((ros::WallTime::now() - start).toSec() * 1e3);
    } catch (const cv::Exception& e) {
      // An OpenCV assertion on input the checks let through must not take the manager (and every
      // nodelet in it) down: the frame is dropped, the intake goes on.
      rejections_->reject("image", "processing_failed", e.what());
    }
  }

  /// Edges of an incomplete frame (Canny, every class bit: the class is unknown) or of a complete one.
  void makeFrame(const FramePairing::Frame& input) {
    const sensor_msgs::Image& image = *input.image;
    cv_bridge::CvImageConstPtr gray_input;
    try {
      gray_input = cv_bridge::toCvShare(image, input.image, enc::MONO8);
    } catch (const cv_bridge::Exception& e) {
      rejections_->reject("image", "conversion_failed", e.what());
      return;
    }
    auto frame = boost::make_shared<SemanticEdgeFrame>();
    frame->header = image.header;
    frame->camera_info = rectify_ ? rectifier_.rectifiedInfo() : *input.info;
    frame->camera_info.header = input.info->header;
    frame->class_names = classes_.names();
    // The frame owns its grayscale image; write it in place and run the detectors on that buffer.
    frame->image.header = image.header;
    frame->image.width = image.width;
    frame->image.height = image.height;
    frame->image.encoding = enc::MONO8;
    frame->image.step = image.width;
    frame->image.data.resize(static_cast<std::size_t>(image.width) * image.height);
    cv::Mat gray(static_cast<int>(image.height), static_cast<int>(image.width), CV_8UC1, frame->image.data.data());
    if (rectify_) rectifier_.rectify(gray_input->image, &gray);  // same size and type: written in place
    else gray_input->image.copyTo(gray);

    EdgeSet edges;
    ClassEvidence evidence;  // views the class map message, or the carried map
    const SemanticEdgeExtractor extractor(options_);
    frame->class_map_age = input.complete && options_.mode != IntakeMode::kCanny ? 0.0f : -1.0f;
    if (carry_classes_ && carriedClasses(image.header.stamp, gray, &evidence, &frame->class_map_age)) {
      if (ExtractionError error = extractor.extract(gray, evidence, cv::Mat(), &edges)) {
        rejections_->reject("class map", error.reason, error.detail);
        return;
      }
      frame->intake_mode = toString(options_.mode);
    } else if (carry_classes_ && !fallback_to_canny_) {
      return;
    } else if (input.complete) {
      if (!extractEdges(input, gray, extractor, &edges, &evidence)) return;
      frame->intake_mode = toString(options_.mode);
    } else {
      edges = extractor.cannyEdges(gray, 0u);  // class unknown: matched in the all-edges layer
      frame->intake_mode = toString(IntakeMode::kCanny);
    }
    PointSample sample = sampler_.sample(gray, edges.view());
    frame->sampled_edges = std::move(sample.edge_indices);
    frame->support_u = std::move(sample.support_u);
    frame->support_v = std::move(sample.support_v);
    moveEdgesInto(std::move(edges), frame.get());

    if (edge_image_publisher_.getNumSubscribers() > 0) publishEdgeImage(*frame, gray);
    frame->header.seq = ++frames_published_;  // consecutive: the stages after count the frames lost on the way
    frame_publisher_.publish(SemanticEdgeFrameConstPtr(frame));
    tracer_.published(frame_publisher_, frame.get(), frame->header.stamp);
    diagnostics_->clear("camera_info");
  }

  /// Every refused input counts as dropped; a camera_info that does not describe the images is an
  /// error until a frame is made again.
  void onRejected(const std::string& reason) {
    diagnostics_->dropped();
    if (reason == "no_camera_info" || reason == "size_mismatch" || reason == "invalid_camera_info")
      diagnostics_->problem("camera_info", diagnostic_msgs::DiagnosticStatus::ERROR, "camera_info: " + reason);
  }

  /// The watchdog, before each diagnostics publication: images stopped (or never came).
  void watch() {
    std::lock_guard<std::mutex> lock(mutex_);
    diagnostics_->set("images waiting for camera_info", std::to_string(info_pairing_->waiting()));
    diagnostics_->set("images waiting for class maps", std::to_string(pairing_->pending()));
    const ros::WallTime now = ros::WallTime::now();
    const double silent = (now - (last_image_.isZero() ? started_ : last_image_)).toSec();
    if (silent < image_timeout_) {
      if (silence_logged_.isZero()) return;
      diagnostics_->clear("no_image");
      silence_logged_ = ros::WallTime();
      NODELET_INFO_STREAM("watchdog: images on " << image_topic_ << " again");
      return;
    }
    std::ostringstream message;
    message << "no image on " << image_topic_ << " for " << std::fixed << std::setprecision(1) << silent << " s"
            << (last_image_.isZero() ? " (none since the start)" : "");
    diagnostics_->problem("no_image", diagnostic_msgs::DiagnosticStatus::ERROR, message.str());
    // Logged when the silence starts, then every 30 s while it lasts.
    if (silence_logged_.isZero() || (now - silence_logged_).toSec() >= 30.0) {
      NODELET_ERROR_STREAM("watchdog: " << message.str());
      silence_logged_ = now;
    }
  }

  /// class_maps newest: the newest class map carried to the image, and its age; false when none is
  /// recent enough (warned: the frame is made with Canny edges of no class, or dropped).
  bool carriedClasses(const ros::Time& stamp, const cv::Mat& gray, ClassEvidence* evidence, float* age) {
    carrier_.addImage(stamp.toSec(), gray);
    double seconds = 0.0;
    if (carrier_.carryTo(stamp.toSec(), evidence, &seconds)) {
      *age = static_cast<float>(seconds);
      return true;
    }
    NODELET_WARN_STREAM_THROTTLE(5.0, "no class map within class_carry/max_age of the image of " << stamp << ": "
                                      << (fallback_to_canny_ ? "made with Canny, no class" : "dropped"));
    return false;
  }

  /// The edges with classes from the frame's maps (viewed in place); false when a map is refused.
  bool extractEdges(const FramePairing::Frame& input, const cv::Mat& gray, const SemanticEdgeExtractor& extractor,
                    EdgeSet* edges, ClassEvidence* evidence) {
    std::string detail;
    cv::Mat edge_probability;
    std::string reason;
    if (input.classes) reason = classEvidenceFromImage(*input.classes, class_form_, classes_.size(), evidence, &detail);
    if (!reason.empty()) {
      rejections_->reject("class map", reason, detail);
      return false;
    }
    if (input.edges) reason = edgeProbabilityFromImage(*input.edges, &edge_probability, &detail);
    if (!reason.empty()) {
      rejections_->reject("edge map", reason, detail);
      return false;
    }
    if (rectify_) {
      // The maps come in the raw image's geometry, as the image does: the same remap, without
      // blending class indices or bits, into new matrices (the views read the shared messages).
      cv::Mat rectified_classes, rectified_edges;  // empty where there is no map (canny mode)
      if (!evidence->values.empty())
        rectifier_.rectify(evidence->values, &rectified_classes, evidence->form != ClassEvidenceForm::kProbabilities);
      if (!edge_probability.empty()) rectifier_.rectify(edge_probability, &rectified_edges);
      evidence->values = rectified_classes;
      edge_probability = rectified_edges;
    }
    if (ExtractionError error = extractor.extract(gray, *evidence, edge_probability, edges)) {
      rejections_->reject("class map", error.reason, error.detail);
      return false;
    }
    return true;
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

  SemanticEdgeOptions options_;
  PointSamplerOptions sampler_options_;          ///< the config's, then live (guarded by mutex_)
  PointSampler sampler_{PointSamplerOptions()};  ///< set up in onInit
  std::unique_ptr<LiveParameters<EdgeIntakeConfig>> live_;
  ClassTable classes_;
  ClassEvidenceForm class_form_ = ClassEvidenceForm::kProbabilities;
  bool fallback_to_canny_ = true;
  bool carry_classes_ = false;  ///< class_maps newest (fused, semantic_edges)
  ClassMapCarrier carrier_;      ///< class_maps newest
  std::unique_ptr<NodeletDiagnostics> diagnostics_;
  std::unique_ptr<InputRejections> rejections_;
  MessageTracer tracer_;
  ros::Publisher frame_publisher_;
  image_transport::Publisher edge_image_publisher_;
  std::string image_topic_;  ///< resolved
  image_transport::Subscriber image_subscriber_;
  ros::Subscriber compressed_subscriber_, info_subscriber_, class_subscriber_, edge_subscriber_;
  ros::WallTimer expiry_timer_, pairing_timer_;
  double image_timeout_ = 3.0;  // s, IntakeStreamOptions::image_timeout
  std::mutex mutex_;  // guards everything below and serializes all callbacks (frames leave in stamp order)
  std::unique_ptr<CameraInfoPairing> info_pairing_;
  ros::WallTime started_, last_image_;
  ros::WallTime silence_logged_;  ///< when the watchdog last logged the current silence (zero: images flow)
  std::uint32_t frames_published_ = 0;
  std::unique_ptr<FramePairing> pairing_;
  bool rectify_ = false;  // IntakeStreamOptions::rectify
  Rectifier rectifier_;   // maps of the last calibration (rectify_ only)
  double time_jump_back_ = 1.0;  // s, IntakeStreamOptions::time_jump_back
  StampOrder stamp_order_{time_jump_back_};  // of the accepted images
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::EdgeIntakeNodelet, nodelet::Nodelet)
