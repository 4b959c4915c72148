#pragma once
#include <cstdint>
#include <string>

namespace semantic_edge_vo {

/// The host's CPU time counters (Linux /proc/stat, all CPUs together, clock ticks). On a virtual
/// machine `steal` is the time its CPUs were ready to run but the hypervisor ran something else:
/// on a shared host it is why the same code measures slower in wall time from one hour to the next.
struct HostCpuTimes {
  std::uint64_t busy = 0;   ///< user, nice, system, irq, softirq
  std::uint64_t idle = 0;   ///< idle and iowait
  std::uint64_t steal = 0;  ///< taken by the hypervisor
  std::uint64_t total() const { return busy + idle + steal; }
};

/// Parses the aggregate "cpu ..." line of /proc/stat's text; false (and `*error` says why) otherwise.
bool parseHostCpuTimes(const std::string& proc_stat, HostCpuTimes* times, std::string* error);
/// Reads /proc/stat now; false where there is none (not Linux) or it cannot be parsed.
bool readHostCpuTimes(HostCpuTimes* times);
/// Share of the host's CPU time the hypervisor took between two readings, in [0, 1]; 0 when no
/// time passed.
double stolenShare(const HostCpuTimes& before, const HostCpuTimes& after);

/// CPU time of this process (all its threads) so far, s: unlike wall time it does not grow while
/// the process waits for a CPU.
double processCpuSeconds();

}  // namespace semantic_edge_vo
