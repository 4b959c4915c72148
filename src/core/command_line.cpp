#include "semantic_edge_vo/command_line.h"

#include <cstdio>
#include <stdexcept>

namespace semantic_edge_vo {

std::string parseFlags(int argc, char** argv, const std::map<std::string, std::string*>& values,
                       const std::map<std::string, bool*>& switches) {
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (const auto on = switches.find(flag); on != switches.end()) {
      *on->second = true;
    } else if (const auto value = values.find(flag); value != values.end()) {
      if (i + 1 >= argc) return flag + " needs a value";
      *value->second = argv[++i];
    } else {
      return "unknown flag " + flag;
    }
  }
  return "";
}

std::string parseInt(const std::string& flag, const std::string& text, int* value) {
  if (text.empty()) return "";
  std::size_t used = 0;
  try {
    const int parsed = std::stoi(text, &used);
    if (used == text.size()) {
      *value = parsed;
      return "";
    }
  } catch (const std::exception&) {  // not a number, or out of range
  }
  return flag + " takes a whole number (got '" + text + "')";
}

bool printUsageIfAsked(int argc, char** argv, const char* usage) {
  if (argc != 2 || (std::string(argv[1]) != "--help" && std::string(argv[1]) != "-h")) return false;
  std::fputs(usage, stdout);
  return true;
}

}  // namespace semantic_edge_vo
