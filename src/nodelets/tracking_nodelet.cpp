// Tracking: SemanticEdgeFrame + NearestNeighborField (paired by stamp) -> the odometry (core
// Odometry: initialisation, frame-to-keyframe tracking and its checks; its mapping runs in the
// Mapping nodelet, reached through NodeletMappingLink) -> tf odom -> base_link and
// nav_msgs/Odometry for every trusted pose, TrackingStatus for every frame, TrackedFrame for the path.
#include <atomic>
#include <mutex>
#include <optional>
#include <utility>

#include <message_filters/subscriber.h>
#include <message_filters/time_synchronizer.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <std_srvs/Trigger.h>

#include "semantic_edge_vo/NearestNeighborField.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/TrackingConfig.h"
#include "semantic_edge_vo/TrackingStatus.h"
#include "semantic_edge_vo/backend/odometry.h"
#include "semantic_edge_vo/backend/trajectory_record.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/live_parameters.h"
#include "semantic_edge_vo/ros/map_files.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/nodelet_diagnostics.h"
#include "semantic_edge_vo/ros/nodelet_mapping_link.h"
#include "semantic_edge_vo/ros/odometry_message.h"
#include "semantic_edge_vo/ros/odometry_tf.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"
#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {

/// LiveTuning and the generated TrackingConfig (cfg/Tracking.cfg) name their fields alike.
template <typename From, typename To>
void copyTuning(const From& from, To* to) {
  to->photometric_huber = from.photometric_huber;
  to->edge_huber = from.edge_huber;
  to->keyframe_flow = from.keyframe_flow;
  to->keyframe_max_interval = from.keyframe_max_interval;
  to->keyframe_min_parallax = from.keyframe_min_parallax;
}

