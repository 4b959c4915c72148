// Mapping: the odometry's backend and the maps it makes.
//  - The core MappingThread (keyframes, depth filtering of new points, the windowed optimisation)
//    answers the Tracking nodelet's requests on its own thread: mapping_request -> mapping_outcome,
//    shared pointers inside one manager. A request of a new session (a new odometry) starts a new mapper.
//  - A worker thread behind a bounded queue builds, from each window mapping makes, the KeyframeMap
//    and the semantic edge map (PointCloud2, voxel filtered and bounded: keyframes leaving the
//    window are committed to it), and from TrackedFrame the nav_msgs/Path.
#include <array>
#include <condition_variable>
#include <deque>
#include <map>
#include <thread>
#include <unordered_map>

#include <boost/make_shared.hpp>
#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/callback_queue.h>
#include <ros/spinner.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "semantic_edge_vo/KeyframeMap.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/backend/mapping_thread.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/ros/nodelet_diagnostics.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/map_files.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/ros/mapping_messages.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"
#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {

class MappingNodelet : public nodelet::Nodelet {
 public:
  ~MappingNodelet() override {
    // Requests first (they may start a mapper), then the mapper (it hands windows to the worker).
    if (request_spinner_) request_spinner_->stop();
    request_subscriber_.shutdown();
    {
      std::lock_guard<std::mutex> lock(session_mutex_);
      mapping_.reset();
    }
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      stopping_ = true;
    }
    queue_ready_.notify_all();
    if (worker_.joinable()) worker_.join();
  }

 private:
  /// A window mapping made, with what the KeyframeMap needs beside it.
  struct WindowJob {
    std::shared_ptr<const KeyframeWindow> window;
    ros::Time stamp;                       ///< of the frame whose request made it
    std::vector<ros::Time> keyframe_stamps;  ///< one per keyframe of the window
    PinholeCamera camera;
    std::vector<std::string> class_names;
  };
  struct Job {
    TrackedFrameConstPtr tracked;  ///< one of the two is set
    std::shared_ptr<const WindowJob> window;
  };
  struct MapPointOut {
    Eigen::Vector3f position;  ///< odom frame
    std::uint32_t label;       ///< class index in the intake's class table
    std::array<std::uint8_t, 3> rgb;
  };

  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    const RosParameterSource parameters(private_node);
    ParameterLoader loader(parameters);
    std::string error = loadMapOutputOptions(&loader, &options_);
    if (error.empty()) error = loadClassTable(&loader, &classes_);
    tracer_.init(node, &loader, getName());
    NODELET_INFO_STREAM("parameters:" << loader.summary() << "\n  classes: " << classes_.size());
    warnUnknownParameters(loader, getName());
    if (error.empty()) error = parameters.error();
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    diagnostics_ = std::make_unique<NodeletDiagnostics>(node, getName());
    rejections_ = std::make_unique<InputRejections>(getName(), [this](const std::string&) { diagnostics_->dropped(); });
    diagnostics_->beforePublishing([this] {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      diagnostics_->set("queue depth", std::to_string(queue_.size()) + " of " + std::to_string(options_.queue_size));
    });
    cloud_publisher_ = node.advertise<sensor_msgs::PointCloud2>("semantic_edge_map", 1, /*latch=*/true);
    path_publisher_ = node.advertise<nav_msgs::Path>("path", 1);
    map_publisher_ = node.advertise<KeyframeMap>("keyframe_map", 2, /*latch=*/true);
    outcome_publisher_ = node.advertise<MappingOutcomeMessage>("mapping_outcome", 1000);
    tracked_subscriber_ = node.subscribe("tracked_frame", 100, &MappingNodelet::onTrackedFrame, this);  // late poses come in bursts
    worker_ = std::thread(&MappingNodelet::run, this);
    save_service_ = private_node.advertiseService("save_map", &MappingNodelet::onSaveMap, this);
    // Requests on a thread of their own: tracking may wait for their outcomes in its callback, and
    // they must not wait for the manager's threads. Deep: the bound is the mapper's queue.
    ros::NodeHandle request_node(node);
    request_node.setCallbackQueue(&request_queue_);
    request_subscriber_ = request_node.subscribe("mapping_request", 1000, &MappingNodelet::onRequest, this);
    request_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &request_queue_);
    request_spinner_->start();
  }

  void onRequest(const boost::shared_ptr<const MappingRequestMessage>& message) {
    tracer_.received(request_subscriber_.getTopic(), message.get(), message->stamp);
    if (!message->request.frame || !message->options) {
      rejections_->reject("mapping request", "not_in_process",
                          "mapping requests carry frames only inside one process: load Tracking and Mapping in one nodelet manager");
      return;
    }
    std::lock_guard<std::mutex> lock(session_mutex_);
    const bool new_session = !mapping_ || message->session != session_;
    if (new_session) {
      if (mapping_) NODELET_INFO_STREAM("a new odometry: mapping starts a new map");
      mapping_.reset();  // finishes the request it is on
      session_ = message->session;
      const std::uint64_t session = session_;
      mapping_ = std::make_unique<MappingThread>(*message->options, message->camera,
                                                 [this, session](MappingOutcome outcome) { onOutcome(session, std::move(outcome)); });
    }
    {
      // Not held while posting: a full queue answers its oldest request (onOutcome) at once.
      std::lock_guard<std::mutex> stamps_lock(stamps_mutex_);
      if (new_session) stamps_.clear();
      stamps_[message->request.frame->index] = message->stamp;
      while (stamps_.size() > kRememberedStamps) stamps_.erase(stamps_.begin());
      camera_ = message->camera;
      class_names_ = message->class_names;
    }
    mapping_->post(message->request);
  }

  /// On the mapping thread: the outcome goes back to tracking at once, its window to the worker.
  void onOutcome(std::uint64_t session, MappingOutcome outcome) {
    auto message = boost::make_shared<MappingOutcomeMessage>();
    message->session = session;
    std::shared_ptr<WindowJob> job;
    {
      std::lock_guard<std::mutex> lock(stamps_mutex_);
      message->stamp = stampOf(outcome.frame_index);
      if (outcome.window) {
        job = std::make_shared<WindowJob>();
        job->window = outcome.window;
        job->stamp = message->stamp;
        for (const auto& keyframe : outcome.window->keyframes) job->keyframe_stamps.push_back(stampOf(keyframe->frame->index));
        job->camera = camera_;
        job->class_names = class_names_;
      }
    }
    if (!outcome.error.empty()) rejections_->reject("mapping request", "mapping_failed", outcome.error);
    message->outcome = std::move(outcome);
    outcome_publisher_.publish(boost::shared_ptr<const MappingOutcomeMessage>(message));
    tracer_.published(outcome_publisher_, message.get(), message->stamp);
    if (job) enqueue({nullptr, job});
  }

  ros::Time stampOf(int frame_index) const {
    const auto stamp = stamps_.find(frame_index);
    return stamp != stamps_.end() ? stamp->second : ros::Time();
  }

  void onTrackedFrame(const TrackedFrameConstPtr& tracked) {
    diagnostics_->input(tracked->header.seq);
    tracer_.received(tracked_subscriber_.getTopic(), tracked.get(), tracked->header.stamp);
    enqueue({tracked, nullptr});
  }

  void enqueue(Job job) {
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      if (static_cast<int>(queue_.size()) >= options_.queue_size) {
        queue_.pop_front();
        rejections_->reject("oldest queued message", "queue_full", "mapping is behind; raise queue_size or lower the rate");
      }
      queue_.push_back(std::move(job));
    }
    queue_ready_.notify_one();
  }

  void run() {
    while (true) {
      Job job;
      {
        std::unique_lock<std::mutex> lock(queue_mutex_);
        queue_ready_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (stopping_) return;
        job = std::move(queue_.front());
        queue_.pop_front();
      }
      const ros::WallTime start = ros::WallTime::now();
      if (job.tracked) extendPath(*job.tracked);
      if (job.window) updateMap(*keyframeMapOf(*job.window));
      diagnostics_->processed((ros::WallTime::now() - start).toSec() * 1e3);
    }
  }

  void extendPath(const TrackedFrame& tracked) {
    if (path_order_.accept(tracked.header.stamp) == StampOrder::Verdict::kRestart) {
      NODELET_WARN_STREAM("the tracked frames' stamps jumped back: the path starts over");
      path_.poses.clear();
    }
    T_base_cam_ = fromPoseMsg(tracked.pose_base_camera);
    const Eigen::Isometry3d& T_base_cam = T_base_cam_;
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = tracked.header.stamp;
    pose.header.frame_id = options_.odom_frame;
    pose.pose = toPoseMsg(baseInOdom(fromPoseMsg(tracked.pose_world_camera), T_base_cam));
    path_.header = pose.header;
    path_.poses.push_back(pose);
    if (static_cast<int>(path_.poses.size()) > options_.max_path_poses) path_.poses.erase(path_.poses.begin());
    path_publisher_.publish(path_);
  }

  /// Points of one keyframe in odom, edge points only (supportive points carry no class).
  /// Colour of a class of the intake's table: from the class table of the same name, white if none.
  std::array<std::uint8_t, 3> colourOf(const std::vector<std::string>& names, std::uint32_t label) const {
    const int index = label < names.size() ? classes_.indexOf(names[label]) : -1;
    return index >= 0 ? classes_[index].rgb : std::array<std::uint8_t, 3>{{255, 255, 255}};
  }

  std::vector<MapPointOut> pointsOf(const MapKeyframe& keyframe, const PinholeCamera& camera, const Eigen::Isometry3d& T_base_cam,
                                    const std::vector<std::string>& class_names) const {
    std::vector<MapPointOut> points;
    const Eigen::Isometry3d T_odom_cam = T_base_cam * fromPoseMsg(keyframe.pose_world_camera);
    for (std::size_t i = 0; i < keyframe.point_u.size(); ++i) {
      const std::uint32_t mask = keyframe.point_class_mask[i];
      if (!mask || !(keyframe.point_inverse_depth[i] > 0.0f)) continue;
      const Eigen::Vector3d p = camera.backProject(keyframe.point_u[i], keyframe.point_v[i], 1.0 / keyframe.point_inverse_depth[i]);
      const auto label = static_cast<std::uint32_t>(__builtin_ctz(mask));
      points.push_back({(T_odom_cam * p).cast<float>(), label, colourOf(class_names, label)});
    }
    return points;
  }

  /// The window as a KeyframeMap (the points whose depth is measured), published.
  KeyframeMapConstPtr keyframeMapOf(const WindowJob& job) {
    auto map = boost::make_shared<KeyframeMap>();
    map->header.stamp = job.stamp;
    map->header.frame_id = "world";
    for (std::size_t k = 0; k < job.window->keyframes.size(); ++k) {
      const Keyframe& keyframe = *job.window->keyframes[k];
      MapKeyframe message;
      message.id = static_cast<std::uint32_t>(keyframe.id);
      message.stamp = job.keyframe_stamps[k];
      message.pose_world_camera = toPoseMsg(keyframe.T_world_cam);
      for (const MapPoint& point : keyframe.points) {
        if (!point.hasDepth()) continue;
        message.point_u.push_back(point.u);
        message.point_v.push_back(point.v);
        message.point_inverse_depth.push_back(static_cast<float>(point.inverse_depth));
        message.point_inverse_depth_variance.push_back(static_cast<float>(point.inverse_depth_variance));
        message.point_class_mask.push_back(point.class_mask);
        message.point_normal_x.push_back(point.normal.x());
        message.point_normal_y.push_back(point.normal.y());
      }
      map->keyframes.push_back(std::move(message));
    }
    map->camera_info = cameraInfoOf(job.camera, "");
    map->class_names = job.class_names;
    map_publisher_.publish(KeyframeMapConstPtr(map));
    tracer_.published(map_publisher_, map.get(), job.stamp);
    return map;
  }

  /// Commits keyframes that left the window to the voxel map, then publishes voxels + window.
  void updateMap(const KeyframeMap& map) {
    if (map_order_.accept(map.header.stamp) == StampOrder::Verdict::kRestart) {
      NODELET_WARN_STREAM("the keyframe maps' stamps jumped back: the semantic edge map starts over");
      voxels_.clear();
      voxel_order_.clear();
      last_window_.clear();
    }
    const Eigen::Isometry3d& T_base_cam = T_base_cam_;
    const PinholeCamera camera = cameraFromInfo(map.camera_info);
    std::set<std::uint32_t> in_window;
    for (const MapKeyframe& keyframe : map.keyframes) in_window.insert(keyframe.id);
    for (const MapKeyframe& keyframe : last_window_)
      if (!in_window.count(keyframe.id))
        for (const MapPointOut& point : pointsOf(keyframe, last_camera_, T_base_cam, last_class_names_)) commit(point);
    last_window_ = map.keyframes;
    last_camera_ = camera;
    last_class_names_ = map.class_names;

    std::vector<MapPointOut> points;
    points.reserve(voxels_.size());
    for (const auto& entry : voxels_) points.push_back(entry.second);
    for (const MapKeyframe& keyframe : map.keyframes)
      for (const MapPointOut& point : pointsOf(keyframe, camera, T_base_cam, map.class_names)) points.push_back(point);
    publishCloud(points, map.header.stamp, map.class_names);
  }

  void commit(const MapPointOut& point) {
    const Eigen::Vector3i cell = (point.position / static_cast<float>(options_.voxel_size)).array().floor().cast<int>();
    const std::uint64_t key = (static_cast<std::uint64_t>(cell.x() & 0x1FFFFF) << 42) |
                              (static_cast<std::uint64_t>(cell.y() & 0x1FFFFF) << 21) | static_cast<std::uint64_t>(cell.z() & 0x1FFFFF);
    if (!voxels_.emplace(key, point).second) return;
    voxel_order_.push_back(key);
    while (static_cast<int>(voxel_order_.size()) > options_.max_map_points) {  // bounded: the oldest go first
      voxels_.erase(voxel_order_.front());
      voxel_order_.pop_front();
    }
  }

  void publishCloud(const std::vector<MapPointOut>& points, const ros::Time& stamp, const std::vector<std::string>& class_names) {
    auto cloud = boost::make_shared<sensor_msgs::PointCloud2>();
    cloud->header.stamp = stamp;
    cloud->header.frame_id = options_.odom_frame;
    sensor_msgs::PointCloud2Modifier modifier(*cloud);
    modifier.setPointCloud2Fields(5, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                  "z", 1, sensor_msgs::PointField::FLOAT32, "label", 1, sensor_msgs::PointField::UINT32,
                                  "rgb", 1, sensor_msgs::PointField::FLOAT32);
    modifier.resize(points.size());
    sensor_msgs::PointCloud2Iterator<float> x(*cloud, "x");
    sensor_msgs::PointCloud2Iterator<std::uint32_t> label(*cloud, "label");
    sensor_msgs::PointCloud2Iterator<std::uint8_t> rgb(*cloud, "rgb");  // packed b, g, r, a bytes
    for (const MapPointOut& point : points) {
      x[0] = point.position.x();
      x[1] = point.position.y();
      x[2] = point.position.z();
      *label = point.label;
      rgb[0] = point.rgb[2];
      rgb[1] = point.rgb[1];
      rgb[2] = point.rgb[0];
      rgb[3] = 255;
      ++x, ++label, ++rgb;
    }
    cloud_publisher_.publish(sensor_msgs::PointCloud2ConstPtr(cloud));
    std::lock_guard<std::mutex> lock(saved_mutex_);
    last_cloud_ = cloud;
    last_cloud_classes_ = class_names;
  }

  /// The semantic edge map as published last (committed voxels and the window), as PCD and PLY.
  bool onSaveMap(SaveFiles::Request& request, SaveFiles::Response& response) {
    sensor_msgs::PointCloud2ConstPtr cloud;
    std::vector<std::string> class_names;
    {
      std::lock_guard<std::mutex> lock(saved_mutex_);
      cloud = last_cloud_;
      class_names = last_cloud_classes_;
    }
    serveSaveFiles(request, &response, [&](const std::string& directory, std::vector<std::string>* files) {
      return cloud ? writeMapFiles(*cloud, class_names, directory, files) : std::string("no map yet: the odometry has not initialised");
    });
    NODELET_INFO_STREAM("save_map: " << (cloud ? cloud->width : 0u) << " points: " << response.message);
    return true;
  }

  // Parameters (read in onInit, constant afterwards).
  MapOutputOptions options_;
  ClassTable classes_;

  std::unique_ptr<NodeletDiagnostics> diagnostics_;
  std::unique_ptr<InputRejections> rejections_;
  MessageTracer tracer_;
  ros::Publisher cloud_publisher_, path_publisher_, map_publisher_, outcome_publisher_;
  ros::Subscriber tracked_subscriber_;
  ros::ServiceServer save_service_;
  std::mutex saved_mutex_;  // guards the last cloud (the worker publishes it, the save service reads it)
  sensor_msgs::PointCloud2ConstPtr last_cloud_;
  std::vector<std::string> last_cloud_classes_;

  // The requests' thread (the mapper's outcomes come on the mapping thread).
  ros::CallbackQueue request_queue_;
  ros::Subscriber request_subscriber_;
  std::unique_ptr<ros::AsyncSpinner> request_spinner_;
  std::mutex session_mutex_;  // guards session_ and mapping_
  std::uint64_t session_ = 0;
  std::unique_ptr<MappingThread> mapping_;
  std::mutex stamps_mutex_;  // guards stamps_, camera_ and class_names_
  /// Stamps of the session's recent frames by odometry index: the window's keyframes are among them.
  std::map<int, ros::Time> stamps_;
  static constexpr std::size_t kRememberedStamps = 2000;
  PinholeCamera camera_;
  std::vector<std::string> class_names_;

  std::mutex queue_mutex_;  // guards queue_ and stopping_
  std::condition_variable queue_ready_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::thread worker_;

  // Worker thread only.
  // Stamps going back mean the odometry started over (its input was played again): so do the path
  // and the map, each on its own topic's stamps (the two topics interleave in any order).
  StampOrder path_order_{0.0}, map_order_{0.0};
  Eigen::Isometry3d T_base_cam_ = opticalDefault();  ///< the camera's mounting, of the latest tracked frame
  nav_msgs::Path path_;
  std::vector<MapKeyframe> last_window_;
  PinholeCamera last_camera_;
  std::vector<std::string> last_class_names_;
  std::unordered_map<std::uint64_t, MapPointOut> voxels_;
  std::deque<std::uint64_t> voxel_order_;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::MappingNodelet, nodelet::Nodelet)
