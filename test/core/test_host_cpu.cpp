#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "semantic_edge_vo/support/host_cpu.h"

namespace semantic_edge_vo {
namespace {

TEST(HostCpu, ParsesTheAggregateLineOfProcStat) {
  // A real /proc/stat head (KVM guest, 2 CPUs); the per-CPU lines must not be taken for it.
  const std::string text =
      "cpu  2928616 7 181266 2411248 10865 3 2116 28352 0 0\n"
      "cpu0 1055503 0 81443 1624259 1043 0 726 16433 0 0\n"
      "intr 1 2 3\n";
  HostCpuTimes times;
  std::string error;
  ASSERT_TRUE(parseHostCpuTimes(text, &times, &error)) << error;
  EXPECT_EQ(times.busy, 2928616u + 7u + 181266u + 3u + 2116u);
  EXPECT_EQ(times.idle, 2411248u + 10865u);
  EXPECT_EQ(times.steal, 28352u);
}

TEST(HostCpu, RefusesAStatWithoutStealOrCpuLine) {
  HostCpuTimes times;
  std::string error;
  EXPECT_FALSE(parseHostCpuTimes("cpu  1 2 3 4\n", &times, &error));
  EXPECT_NE(error.find("steal"), std::string::npos) << error;
  EXPECT_FALSE(parseHostCpuTimes("cpu0 1 2 3 4 5 6 7 8\n", &times, &error));
  EXPECT_NE(error.find("no aggregate"), std::string::npos) << error;
}

TEST(HostCpu, StolenShareIsStealOverAllTimeBetweenReadings) {
  HostCpuTimes before, after;
  before.busy = 100;
  before.idle = 50;
  before.steal = 10;
  after = before;
  EXPECT_EQ(stolenShare(before, after), 0.0);  // no time passed
  after.busy += 60;
  after.idle += 20;
  after.steal += 20;
  EXPECT_DOUBLE_EQ(stolenShare(before, after), 0.2);
  EXPECT_EQ(stolenShare(after, before), 0.0);  // readings swapped: nothing sensible to say
}

TEST(HostCpu, ProcessCpuTimeGrowsWithWorkNotWithSleep) {
  const double start = processCpuSeconds();
  volatile double sink = 0.0;
  for (int i = 0; i < 20000000; ++i) sink = sink + 1e-9 * i;
  const double worked = processCpuSeconds() - start;
  EXPECT_GT(worked, 0.0);
  const double before_sleep = processCpuSeconds();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_LT(processCpuSeconds() - before_sleep, 0.05) << "a sleeping process uses no CPU time";
  HostCpuTimes now;
  // On Linux (where these tests run) /proc/stat is always there.
  EXPECT_TRUE(readHostCpuTimes(&now));
  EXPECT_GT(now.total(), 0u);
}

}  // namespace
}  // namespace semantic_edge_vo
