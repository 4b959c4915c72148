#include <algorithm>
#include <fstream>

#include <gtest/gtest.h>

#include "semantic_edge_vo/config/graph_config.h"
#include "semantic_edge_vo/config/options_loading.h"
#include "semantic_edge_vo/config/yaml_parameter_source.h"

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

TEST(YamlParameterSource, NamesEveryValueOnceAListIncluded) {
  const YamlParameterSource file(writeYaml("tracking:\n  tracker: {levels: 3, edge_huber: 1.5}\n  list: [1, 2]\nmapping: {voxel_size: 0.1}\n"));
  std::vector<std::string> names = file.names();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"mapping/voxel_size", "tracking/list", "tracking/tracker/edge_huber", "tracking/tracker/levels"}));
  EXPECT_EQ(file.section("tracking").names().size(), 3u);
}

// One source of defaults: the shipped config sets every option the graph reads (none falls back
// to a silent default), every value is valid, and each equals the option's built-in default, so
// run_sequence without --config, the launch file and the tests run the same odometry.
TEST(GraphConfig, ShippedConfigSetsEveryOptionToItsDefault) {
  GraphConfig config;
  ASSERT_EQ(loadGraphConfig(SEVO_SOURCE_DIR "/config/semantic_edge_vo.yaml", &config), "");
  EXPECT_EQ(config.summary.find("(default)"), std::string::npos) << config.summary;
  std::string changed;
  for (const std::string& line : config.changed_from_defaults) changed += "\n  " + line;
  EXPECT_EQ(changed, "") << "the shipped config differs from the built-in defaults";
  EXPECT_EQ(config.classes.names(), ClassTable::cityscapes().names());
}

TEST(GraphConfig, AnUnknownKeyOrBlockIsNamed) {
  GraphConfig config;
  const std::string typo = loadGraphConfig(writeYaml("tracking:\n  tracker: {edge_hubr: 2.0}\n"), &config);
  EXPECT_NE(typo.find("tracking/tracker/edge_hubr"), std::string::npos) << typo;
  const std::string block = loadGraphConfig(writeYaml("trackng:\n  keyframe_flow: 50.0\n"), &config);
  EXPECT_NE(block.find("trackng"), std::string::npos) << block;
  EXPECT_EQ(loadGraphConfig(writeYaml("tracking:\n  keyframe_flow: 50.0\n"), &config), "");
  EXPECT_DOUBLE_EQ(config.odometry.keyframe_flow, 50.0);
  ASSERT_EQ(config.changed_from_defaults.size(), 1u);
  EXPECT_NE(config.changed_from_defaults[0].find("tracking/keyframe_flow = 50"), std::string::npos);
  EXPECT_EQ(loadGraphConfig("", &config), "");
}

}  // namespace
}  // namespace semantic_edge_vo
