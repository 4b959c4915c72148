#include "semantic_edge_vo/support/host_cpu.h"

#include <ctime>
#include <fstream>
#include <sstream>

namespace semantic_edge_vo {

bool parseHostCpuTimes(const std::string& proc_stat, HostCpuTimes* times, std::string* error) {
  std::istringstream lines(proc_stat);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string name;
    fields >> name;
    if (name != "cpu") continue;
    // user nice system idle iowait irq softirq steal [guest guest_nice: already counted in user, nice]
    std::uint64_t value[8];
    int count = 0;
    while (count < 8 && fields >> value[count]) ++count;
    if (count < 8) {
      *error = "/proc/stat: the cpu line has " + std::to_string(count) + " counters, expected at least 8 (with steal)";
      return false;
    }
    times->busy = value[0] + value[1] + value[2] + value[5] + value[6];
    times->idle = value[3] + value[4];
    times->steal = value[7];
    return true;
  }
  *error = "/proc/stat: no aggregate cpu line";
  return false;
}

bool readHostCpuTimes(HostCpuTimes* times) {
  std::ifstream file("/proc/stat");
  if (!file) return false;
  std::ostringstream text;
  text << file.rdbuf();
  std::string error;
  return parseHostCpuTimes(text.str(), times, &error);
}

double stolenShare(const HostCpuTimes& before, const HostCpuTimes& after) {
  if (after.total() <= before.total() || after.steal < before.steal) return 0.0;
  return static_cast<double>(after.steal - before.steal) / static_cast<double>(after.total() - before.total());
}

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace semantic_edge_vo
