#include "semantic_edge_vo/support/progress_bar.h"

#include <cstdio>

namespace semantic_edge_vo {

ProgressBar::ProgressBar(int total, bool enabled, const char* unit)
    : total_(total), enabled_(enabled && total > 0), unit_(unit), start_(Clock::now()) {}

void ProgressBar::update(int done) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (done < total_ && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0.0 ? done / elapsed : 0.0;
  const int eta = rate > 0.0 ? static_cast<int>((total_ - done) / rate) : 0;
  constexpr int kWidth = 40;
  const int filled = static_cast<int>(static_cast<long long>(kWidth) * done / total_);
  std::fprintf(stderr, "\r[%.*s%*s] %d/%d  %.1f %s/s  ETA %02d:%02d ", filled, "########################################",
               kWidth - filled, "", done, total_, rate, unit_, eta / 60, eta % 60);
  if (done == total_) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace semantic_edge_vo
