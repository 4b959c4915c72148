#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "semantic_edge_vo/support/command_line.h"

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
  EXPECT_EQ(parseNumber("--runs", "", &count), "");
  EXPECT_EQ(count, 7);  // not given: the default stays
  EXPECT_EQ(parseNumber("--runs", "12", &count), "");
  EXPECT_EQ(count, 12);
  EXPECT_EQ(parseNumber("--runs", "3x", &count), "--runs takes a whole number (got '3x')");
  EXPECT_EQ(parseNumber("--runs", "abc", &count), "--runs takes a whole number (got 'abc')");
  EXPECT_NE(parseNumber("--runs", "99999999999", &count), "");
  EXPECT_NE(parseNumber("--runs", " 3", &count), "");  // std::stoi would skip the space
  EXPECT_NE(parseNumber("--runs", "+3", &count), "");
  EXPECT_EQ(parseNumber("--runs", "-3", &count), "");
  EXPECT_EQ(count, -3);
}

TEST(CommandLine, SeedsAndRealsAreCheckedToo) {
  std::uint64_t seed = 1;
  EXPECT_EQ(parseNumber("--seed", "18446744073709551615", &seed), "");
  EXPECT_EQ(seed, 18446744073709551615u);
  EXPECT_EQ(parseNumber("--seed", "-1", &seed), "--seed takes a whole number >= 0 (got '-1')");  // stoull would wrap it
  EXPECT_NE(parseNumber("--seed", "1.5", &seed), "");
  EXPECT_EQ(seed, 18446744073709551615u);

  double radius = 1.5;
  EXPECT_EQ(parseNumber("--radius", "2.25", &radius), "");
  EXPECT_EQ(radius, 2.25);
  EXPECT_EQ(parseNumber("--radius", "1e-3", &radius), "");
  EXPECT_EQ(radius, 1e-3);
  EXPECT_EQ(parseNumber("--radius", "0.3x", &radius), "--radius takes a number (got '0.3x')");
  EXPECT_EQ(parseNumber("--radius", "nan", &radius), "--radius takes a number (got 'nan')");
  EXPECT_EQ(parseNumber("--radius", "-inf", &radius), "--radius takes a finite number (got '-inf')");
  EXPECT_NE(parseNumber("--radius", "0x1p3", &radius), "");  // std::stod reads hexadecimal
  EXPECT_EQ(parseNumber("--radius", ".5", &radius), "");
  EXPECT_EQ(radius, 0.5);
  EXPECT_NE(parseNumber("--seed", "18446744073709551616", &seed), "");  // 2^64: out of range
}

}  // namespace
}  // namespace semantic_edge_vo
