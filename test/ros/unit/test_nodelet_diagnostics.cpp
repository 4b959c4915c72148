#include <gtest/gtest.h>

#include "semantic_edge_vo/ros/nodelet_diagnostics.h"

namespace semantic_edge_vo {
namespace {

std::string valueOf(const diagnostic_msgs::DiagnosticStatus& status, const std::string& key) {
  for (const auto& pair : status.values)
    if (pair.key == key) return pair.value;
  return "(none)";
}

TEST(DiagnosticCounts, RateTimesAndLossesFromSequenceGaps) {
  DiagnosticCounts counts;
  for (std::uint32_t seq : {10u, 11u, 14u, 15u}) counts.input(seq);  // 12 and 13 lost on the way
  counts.processed(20.0);
  counts.processed(40.0);
  counts.processed(30.0);
  const diagnostic_msgs::DiagnosticStatus status = counts.takePeriod(2.0);
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(valueOf(status, "input rate (Hz)"), "2.0");
  EXPECT_EQ(valueOf(status, "processing time median (ms)"), "30.0");
  EXPECT_EQ(valueOf(status, "processing time max (ms)"), "40.0");
  EXPECT_EQ(valueOf(status, "inputs lost in queues (total)"), "2");
}

TEST(DiagnosticCounts, DropsWarnForTheirPeriodAndAreTotalled) {
  DiagnosticCounts counts;
  counts.dropped(3);
  diagnostic_msgs::DiagnosticStatus status = counts.takePeriod(1.0);
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::WARN);
  EXPECT_EQ(valueOf(status, "inputs dropped (period)"), "3");
  status = counts.takePeriod(1.0);
  EXPECT_EQ(status.level, diagnostic_msgs::DiagnosticStatus::OK);
  EXPECT_EQ(valueOf(status, "inputs dropped (total)"), "3");
}

TEST(DiagnosticCounts, ANewPublisherIsNotALoss) {
  DiagnosticCounts counts;
  for (std::uint32_t seq : {500u, 501u, 1u, 2u, 90000u, 90001u}) counts.input(seq);  // restarted twice
  EXPECT_EQ(valueOf(counts.takePeriod(1.0), "inputs lost in queues (total)"), "0");
}

}  // namespace
}  // namespace semantic_edge_vo
