#pragma once
#include <chrono>

namespace semantic_edge_vo {

/// A one-line progress bar on stderr (done/total, rate, ETA), redrawn at most 10 times a second and
/// ended with a newline when done reaches total.
class ProgressBar {
 public:
  /// `unit`: what is counted, e.g. "frames" (a string literal: the bar keeps the pointer).
  ProgressBar(int total, bool enabled, const char* unit = "frames");
  void update(int done);

 private:
  using Clock = std::chrono::steady_clock;
  int total_;
  bool enabled_;
  const char* unit_;
  Clock::time_point start_, last_;
};

}  // namespace semantic_edge_vo
