// Mapping: TrackedFrame (paired by stamp with the SemanticEdgeFrame it tracked) -> keyframes,
// KeyframeMap for tracking, the semantic edge map as PointCloud2, and nav_msgs/Path.
// Work happens in an owned thread behind a bounded queue; callbacks only enqueue.
//
// Foundation stage: keyframes are taken at a fixed interval and their points carry the prior
// inverse depth (no epipolar search or windowed optimisation yet). Threading, frames and outputs are final.
#include <condition_variable>
#include <deque>
#include <map>
#include <thread>

#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include "semantic_edge_vo/KeyframeMap.h"
#include "semantic_edge_vo/SemanticEdgeFrame.h"
#include "semantic_edge_vo/TrackedFrame.h"
#include "semantic_edge_vo/class_table.h"
#include "semantic_edge_vo/ros/camera_extrinsic.h"
#include "semantic_edge_vo/ros/conversions.h"
#include "semantic_edge_vo/ros/input_rejections.h"
#include "semantic_edge_vo/ros/message_tracer.h"
#include "semantic_edge_vo/ros/options_loading.h"

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
    TrackedFrameConstPtr tracked;
    SemanticEdgeFrameConstPtr frame;
  };

  void onInit() override {
    ros::NodeHandle& node = getNodeHandle();
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    ParameterLoader loader(private_node);
    loader.load("odom_frame", &odom_frame_);
    loader.load("base_frame", &base_frame_);
    loader.load("queue_size", &queue_size_, "frames");
    loader.load("keyframe_interval", &keyframe_interval_, "frames");
    loader.load("window_size", &window_size_, "keyframes");
    loader.load("initial_depth", &initial_depth_, "m");
    loader.load("max_map_points", &max_map_points_, "points");
    loader.load("max_path_poses", &max_path_poses_, "poses");
    std::string error = loadClassTable(private_node, &classes_);
    NODELET_INFO_STREAM("parameters:" << loader.summary() << "\n  classes: " << classes_.size());
    if (error.empty() && (queue_size_ < 1 || keyframe_interval_ < 1 || window_size_ < 1 || max_map_points_ < 1 ||
                         max_path_poses_ < 1))
      error = "queue_size, keyframe_interval, window_size, max_map_points and max_path_poses must be >= 1";
    if (error.empty() && !(initial_depth_ > 0.0)) error = "initial_depth must be > 0 m";
    if (!error.empty()) {
      NODELET_ERROR_STREAM("invalid parameters, the nodelet stays inert: " << error);
      return;
    }
    rejections_ = std::make_unique<InputRejections>(getName());
    extrinsic_ = std::make_unique<CameraExtrinsic>(base_frame_, 0.0);
    tracer_.init(node, private_node, getName());
    map_publisher_ = node.advertise<KeyframeMap>("keyframe_map", 2, /*latch=*/true);
    cloud_publisher_ = node.advertise<sensor_msgs::PointCloud2>("semantic_edge_map", 1, /*latch=*/true);
    path_publisher_ = node.advertise<nav_msgs::Path>("path", 1);
    frame_subscriber_ = node.subscribe("edge_frame", 10, &MappingNodelet::onEdgeFrame, this);
    tracked_subscriber_ = node.subscribe("tracked_frame", 10, &MappingNodelet::onTrackedFrame, this);
    worker_ = std::thread(&MappingNodelet::run, this);
  }

  void onEdgeFrame(const SemanticEdgeFrameConstPtr& frame) {
    tracer_.received(frame_subscriber_.getTopic(), frame.get(), frame->header.stamp);
    std::lock_guard<std::mutex> lock(frames_mutex_);
    recent_frames_[frame->header.stamp] = frame;
    while (recent_frames_.size() > 30) recent_frames_.erase(recent_frames_.begin());
  }

  void onTrackedFrame(const TrackedFrameConstPtr& tracked) {
    tracer_.received(tracked_subscriber_.getTopic(), tracked.get(), tracked->header.stamp);
    Job job{tracked, nullptr};
    {
      std::lock_guard<std::mutex> lock(frames_mutex_);
      auto it = recent_frames_.find(tracked->header.stamp);
      if (it != recent_frames_.end()) job.frame = it->second;
    }
    if (!job.frame) {
      rejections_->reject("tracked frame", "frame_not_received", "no edge_frame with its stamp arrived (yet)");
      return;
    }
    {
      std::lock_guard<std::mutex> lock(queue_mutex_);
      if (static_cast<int>(queue_.size()) >= queue_size_) {
        queue_.pop_front();
        rejections_->reject("oldest queued frame", "queue_full", "mapping is behind; raise queue_size or lower the rate");
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
      process(job);
    }
  }

  void process(const Job& job) {
    const Eigen::Isometry3d T_world_cam = fromPoseMsg(job.tracked->pose_world_camera);
    const Eigen::Isometry3d T_base_cam = extrinsic_->baseFromCamera(job.frame->header.frame_id);
    const ros::Time stamp = job.tracked->header.stamp;

    geometry_msgs::PoseStamped pose;
    pose.header.stamp = stamp;
    pose.header.frame_id = odom_frame_;
    pose.pose = toPoseMsg(baseInOdom(T_world_cam, T_base_cam));
    path_.header = pose.header;
    path_.poses.push_back(pose);
    if (static_cast<int>(path_.poses.size()) > max_path_poses_) path_.poses.erase(path_.poses.begin());
    path_publisher_.publish(path_);

    if (frames_since_keyframe_++ % keyframe_interval_ != 0 || !job.tracked->pose_trusted) return;
    addKeyframe(*job.frame, T_world_cam, stamp);
    publishMap(stamp);
    publishCloud(T_base_cam, stamp);
  }

  void addKeyframe(const SemanticEdgeFrame& frame, const Eigen::Isometry3d& T_world_cam, const ros::Time& stamp) {
    Keyframe keyframe;
    keyframe.id = next_keyframe_id_++;
    keyframe.stamp = stamp;
    keyframe.pose_world_camera = toPoseMsg(T_world_cam);
    const auto add = [&](float u, float v, std::uint32_t mask, float nx, float ny) {
      keyframe.point_u.push_back(u);
      keyframe.point_v.push_back(v);
      keyframe.point_inverse_depth.push_back(static_cast<float>(1.0 / initial_depth_));
      keyframe.point_inverse_depth_variance.push_back(static_cast<float>(1.0 / (initial_depth_ * initial_depth_)));
      keyframe.point_class_mask.push_back(mask);
      keyframe.point_normal_x.push_back(nx);
      keyframe.point_normal_y.push_back(ny);
    };
    for (std::uint32_t i : frame.sampled_edges)
      add(frame.edge_u[i], frame.edge_v[i], frame.edge_class_mask[i], frame.edge_normal_x[i], frame.edge_normal_y[i]);
    for (std::size_t i = 0; i < frame.support_u.size(); ++i) add(frame.support_u[i], frame.support_v[i], 0u, 0.0f, 0.0f);
    window_.push_back(std::move(keyframe));
    keyframe_cameras_.push_back(cameraFromInfo(frame.camera_info));
    while (static_cast<int>(window_.size()) > window_size_) {
      window_.pop_front();
      keyframe_cameras_.pop_front();
    }
  }

  void publishMap(const ros::Time& stamp) {
    auto map = boost::make_shared<KeyframeMap>();
    map->header.stamp = stamp;
    map->header.frame_id = "world";
    map->keyframes.assign(window_.begin(), window_.end());
    map_publisher_.publish(KeyframeMapConstPtr(map));
    tracer_.published(map_publisher_, map.get(), stamp);
  }

  /// Edge points (not supportive ones) of the window's keyframes, in odom, coloured by class.
  void publishCloud(const Eigen::Isometry3d& T_base_cam, const ros::Time& stamp) {
    struct Point {
      Eigen::Vector3f position;
      std::uint32_t label;
    };
    std::vector<Point> points;
    for (std::size_t k = 0; k < window_.size(); ++k) {
      const Keyframe& keyframe = window_[k];
      const Eigen::Isometry3d T_odom_cam = T_base_cam * fromPoseMsg(keyframe.pose_world_camera);
      for (std::size_t i = 0; i < keyframe.point_u.size(); ++i) {
        if (!keyframe.point_class_mask[i]) continue;
        const Eigen::Vector3d p = keyframe_cameras_[k].backProject(keyframe.point_u[i], keyframe.point_v[i],
                                                                   1.0 / keyframe.point_inverse_depth[i]);
        points.push_back({(T_odom_cam * p).cast<float>(), static_cast<std::uint32_t>(__builtin_ctz(keyframe.point_class_mask[i]))});
      }
    }
    if (static_cast<int>(points.size()) > max_map_points_) points.erase(points.begin(), points.end() - max_map_points_);

    auto cloud = boost::make_shared<sensor_msgs::PointCloud2>();
    cloud->header.stamp = stamp;
    cloud->header.frame_id = odom_frame_;
    sensor_msgs::PointCloud2Modifier modifier(*cloud);
    modifier.setPointCloud2Fields(5, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32,
                                  "z", 1, sensor_msgs::PointField::FLOAT32, "label", 1, sensor_msgs::PointField::UINT32,
                                  "rgb", 1, sensor_msgs::PointField::FLOAT32);
    modifier.resize(points.size());
    sensor_msgs::PointCloud2Iterator<float> x(*cloud, "x");
    sensor_msgs::PointCloud2Iterator<std::uint32_t> label(*cloud, "label");
    sensor_msgs::PointCloud2Iterator<std::uint8_t> rgb(*cloud, "rgb");  // packed b, g, r, a bytes
    for (const Point& point : points) {
      x[0] = point.position.x();
      x[1] = point.position.y();
      x[2] = point.position.z();
      *label = point.label;
      const auto& colour = point.label < static_cast<std::uint32_t>(classes_.size()) ? classes_[static_cast<int>(point.label)].rgb
                                                                                      : classes_[0].rgb;
      rgb[0] = colour[2];
      rgb[1] = colour[1];
      rgb[2] = colour[0];
      rgb[3] = 255;
      ++x, ++label, ++rgb;
    }
    cloud_publisher_.publish(sensor_msgs::PointCloud2ConstPtr(cloud));
  }

  // Parameters (read in onInit, constant afterwards).
  std::string odom_frame_ = "odom";
  std::string base_frame_ = "base_link";
  int queue_size_ = 10;
  int keyframe_interval_ = 5;
  int window_size_ = 7;
  double initial_depth_ = 10.0;
  int max_map_points_ = 200000;
  int max_path_poses_ = 10000;
  ClassTable classes_;

  std::unique_ptr<InputRejections> rejections_;
  std::unique_ptr<CameraExtrinsic> extrinsic_;  // worker thread only
  MessageTracer tracer_;
  ros::Publisher map_publisher_, cloud_publisher_, path_publisher_;
  ros::Subscriber frame_subscriber_, tracked_subscriber_;

  std::mutex frames_mutex_;  // guards recent_frames_
  std::map<ros::Time, SemanticEdgeFrameConstPtr> recent_frames_;

  std::mutex queue_mutex_;  // guards queue_ and stopping_
  std::condition_variable queue_ready_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::thread worker_;

  // Worker thread only.
  nav_msgs::Path path_;
  std::deque<Keyframe> window_;
  std::deque<PinholeCamera> keyframe_cameras_;
  std::uint32_t next_keyframe_id_ = 0;
  unsigned long frames_since_keyframe_ = 0;
};

}  // namespace semantic_edge_vo

PLUGINLIB_EXPORT_CLASS(semantic_edge_vo::MappingNodelet, nodelet::Nodelet)
