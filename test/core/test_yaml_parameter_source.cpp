#include <fstream>

#include <gtest/gtest.h>

#include "semantic_edge_vo/intake_options_loading.h"
#include "semantic_edge_vo/options_loading.h"
#include "semantic_edge_vo/yaml_parameter_source.h"

namespace semantic_edge_vo {
namespace {

std::string writeYaml(const std::string& text) {
  const std::string path = ::testing::TempDir() + "/parameters_test.yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(YamlParameterSource, ReadsNestedNamesOfASection) {
  const YamlParameterSource file(writeYaml(
      "tracking:\n  keyframe_flow: 42.5\n  tracker: {levels: 3}\n  optimize_window: true\n  odom_frame: odom\n"
      "  list: [1, 2, 3]\n"));
  ASSERT_EQ(file.error(), "");
  const YamlParameterSource tracking = file.section("tracking");
  double flow = 0.0;
  int levels = 0;
  bool optimize = false;
  std::string frame;
  std::vector<int> list;
  EXPECT_TRUE(tracking.get("keyframe_flow", &flow));
  EXPECT_TRUE(tracking.get("tracker/levels", &levels));
  EXPECT_TRUE(tracking.get("optimize_window", &optimize));
  EXPECT_TRUE(tracking.get("odom_frame", &frame));
  EXPECT_TRUE(tracking.get("list", &list));
  EXPECT_DOUBLE_EQ(flow, 42.5);
  EXPECT_EQ(levels, 3);
  EXPECT_TRUE(optimize);
  EXPECT_EQ(frame, "odom");
  EXPECT_EQ(list, (std::vector<int>{1, 2, 3}));
  EXPECT_NE(tracking.resolve("tracker/levels").find("tracking/tracker/levels"), std::string::npos);
}

TEST(YamlParameterSource, MissingNamesKeepTheDefaultAndWrongTypesAreReported) {
  const YamlParameterSource file(writeYaml("tracking:\n  tracker: {levels: many}\n"));
  const YamlParameterSource tracking = file.section("tracking");
  int levels = 4, absent = 7;
  EXPECT_FALSE(tracking.get("tracker/absent", &absent));
  EXPECT_FALSE(tracking.get("nothing/here/at_all", &absent));
  EXPECT_FALSE(file.section("no_such_block").get("tracker/levels", &absent));
  EXPECT_EQ(absent, 7);
  EXPECT_EQ(tracking.error(), "");
  EXPECT_FALSE(tracking.get("tracker/levels", &levels));
  EXPECT_EQ(levels, 4);
  EXPECT_NE(tracking.error().find("tracking/tracker/levels has the wrong type"), std::string::npos) << tracking.error();
}

TEST(YamlParameterSource, NamesAMissingOrBrokenFile) {
  EXPECT_NE(YamlParameterSource("/nonexistent/config.yaml").error().find("/nonexistent/config.yaml"), std::string::npos);
  EXPECT_NE(YamlParameterSource(writeYaml("a: [1, 2\n")).error(), "");
  EXPECT_EQ(YamlParameterSource("").error(), "");
}

TEST(YamlParameterSource, ReadsAClassTableAndRefusesAMalformedOne) {
  const YamlParameterSource good(writeYaml("classes:\n  - {name: road, id: 0, rgb: [128, 64, 128]}\n  - {name: car, id: 13, rgb: [0, 0, 142]}\n"));
  ParameterLoader loader(good);
  ClassTable table;
  ASSERT_EQ(loadClassTable(&loader, &table), "");
  ASSERT_EQ(table.size(), 2);
  EXPECT_EQ(table[1].name, "car");
  EXPECT_EQ(table[1].id, 13);
  EXPECT_EQ(table[0].rgb[1], 64);

  const YamlParameterSource bad(writeYaml("classes:\n  - {name: road, id: 0, rgb: [128, 64]}\n"));
  std::vector<SemanticClass> classes;
  EXPECT_FALSE(bad.get("classes", &classes));
  EXPECT_NE(bad.error().find("classes[0]"), std::string::npos) << bad.error();
}

// The shipped config sets every option the loaders read (none falls back to a silent default),
// and every value in it is readable and valid. run_sequence --config reads it like the nodelets.
TEST(YamlParameterSource, ShippedConfigSetsEveryOptionValidly) {
  const YamlParameterSource file(SEVO_SOURCE_DIR "/config/semantic_edge_vo.yaml");
  ASSERT_EQ(file.error(), "");
  const YamlParameterSource intake = file.section("edge_intake"), segmenter = file.section("segmenter"),
                            field = file.section("nearest_neighbor_field"), tracking = file.section("tracking");
  ParameterLoader intake_loader(intake), segmenter_loader(segmenter), field_loader(field), tracking_loader(tracking);
  SemanticEdgeOptions edges;
  PointSamplerOptions sampler;
  ClassTable classes;
  SegmenterOptions segmentation;
  FieldOptions field_options;
  OdometryOptions odometry;
  EXPECT_EQ(loadSemanticEdgeOptions(&intake_loader, &edges), "");
  EXPECT_EQ(loadPointSamplerOptions(&intake_loader, &sampler), "");
  EXPECT_EQ(loadClassTable(&intake_loader, &classes), "");
  EXPECT_EQ(loadSegmenterOptions(&segmenter_loader, &segmentation), "");
  EXPECT_EQ(loadFieldOptions(&field_loader, &field_options), "");
  EXPECT_EQ(loadOdometryOptions(&tracking_loader, &odometry), "");
  for (const ParameterLoader* loader : {&intake_loader, &segmenter_loader, &field_loader, &tracking_loader})
    EXPECT_EQ(loader->summary().find("(default)"), std::string::npos) << loader->summary();
  for (const ParameterSource* source : {&intake, &segmenter, &field, &tracking}) EXPECT_EQ(source->error(), "");
  EXPECT_EQ(classes.size(), 19);
  EXPECT_EQ(classes[13].name, "car");
}

}  // namespace
}  // namespace semantic_edge_vo
