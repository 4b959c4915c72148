#pragma once
#include <cstdint>
#include <map>
#include <string>

namespace semantic_edge_vo {

/// Reads a tool's command line: each flag of `values` is followed by its value, stored in the string
/// it points to; each flag of `switches` stands alone and sets its bool. Values are text; the tool
/// converts and checks them.
/// @return "" or what is wrong: an unknown flag, a flag without its value
std::string parseFlags(int argc, char** argv, const std::map<std::string, std::string*>& values,
                       const std::map<std::string, bool*>& switches);

/// Converts the value of `flag` (the text given to it; empty: `value` left as it is): all of it must
/// be a number of the value's type (whole, not negative for the unsigned seeds; finite for reals).
/// @return "" or what is wrong, e.g. "--runs takes a whole number (got '3x')"
std::string parseNumber(const std::string& flag, const std::string& text, int* value);
std::string parseNumber(const std::string& flag, const std::string& text, std::uint64_t* value);
std::string parseNumber(const std::string& flag, const std::string& text, double* value);

/// Prints `usage` to stdout when the only argument is --help or -h: true then (the tool exits 0).
bool printUsageIfAsked(int argc, char** argv, const char* usage);

}  // namespace semantic_edge_vo
