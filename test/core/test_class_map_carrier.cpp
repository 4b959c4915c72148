// ClassMapCarrier: a class map carried frames ahead along the optical flow.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "semantic_edge_vo/edges/class_map_carrier.h"
#include "semantic_edge_vo/synthetic/synthetic_sequence.h"

namespace semantic_edge_vo {
namespace {

ClassEvidence labelsOf(const synthetic::SyntheticFrame& frame) {
  ClassEvidence evidence;
  evidence.form = ClassEvidenceForm::kLabels;
  evidence.classes = 19;
  evidence.values = frame.class_id.clone();
  return evidence;
}

/// Share of the frame's edge pixels (Canny, what the intake labels) whose true class the labels put
/// within a pixel of them (the intake reads classes on both sides of an edge anyway).
double edgeAgreement(const cv::Mat& labels, const cv::Mat& truth, const cv::Mat& gray) {
  cv::Mat edges;
  cv::Canny(gray, edges, 40, 100);
  int edge = 0, agree = 0;
  for (int y = 2; y < truth.rows - 2; ++y)
    for (int x = 2; x < truth.cols - 2; ++x) {
      if (!edges.at<uchar>(y, x)) continue;
      ++edge;
      bool near = false;
      for (int dy = -1; dy <= 1 && !near; ++dy)
        for (int dx = -1; dx <= 1 && !near; ++dx) near = labels.at<uchar>(y + dy, x + dx) == truth.at<uchar>(y, x);
      agree += near;
    }
  return edge ? static_cast<double>(agree) / edge : 0.0;
}

struct Drive {
  std::vector<synthetic::SyntheticFrame> frames;
};

const Drive& cityDrive() {
  static const Drive drive = [] {
    synthetic::SyntheticSequenceOptions options = synthetic::SyntheticSequenceOptions::forScene(synthetic::SceneType::kCity, 7);
    options.semantics = false;
    synthetic::SyntheticSequence sequence(options);
    Drive d;
    for (int i = 40; i <= 44; ++i) d.frames.push_back(sequence.frame(i));
    return d;
  }();
  return drive;
}

TEST(ClassMapCarrier, CarriedMapLabelsTheLaterFramesEdgesBetterThanTheStaleOne) {
  const Drive& drive = cityDrive();
  const synthetic::SyntheticFrame& first = drive.frames.front();
  ClassMapCarrier carrier;
  // The map of the first frame comes while the second is the newest, as a slow segmenter's would.
  carrier.addImage(first.time, first.gray);
  carrier.addImage(drive.frames[1].time, drive.frames[1].gray);
  ASSERT_TRUE(carrier.setClassMap(first.time, labelsOf(first)));
  for (std::size_t later = 1; later < drive.frames.size(); ++later) {
    const synthetic::SyntheticFrame& frame = drive.frames[later];
    if (later > 1) carrier.addImage(frame.time, frame.gray);
    ClassEvidence carried;
    double age = 0.0;
    ASSERT_TRUE(carrier.carryTo(frame.time, &carried, &age));
    EXPECT_NEAR(age, frame.time - first.time, 1e-9);
    ASSERT_EQ(carried.values.size(), frame.class_id.size());
    const double stale = edgeAgreement(first.class_id, frame.class_id, frame.gray);
    const double moved = edgeAgreement(carried.values, frame.class_id, frame.gray);
    std::printf("%zu frames ahead: edge pixels labelled right %.3f carried, %.3f stale\n", later, moved, stale);
    // Never worse than the stale map, better while the flow is sure of itself.
    EXPECT_GE(moved, stale - 0.005);
    if (later <= 2) EXPECT_GT(moved, stale + 0.03);
  }
}

TEST(ClassMapCarrier, TheMapOfTheSameImageIsTakenAsItIs) {
  const synthetic::SyntheticFrame& frame = cityDrive().frames.front();
  ClassMapCarrier carrier;
  carrier.addImage(frame.time, frame.gray);
  ASSERT_TRUE(carrier.setClassMap(frame.time, labelsOf(frame)));
  ClassEvidence carried;
  double age = -1.0;
  ASSERT_TRUE(carrier.carryTo(frame.time, &carried, &age));
  EXPECT_EQ(age, 0.0);
  EXPECT_EQ(cv::countNonZero(carried.values != frame.class_id), 0);
}

TEST(ClassMapCarrier, UnknownImagesOldMapsAndTooOldMapsAreRefused) {
  const Drive& drive = cityDrive();
  ClassMapCarrierOptions options;
  options.max_age = 0.25;  // 2.5 frames at 10 Hz
  ClassMapCarrier carrier(options);
  ClassEvidence carried;
  double age = 0.0;
  carrier.addImage(drive.frames[0].time, drive.frames[0].gray);
  EXPECT_FALSE(carrier.carryTo(drive.frames[0].time, &carried, &age)) << "no map yet";
  EXPECT_FALSE(carrier.setClassMap(drive.frames[1].time, labelsOf(drive.frames[1]))) << "its image was never added";
  for (int i = 1; i <= 3; ++i) carrier.addImage(drive.frames[i].time, drive.frames[i].gray);
  ASSERT_TRUE(carrier.setClassMap(drive.frames[1].time, labelsOf(drive.frames[1])));
  EXPECT_FALSE(carrier.setClassMap(drive.frames[0].time, labelsOf(drive.frames[0]))) << "older than the map it has";
  EXPECT_FALSE(carrier.carryTo(drive.frames[2].time, &carried, &age)) << "not the newest image";
  EXPECT_TRUE(carrier.carryTo(drive.frames[3].time, &carried, &age));
  carrier.addImage(drive.frames[4].time, drive.frames[4].gray);
  EXPECT_FALSE(carrier.carryTo(drive.frames[4].time, &carried, &age)) << "0.3 s old";
  carrier.clear();
  EXPECT_FALSE(carrier.carryTo(drive.frames[4].time, &carried, &age));
}

TEST(ClassMapCarrier, OptionsAreValidated) {
  ClassMapCarrierOptions options;
  EXPECT_EQ(options.validate(), "");
  options.flow_scale = 0.0;
  EXPECT_NE(options.validate(), "");
  options = ClassMapCarrierOptions();
  options.max_age = -1.0;
  EXPECT_NE(options.validate(), "");
}

}  // namespace
}  // namespace semantic_edge_vo
