#include <vector>

#include <gtest/gtest.h>

#include "semantic_edge_vo/command_line.h"

namespace semantic_edge_vo {
namespace {

struct Parsed {
  std::string sequence, output;
  bool quiet = false;
};

std::string parse(std::vector<std::string> arguments, Parsed* parsed) {
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  return parseFlags(static_cast<int>(argv.size()), argv.data(), {{"--sequence", &parsed->sequence}, {"--output", &parsed->output}},
                    {{"--quiet", &parsed->quiet}});
}

TEST(CommandLine, FlagsTakeTheirValuesAndSwitchesStandAlone) {
  Parsed parsed;
  EXPECT_EQ(parse({"tool", "--sequence", "dir", "--quiet", "--output", "out"}, &parsed), "");
  EXPECT_EQ(parsed.sequence, "dir");
  EXPECT_EQ(parsed.output, "out");
  EXPECT_TRUE(parsed.quiet);
}

TEST(CommandLine, UnknownFlagsAndMissingValuesAreNamed) {
  Parsed parsed;
  EXPECT_EQ(parse({"tool", "--sequence"}, &parsed), "--sequence needs a value");
  EXPECT_EQ(parse({"tool", "--frames", "3"}, &parsed), "unknown flag --frames");
  EXPECT_FALSE(parsed.quiet);
}

TEST(CommandLine, NumbersMustBeWholeValues) {
  int count = 7;
  EXPECT_EQ(parseInt("--runs", "", &count), "");
  EXPECT_EQ(count, 7);  // not given: the default stays
  EXPECT_EQ(parseInt("--runs", "12", &count), "");
  EXPECT_EQ(count, 12);
  EXPECT_EQ(parseInt("--runs", "3x", &count), "--runs takes a whole number (got '3x')");
  EXPECT_EQ(parseInt("--runs", "abc", &count), "--runs takes a whole number (got 'abc')");
  EXPECT_NE(parseInt("--runs", "99999999999", &count), "");
  EXPECT_EQ(count, 12);
}

}  // namespace
}  // namespace semantic_edge_vo
