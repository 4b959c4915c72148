// Mapping: KeyframeMap and TrackedFrame from Tracking -> the semantic edge map (PointCloud2, voxel
// filtered and bounded: keyframes leaving the window are committed to it) and nav_msgs/Path.
// Work happens in an owned thread behind a bounded queue; callbacks only enqueue.
#include <array>
#include <condition_variable>
#include <deque>
#include <thread>
#include <unordered_map>

#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "semantic_edge_vo/KeyframeMap.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/common/class_table.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/config/live_options.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/ros/ros_parameter_source.h"
#include "semantic_edge_vo/ros/stamp_order.h"

namespace semantic_edge_vo {

class MappingNodelet : public nodelet::Nodelet {
 public:
  ~MappingNodelet() override {
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      stopping_ = true;
    }
    queue_ready_.notify_all();
    if (worker_.joinable()) worker_.join();
  }

 private:
  struct Job {
    TrackedFrameConstPtr tracked;  ///< one of the two is set
    KeyframeMapConstPtr map;
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
    rejections_ = std::make_unique<InputRejections>(getName());
    extrinsic_ = std::make_unique<CameraExtrinsic>(options_.frames.base_frame, 0.0);
    cloud_publisher_ = node.advertise<sensor_msgs::PointCloud2>("semantic_edge_map", 1, /*latch=*/true);
    path_publisher_ = node.advertise<nav_msgs::Path>("path", 1);
    tracked_subscriber_ = node.subscribe("tracked_frame", 100, &MappingNodelet::onTrackedFrame, this);  // late poses come in bursts
    map_subscriber_ = node.subscribe("keyframe_map", 2, &MappingNodelet::onKeyframeMap, this);
    worker_ = std::thread(&MappingNodelet::run, this);
  }

  void onTrackedFrame(const TrackedFrameConstPtr& tracked) {
    tracer_.received(tracked_subscriber_.getTopic(), tracked.get(), tracked->header.stamp);
    enqueue({tracked, nullptr});
  }
  void onKeyframeMap(const KeyframeMapConstPtr& map) {
    tracer_.received(map_subscriber_.getTopic(), map.get(), map->header.stamp);
    enqueue({nullptr, map});
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
      if (job.tracked) extendPath(*job.tracked);
      if (job.map) updateMap(*job.map);
    }
  }

  void extendPath(const TrackedFrame& tracked) {
    if (path_order_.accept(tracked.header.stamp) == StampOrder::Verdict::kRestart) {
      NODELET_WARN_STREAM("the tracked frames' stamps jumped back: the path starts over");
      path_.poses.clear();
    }
    camera_frame_ = tracked.camera_frame_id;
    const Eigen::Isometry3d T_base_cam = extrinsic_->baseFromCamera(camera_frame_);
    geometry_msgs::PoseStamped pose;
    pose.header.stamp = tracked.header.stamp;
    pose.header.frame_id = options_.frames.odom_frame;
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

  /// Commits keyframes that left the window to the voxel map, then publishes voxels + window.
  void updateMap(const KeyframeMap& map) {
    if (map_order_.accept(map.header.stamp) == StampOrder::Verdict::kRestart) {
      NODELET_WARN_STREAM("the keyframe maps' stamps jumped back: the semantic edge map starts over");
      voxels_.clear();
      voxel_order_.clear();
      last_window_.clear();
    }
    const Eigen::Isometry3d T_base_cam = extrinsic_->baseFromCamera(camera_frame_);
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
    publishCloud(points, map.header.stamp);
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

  void publishCloud(const std::vector<MapPointOut>& points, const ros::Time& stamp) {
    auto cloud = boost::make_shared<sensor_msgs::PointCloud2>();
    cloud->header.stamp = stamp;
    cloud->header.frame_id = options_.frames.odom_frame;
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
  }

  // Parameters (read in onInit, constant afterwards).
  MapOutputOptions options_;
  ClassTable classes_;

  std::unique_ptr<InputRejections> rejections_;
  std::unique_ptr<CameraExtrinsic> extrinsic_;  // worker thread only
  MessageTracer tracer_;
  ros::Publisher cloud_publisher_, path_publisher_;
  ros::Subscriber tracked_subscriber_, map_subscriber_;

  std::mutex queue_mutex_;  // guards queue_ and stopping_
  std::condition_variable queue_ready_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::thread worker_;

  // Worker thread only.
  // Stamps going back mean the odometry started over (its input was played again): so do the path
  // and the map, each on its own topic's stamps (the two topics interleave in any order).
  StampOrder path_order_{0.0}, map_order_{0.0};
  std::string camera_frame_;  ///< of the latest tracked frame
  nav_msgs::Path path_;
  std::vector<MapKeyframe> last_window_;
  PinholeCamera last_camera_;
  std::vector<std::string> last_class_names_;
  std::unordered_map<std::uint64_t, MapPointOut> voxels_;
  std::deque<std::uint64_t> voxel_order_;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::MappingNodelet, nodelet::Nodelet)
