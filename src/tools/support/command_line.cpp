#include "semantic_edge_vo/support/command_line.h"

#include <cctype>
#include <cmath>
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

namespace {

/// `convert` reads a number from the text and says how many characters it used (the std::sto*
/// family); the whole text must be used, and it starts with a digit, '-' or '.' and is decimal
/// (std::sto* would also skip spaces, take a '+', and std::stod hexadecimal).
template <typename T, typename Convert>
std::string convertAll(const std::string& flag, const std::string& text, const char* kind, Convert convert, T* value) {
  if (text.empty()) return "";
  const std::string bad = flag + " takes " + kind + " (got '" + text + "')";
  const unsigned char first = static_cast<unsigned char>(text[0]);
  if ((!std::isdigit(first) && first != '-' && first != '.') || text.find_first_of("xX") != std::string::npos) return bad;  // no hex
  std::size_t used = 0;
  try {
    const T parsed = convert(text, &used);
    if (used == text.size()) {
      *value = parsed;
      return "";
    }
  } catch (const std::exception&) {  // not a number, or out of range
  }
  return bad;
}

}  // namespace

std::string parseNumber(const std::string& flag, const std::string& text, int* value) {
  return convertAll(flag, text, "a whole number", [](const std::string& t, std::size_t* used) { return std::stoi(t, used); }, value);
}

std::string parseNumber(const std::string& flag, const std::string& text, std::uint64_t* value) {
  // stoull reads "-1" as the largest value: a seed starts with a digit.
  if (!text.empty() && !std::isdigit(static_cast<unsigned char>(text[0]))) return flag + " takes a whole number >= 0 (got '" + text + "')";
  return convertAll(flag, text, "a whole number >= 0", [](const std::string& t, std::size_t* used) { return std::stoull(t, used); }, value);
}

std::string parseNumber(const std::string& flag, const std::string& text, double* value) {
  double parsed = 0.0;
  const std::string error = convertAll(flag, text, "a number", [](const std::string& t, std::size_t* used) { return std::stod(t, used); }, &parsed);
  if (!error.empty() || text.empty()) return error;
  if (!std::isfinite(parsed)) return flag + " takes a finite number (got '" + text + "')";  // stod reads "inf" and "nan"
  *value = parsed;
  return "";
}

bool printUsageIfAsked(int argc, char** argv, const char* usage) {
  if (argc != 2 || (std::string(argv[1]) != "--help" && std::string(argv[1]) != "-h")) return false;
  std::fputs(usage, stdout);
  return true;
}

}  // namespace semantic_edge_vo
