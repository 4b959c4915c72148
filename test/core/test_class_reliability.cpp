// A drive's class reliability: a class whose points the frames see again with their class is relied
// on (its SNNF layer matches them); one whose label the frames give to other classes falls back to
// the all-edges layer, as ANNF would match it.
#include <gtest/gtest.h>

#include "semantic_edge_vo/frontend/class_reliability.h"
#include "semantic_edge_vo/frontend/odometry_frame.h"

namespace semantic_edge_vo {
namespace {

constexpr int kRoad = 0, kCar = 1, kTree = 2, kClasses = 3;

/// A keyframe 10 m before a wall of edge points: a row of road points and a row of car points, all
/// at their exact depth; its frame has an SNNF field of kClasses classes.
struct Scene {
  PinholeCamera camera = kittiCamera();
  std::shared_ptr<Keyframe> keyframe = std::make_shared<Keyframe>();

  Scene() {
    auto frame = std::make_shared<OdometryFrame>();
    frame->pyramid = std::make_shared<ImagePyramid>(cv::Mat(camera.height, camera.width, CV_8UC1, cv::Scalar(0)), camera, 1);
    keyframe->frame = frame;
    for (int i = 0; i < 100; ++i)
      for (const int label : {kRoad, kCar}) {
        MapPoint point;
        point.u = 100.0f + 10.0f * static_cast<float>(i);
        point.v = label == kRoad ? 300.0f : 150.0f;
        point.class_mask = 1u << label;
        point.inverse_depth = 0.1;
        point.inverse_depth_variance = 1e-6;
        point.observations = 1;
        keyframe->points.push_back(point);
      }
  }

  /// The frame's field, the camera not moved: its edges where the keyframe's points are, the road's
  /// labelled road and the car's labelled `car_label`.
  NearestNeighborFieldData frameField(int car_label) const {
    EdgeSet edges;
    for (const MapPoint& point : keyframe->points)
      edges.push_back(point.u, point.v, 0.0f, 1.0f, 1.0f, point.class_mask == 1u << kRoad ? 1u << kRoad : 1u << car_label);
    FieldOptions options;
    options.pyramid_levels = 1;
    return buildNearestNeighborField(edges.view(), camera.width, camera.height, {"road", "car", "tree"}, options);
  }
};

TEST(ClassReliability, AClassTheFramesRelabelIsMatchedInTheAllEdgesLayer) {
  Scene scene;
  ClassReliability reliability{ClassReliabilityOptions()};
  const NearestNeighborFieldData field = scene.frameField(kTree);  // the car's edges come back as tree
  ASSERT_EQ(field.all_edges_layer, kClasses);
  for (int frame = 0; frame < 5; ++frame) reliability.observe(*scene.keyframe, Eigen::Isometry3d::Identity(), field.view());
  EXPECT_DOUBLE_EQ(reliability.agreement(kRoad), 1.0);
  EXPECT_DOUBLE_EQ(reliability.agreement(kCar), 0.0);
  EXPECT_EQ(reliability.fieldLayers(1u << kRoad, kClasses), 1u << kRoad);
  EXPECT_EQ(reliability.fieldLayers(1u << kCar, kClasses), 1u << kClasses) << "the all-edges layer";
  // A point of both classes keeps the one relied on.
  EXPECT_EQ(reliability.fieldLayers(1u << kRoad | 1u << kCar, kClasses), 1u << kRoad);
  // Without an all-edges layer (one class: Canny edges) the classes stay.
  EXPECT_EQ(reliability.fieldLayers(1u << kCar, 0), 1u << kCar);
}

TEST(ClassReliability, AClassSeenAgainWithItsLabelIsReliedOnAndTheVerdictFollowsTheScene) {
  Scene scene;
  ClassReliability reliability{ClassReliabilityOptions()};
  EXPECT_EQ(reliability.fieldLayers(1u << kCar, kClasses), 1u << kClasses) << "nothing seen yet: not relied on";
  const NearestNeighborFieldData agreeing = scene.frameField(kCar), relabelling = scene.frameField(kTree);
  for (int frame = 0; frame < 5; ++frame) reliability.observe(*scene.keyframe, Eigen::Isometry3d::Identity(), agreeing.view());
  EXPECT_EQ(reliability.fieldLayers(1u << kCar, kClasses), 1u << kCar);
  // The segmenter starts calling the car a tree: within a few frames the car is no longer relied on.
  for (int frame = 0; frame < 10; ++frame) reliability.observe(*scene.keyframe, Eigen::Isometry3d::Identity(), relabelling.view());
  EXPECT_LT(reliability.agreement(kCar), 0.5);
  EXPECT_EQ(reliability.fieldLayers(1u << kCar, kClasses), 1u << kClasses);
}

TEST(ClassReliability, ZeroMinimumAgreementReliesOnEveryClass) {
  Scene scene;
  ClassReliabilityOptions options;
  options.min_agreement = 0.0;
  ClassReliability reliability(options);
  EXPECT_EQ(reliability.fieldLayers(1u << kCar | 1u << kTree, kClasses), 1u << kCar | 1u << kTree);
  EXPECT_EQ(options.validate(), "");
  options.min_agreement = -0.1;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