class TrackingNodelet : public nodelet::Nodelet {
 private:
  using Sync = message_filters::TimeSynchronizer<SemanticEdgeFrame, NearestNeighborField>;

  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    const RosParameterSource parameters(getPrivateNodeHandle());
    ParameterLoader loader(parameters);
    loader.load("use_edges", &use_edges_);
    std::string error = loadTfOptions(&loader, &tf_);
    LiveMappingOptions live_mapping;
    if (error.empty()) error = loadLiveMappingOptions(&loader, &live_mapping);
    if (error.empty()) parseMappingMode(live_mapping.mapping_mode, &mapping_mode_);
    if (error.empty()) error = loadOdometryOptions(&loader, &options_);
    tracer_.init(node, &loader, getName());
    NODELET_INFO_STREAM("parameters:" << loader.summary());
    warnUnknownParameters(loader, getName());
    if (error.empty()) error = parameters.error();
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    diagnostics_ = std::make_unique<NodeletDiagnostics>(node, getName());
    rejections_ = std::make_unique<InputRejections>(getName(), [this](const std::string&) { diagnostics_->dropped(); });
    odometry_messages_ = std::make_unique<OdometryMessageBuilder>(tf_.frames, tf_.max_twist_gap);
    odometry_tf_ = std::make_unique<OdometryTf>(tf_);
    if (tf_.publish_tf && !options_.road.enabled())
      NODELET_INFO_STREAM("publishing " << tf_.frames.odom_frame << " -> " << tf_.frames.base_frame
                                        << " in the odometry's arbitrary monocular scale (set camera_height for metres, "
                                           "publish_tf:=false for nav_msgs/Odometry only)");
    // The initialisation releases the poses of every frame that waited for it at once (up to
    // initializer/max_frames + 1): the queues hold such a burst several times over.
    const std::uint32_t burst = static_cast<std::uint32_t>(4 * (options_.initializer.max_frames + 1));
    odometry_publisher_ = node.advertise<nav_msgs::Odometry>("odometry", burst);
    status_publisher_ = node.advertise<TrackingStatus>("tracking_status", burst);
    tracked_publisher_ = node.advertise<TrackedFrame>("tracked_frame", burst);
    // Deep enough queues to absorb a slow frame (a keyframe) without dropping the next ones.
    frame_subscriber_.subscribe(node, "edge_frame", 20);
    field_subscriber_.subscribe(node, "nn_field", 20);
    sync_ = std::make_unique<Sync>(frame_subscriber_, field_subscriber_, 20);
    sync_->registerCallback(&TrackingNodelet::onFrame, this);
    reset_service_ = getPrivateNodeHandle().advertiseService("reset", &TrackingNodelet::onReset, this);
    save_service_ = getPrivateNodeHandle().advertiseService("save_trajectory", &TrackingNodelet::onSaveTrajectory, this);
    TrackingConfig live;
    copyTuning(LiveTuning::of(options_), &live);
    live_ = std::make_unique<LiveParameters<TrackingConfig>>(getPrivateNodeHandle(), live, [this](const TrackingConfig& config) {
      LiveTuning changed;
      copyTuning(config, &changed);
      std::lock_guard<std::mutex> lock(tuning_mutex_);
      pending_tuning_ = changed;  // taken by the frame callback, which owns the odometry
    });
  }

  bool onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
    restart_requested_ = true;  // served by the frame callback, which owns the odometry
    response.success = true;
    response.message = "the odometry initialises again from the next frame; odom continues where it is";
    NODELET_INFO_STREAM("reset: " << response.message);
    return true;
  }

  /// Every frame's camera pose since the odometry started (KITTI, TUM) and which to trust (poses_flags.txt).
  bool onSaveTrajectory(SaveFiles::Request& request, SaveFiles::Response& response) {
    TrajectoryRecord record;
    {
      std::lock_guard<std::mutex> lock(record_mutex_);
      record = record_;
    }
    serveSaveFiles(request, &response, [&](const std::string& directory, std::vector<std::string>* files) {
      return record.write(directory, files);
    });
    NODELET_INFO_STREAM("save_trajectory: " << record.size() << " poses: " << response.message);
    return true;
  }

  void onFrame(const SemanticEdgeFrameConstPtr& frame, const NearestNeighborFieldConstPtr& field) {
    const ros::WallTime start = ros::WallTime::now();
    diagnostics_->input(frame->header.seq);
    track(frame, field);
    diagnostics_->processed((ros::WallTime::now() - start).toSec() * 1e3);
  }

  void track(const SemanticEdgeFrameConstPtr& frame, const NearestNeighborFieldConstPtr& field) {
    tracer_.received(frame_subscriber_.getTopic(), frame.get(), frame->header.stamp);
    tracer_.received(field_subscriber_.getTopic(), field.get(), field->header.stamp);
    std::string error;
    const NearestNeighborFieldView fields = fieldView(*field, &error);
    if (error.empty()) error = fields.validate();
    if (error.empty() && static_cast<int>(fields.levels.size()) < options_.tracker.levels)
      error = "the field has " + std::to_string(fields.levels.size()) + " levels, tracking needs " +
              std::to_string(options_.tracker.levels);
    if (!error.empty()) {
      rejections_->reject("frame", "invalid_field", error);
      return;
    }
    const ros::Time previous = stamp_order_.last();
    const StampOrder::Verdict order = stamp_order_.accept(frame->header.stamp);
    if (order == StampOrder::Verdict::kNotIncreasing) {
      rejections_->reject("frame", "stamp_not_increasing", "the frame's stamp is not after the previous frame's");
      return;
    }
    const PinholeCamera camera = cameraFromInfo(frame->camera_info);
    const bool restart = order == StampOrder::Verdict::kRestart;
    if (!odometry_ || restart || camera.width != camera_.width || camera.height != camera_.height) {
      if (restart)
        NODELET_WARN_STREAM("the frames' stamps jumped back (from " << previous << " to " << frame->header.stamp
                                                                    << "): the odometry starts over, odom at the new first frame");
      else if (odometry_)
        NODELET_WARN_STREAM("the image size changed: the odometry starts over");
      // Frames still waiting for the old odometry's initialisation get their last status (no pose).
      if (odometry_)
        for (const FramePose& pose : odometry_->flush()) publishPose(pose);
      camera_ = camera;
      odometry_.reset();  // its link first: one odometry's requests at a time
      {
        std::lock_guard<std::mutex> lock(record_mutex_);
        if (record_.size() > 0) NODELET_INFO_STREAM("the saved trajectory starts over with the new odometry");
        record_.clear();
      }
      const auto stamp_of = [this](int index) {
        const auto recent = stamps_.find(index);
        return recent != stamps_.end() ? recent->second.header.stamp : ros::Time();
      };
      OdometryOptions options = options_;
      options.road.road_classes = roadClassBits(frame->class_names);  // the intake's table: Canny's has no road
      const CameraMounting& mounting = odometry_tf_->resolve(odometry_tf_->cameraFrameOf(frame->header.frame_id));
      if (options.road.enabled() && mounting.from_tf) {  // the mounting from tf, not the parameters
        options.road.setMounting(mounting.T_base_cam.linear());
        NODELET_INFO_STREAM("camera mounting against the road from tf (" << tf_.frames.base_frame << " -> " << odometry_tf_->cameraFrame()
                                                                         << "): pitch " << options.road.pitch_deg << " deg, roll "
                                                                         << options.road.roll_deg << " deg");
      }
      odometry_ = std::make_unique<Odometry>(
          options, camera_, mapping_mode_,
          std::make_shared<NodeletMappingLink>(getNodeHandle(), options, camera_, stamp_of, &class_names_, &tracer_));
      stamps_.clear();
      frame_count_ = 0;
      odometry_messages_->restart();
    }
    if (restart_requested_.exchange(false)) odometry_->restart();
    applyLiveTuning();
    if (fields.kind != field_kind_) {
      // The keyframes' points hold the old kind's layers: a new map, on the new kind's fields.
      if (frame_count_ > 0) NODELET_INFO_STREAM("the field kind changed to " << toString(fields.kind) << ": a new map");
      if (frame_count_ > 0) odometry_->restart();
      field_kind_ = fields.kind;
    }
    stamps_[frame_count_] = {frame->header, frame->class_map_age};
    class_names_ = frame->class_names;
    const auto odometry_frame =
        odometryFrameFrom(frame, use_edges_ ? field : NearestNeighborFieldConstPtr(), frame_count_++, options_.tracker.levels);
    std::vector<FramePose> poses;
    try {
      poses = odometry_->process(odometry_frame);
    } catch (const std::exception& e) {
      // A library assertion on input the checks above let through must not take the manager (and
      // every other nodelet in it) down: the frame is dropped, the odometry goes on.
      rejections_->reject("frame", "odometry_exception", e.what());
      return;
    }
    // A frame without a pose yet (it waits for the initialisation) still gets its status now.
    if (std::none_of(poses.begin(), poses.end(), [&](const FramePose& p) { return p.index == odometry_frame->index; }))
      publishStatus(frame->header, frame->class_map_age, nullptr);
    for (const FramePose& pose : poses) publishPose(pose);
    odometry_->takeNewWindows();  // the Mapping nodelet publishes them
    while (!stamps_.empty() && stamps_.begin()->first < frame_count_ - 100) stamps_.erase(stamps_.begin());
  }

  void publishPose(const FramePose& pose) {
    const auto recent = stamps_.find(pose.index);
    if (recent == stamps_.end()) return;
    const std_msgs::Header* header = &recent->second.header;
    const ros::Time stamp = header->stamp;
    {
      std::lock_guard<std::mutex> lock(record_mutex_);
      record_.add(pose, stamp.toSec());
    }
    publishStatus(*header, recent->second.class_map_age, &pose);
    if (!pose.trusted) return;  // never publish a pose that is not trusted

    const Eigen::Isometry3d& T_base_cam = odometry_tf_->mounting().T_base_cam;
    const Eigen::Isometry3d T_odom_base = baseInOdom(pose.T_world_cam, T_base_cam);
    odometry_tf_->publish(stamp, T_odom_base);
    const Matrix6d covariance = baseCovariance(pose.tracking.covariance, T_base_cam);
    odometry_publisher_.publish(
        nav_msgs::OdometryConstPtr(odometry_messages_->build(stamp, T_odom_base, covariance, pose.scale != ScaleState::kArbitrary)));

    auto tracked = boost::make_shared<TrackedFrame>();
    tracked->header.stamp = stamp;
    tracked->header.frame_id = "world";
    tracked->camera_frame_id = odometry_tf_->cameraFrame();
    tracked->pose_world_camera = toPoseMsg(pose.T_world_cam);
    tracked->pose_base_camera = toPoseMsg(T_base_cam);
    tracked->pose_trusted = true;
    tracked->keyframe_id = static_cast<std::uint32_t>(std::max(0, pose.keyframe_id));
    tracked->mean_flow_px = static_cast<float>(pose.tracking.mean_flow);
    tracked_publisher_.publish(TrackedFrameConstPtr(tracked));
    tracer_.published(tracked_publisher_, tracked.get(), stamp);
  }

  void publishStatus(const std_msgs::Header& header, float class_map_age, const FramePose* pose) {
    auto status = boost::make_shared<TrackingStatus>();
    status->header = header;
    status->class_map_age = class_map_age;
    const ScaleState scale = pose ? pose->scale : odometry_ ? odometry_->scaleState() : ScaleState::kArbitrary;
    status->scale_is_arbitrary = scale == ScaleState::kArbitrary;
    status->scale_state = toString(scale);
    if (pose) {
      status->scale_confidence = static_cast<float>(pose->scale_confidence);
      status->state = pose->state == OdometryState::kTracking ? (pose->recovered ? TrackingStatus::RECOVERED : TrackingStatus::TRACKING)
                      : pose->state == OdometryState::kLost      ? TrackingStatus::LOST
                      : pose->state == OdometryState::kUntrusted ? TrackingStatus::UNTRUSTED
                                                                 : TrackingStatus::INITIALIZING;
      status->pose_published = pose->trusted && tf_.publish_tf;
      status->keyframe_id = static_cast<std::uint32_t>(std::max(0, pose->keyframe_id));
      status->num_points = static_cast<std::uint32_t>(pose->tracking.points_in_view);
      status->num_edge_points = static_cast<std::uint32_t>(pose->tracking.edge_residuals);
      status->num_inliers = static_cast<std::uint32_t>(pose->tracking.photometric_inliers + pose->tracking.edge_inliers);
      status->photometric_rmse = static_cast<float>(pose->tracking.photometric_rmse);
      status->edge_rmse = static_cast<float>(pose->tracking.edge_rmse);
      status->iterations = static_cast<std::uint32_t>(pose->tracking.iterations);
      status->time_ms = static_cast<float>(pose->tracking_ms + pose->mapping_ms);
    } else {
      status->state = TrackingStatus::INITIALIZING;
    }
    status_publisher_.publish(TrackingStatusConstPtr(status));
    diagnostics_->set("tracking state", stateName(status->state));
    diagnostics_->set("scale state", status->scale_state);
    diagnostics_->set("scale confidence", std::to_string(status->scale_confidence));
    if (odometry_) diagnostics_->set("mapping requests dropped (total)", std::to_string(odometry_->mappingDropped()));
    if (status->state == TrackingStatus::LOST)
      diagnostics_->problem("lost", diagnostic_msgs::DiagnosticStatus::WARN, "tracking lost");
    else if (status->state == TrackingStatus::TRACKING || status->state == TrackingStatus::RECOVERED)
      diagnostics_->clear("lost");
  }

  static std::string stateName(std::uint8_t state) {
    switch (state) {
      case TrackingStatus::TRACKING: return "tracking";
      case TrackingStatus::LOST: return "lost";
      case TrackingStatus::RECOVERED: return "recovered";
      case TrackingStatus::UNTRUSTED: return "untrusted";
      default: return "initializing";
    }
  }

  /// Live parameters changed since the last frame: the odometry (and the next ones) take them.
  void applyLiveTuning() {
    std::optional<LiveTuning> tuning;
    {
      std::lock_guard<std::mutex> lock(tuning_mutex_);
      tuning = std::exchange(pending_tuning_, std::nullopt);
    }
    if (!tuning) return;
    OdometryOptions tuned = options_;
    tuning->applyTo(&tuned);
    if (const std::string error = tuned.validate(); !error.empty()) {
      NODELET_ERROR_STREAM("live parameters refused: " << error);
      return;
    }
    options_ = tuned;
    odometry_->tune(*tuning);
  }

  // Parameters (read in onInit, constant afterwards; options_'s live tuning changes in the frame callback).
  TfOptions tf_;
  bool use_edges_ = true;  ///< false: photometric-only odometry (the ablation's "none")
  OdometryOptions options_;
  MappingMode mapping_mode_ = MappingMode::kDeterministic;

  std::unique_ptr<NodeletDiagnostics> diagnostics_;
  std::unique_ptr<InputRejections> rejections_;
  std::unique_ptr<OdometryMessageBuilder> odometry_messages_;
  std::unique_ptr<OdometryTf> odometry_tf_;
  MessageTracer tracer_;
  message_filters::Subscriber<SemanticEdgeFrame> frame_subscriber_;
  message_filters::Subscriber<NearestNeighborField> field_subscriber_;
  std::unique_ptr<Sync> sync_;
  ros::Publisher odometry_publisher_, status_publisher_, tracked_publisher_;
  ros::ServiceServer reset_service_, save_service_;
  std::unique_ptr<LiveParameters<TrackingConfig>> live_;
  std::mutex tuning_mutex_;  // guards pending_tuning_ (set by the live parameters, taken by the frame callback)
  std::optional<LiveTuning> pending_tuning_;
  std::mutex record_mutex_;  // guards record_ (the frame callback adds, the save service reads)
  TrajectoryRecord record_;
  std::atomic<bool> restart_requested_{false};  ///< set by the reset service, taken by the frame callback

  // Frame callback only (the synchronizer calls it serially).
  PinholeCamera camera_;
  std::unique_ptr<Odometry> odometry_;
  FieldKind field_kind_ = FieldKind::kAnnf;  ///< of the last frame's field
  StampOrder stamp_order_{0.0};  ///< the intake passes frames in order: any step back is a new pass
  struct RecentFrame {
    std_msgs::Header header;
    float class_map_age;  ///< SemanticEdgeFrame::class_map_age
  };
  std::map<int, RecentFrame> stamps_;  ///< recent frames by odometry index (late poses)
  int frame_count_ = 0;
  std::vector<std::string> class_names_;  ///< of the latest frame (the intake's class table), for mapping
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::TrackingNodelet, nodelet::Nodelet)
