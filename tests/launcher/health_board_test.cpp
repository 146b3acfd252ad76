// The system health view without DDS (mpgc/runtime/health_board.hpp): status per component from
// samples, their age and what the caller knows of the processes; changes; the rendered summaries.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "mpgc/runtime/health_board.hpp"

namespace rt = mpgc::rt;
using rt::Reported;
using rt::Status;

namespace {
constexpr int64_t kS = 1'000'000'000;  // [ns]

Status status_of(const rt::HealthBoard& b, const std::string& name, int64_t now) {
  for (const auto& v : b.view(now))
    if (v.name == name) return v.status;
  ADD_FAILURE() << name << " not on the board";
  return Status::kUp;
}
std::string detail_of(const rt::HealthBoard& b, const std::string& name, int64_t now) {
  for (const auto& v : b.view(now))
    if (v.name == name) return v.detail;
  return "(missing)";
}

// Stands in for msg::ComponentHealth (the same field names, the enum's order).
enum class FakeState { STARTING, OK, DEGRADED, ERROR, STOPPING };
struct FakeHealth {
  std::string component;
  FakeState state;
  std::string detail;
};
}  // namespace

TEST(HealthBoard, StatusFollowsTheRules) {
  rt::HealthBoard b({1.0, 3});  // stale after 3 s
  b.expect("opp", 0);
  b.expect("gc", 0);
  EXPECT_EQ(status_of(b, "opp", 1 * kS), Status::kStarting);  // within the stale time: not yet judged
  EXPECT_EQ(status_of(b, "opp", 4 * kS), Status::kDown);      // never heard, process unknown
  EXPECT_EQ(detail_of(b, "opp", 4 * kS), "never heard");
  b.sample("opp", Reported::kOk, "", 4 * kS);
  b.sample("gc", Reported::kDegraded, "no plan", 4 * kS);
  EXPECT_EQ(status_of(b, "opp", 5 * kS), Status::kUp);
  EXPECT_EQ(status_of(b, "gc", 5 * kS), Status::kDegraded);
  EXPECT_EQ(detail_of(b, "gc", 5 * kS), "no plan");
  EXPECT_EQ(status_of(b, "opp", 7 * kS), Status::kUp);        // exactly 3 periods: still up
  EXPECT_EQ(status_of(b, "opp", 7 * kS + 1), Status::kStale);  // a hung process or a cut network
  EXPECT_EQ(detail_of(b, "opp", 8 * kS), "no health for 4.0 s");
  b.sample("gc", Reported::kError, "solver threw", 8 * kS);
  EXPECT_EQ(status_of(b, "gc", 8 * kS), Status::kDegraded);
  EXPECT_EQ(detail_of(b, "gc", 8 * kS), "error: solver threw");
  b.sample("gc", Reported::kStopping, "", 9 * kS);
  EXPECT_EQ(status_of(b, "gc", 9 * kS), Status::kDown);
  EXPECT_EQ(detail_of(b, "gc", 9 * kS), "stopped");
  b.sample("gc", Reported::kStarting, "", 10 * kS);
  EXPECT_EQ(status_of(b, "gc", 10 * kS), Status::kStarting);
}

TEST(HealthBoard, ProcessKnowledgeOfTheCallerWins) {
  rt::HealthBoard b({1.0, 2});
  b.expect("opp", 0);
  b.process_started("opp", 0);
  b.sample("opp", Reported::kDegraded, "no goal", 1 * kS);
  b.process_gone("opp", "killed by signal 9, restarting 1/10", 2 * kS);
  EXPECT_EQ(status_of(b, "opp", 2 * kS), Status::kDown);
  EXPECT_EQ(detail_of(b, "opp", 2 * kS), "killed by signal 9, restarting 1/10");
  // Restarted: the old incarnation's "no goal" is forgotten until the new one speaks.
  b.process_started("opp", 3 * kS);
  EXPECT_EQ(status_of(b, "opp", 3 * kS), Status::kStarting);
  // Running but silent beyond the stale time: stale, not down (its process is there).
  EXPECT_EQ(status_of(b, "opp", 6 * kS), Status::kStale);
  EXPECT_NE(detail_of(b, "opp", 6 * kS).find("running, no health heard"), std::string::npos);
  b.sample("opp", Reported::kOk, "", 6 * kS);
  EXPECT_EQ(status_of(b, "opp", 6 * kS), Status::kUp);
  // Not a component (gpsd): its process is its status.
  b.expect("gpsd", 0, false);
  EXPECT_EQ(status_of(b, "gpsd", 100 * kS), Status::kStale);
  b.process_started("gpsd", 100 * kS);
  EXPECT_EQ(status_of(b, "gpsd", 200 * kS), Status::kUp);
  b.process_gone("gpsd", "exited with code 1", 200 * kS);
  EXPECT_EQ(status_of(b, "gpsd", 200 * kS), Status::kDown);
}

TEST(HealthBoard, SummariesNameWhatIsWrong) {
  rt::HealthBoard b;
  EXPECT_EQ(b.line(0), "no components");
  for (const char* n : {"ship_simulator", "opp", "guidance_control"}) {
    b.expect(n, 0);
    b.sample(n, Reported::kOk, "", 0);
  }
  EXPECT_EQ(b.line(1 * kS), "all 3 up");
  b.process_gone("opp", "killed by signal 9, restarting 1/10", 1 * kS);
  b.sample("guidance_control", Reported::kDegraded, "no plan", 1 * kS);
  EXPECT_EQ(b.line(1 * kS), "opp down (killed by signal 9, restarting 1/10); guidance_control degraded: no plan; 1 up");
  // Heard on the bus but not expected (another host's component): listed after the expected ones.
  FakeHealth other{"ais_gateway", FakeState::DEGRADED, "no fix"};
  b.sample(other, 1 * kS);
  const auto v = b.view(1 * kS);
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].name, "ship_simulator");
  EXPECT_EQ(v[1].name, "opp");
  EXPECT_EQ(v[3].name, "ais_gateway");
  EXPECT_FALSE(v[3].expected);
  EXPECT_EQ(v[3].status, Status::kDegraded);
  const std::string t = b.table(1 * kS);
  EXPECT_NE(t.find("component"), std::string::npos) << t;
  EXPECT_NE(t.find("guidance_control  degraded  0.0 s ago  no plan\n"), std::string::npos) << t;
  EXPECT_NE(t.find("(not launched here)"), std::string::npos) << t;
  EXPECT_EQ(std::count(t.begin(), t.end(), '\n'), 5);
}

TEST(HealthBoard, ChangesAreReportedOnceAndRunningTimesAreNoChange) {
  rt::HealthBoard b({1.0, 3});
  b.expect("a", 0);
  b.expect("b", 0);
  EXPECT_EQ(b.changes(0).size(), 2u);  // the first call: everything
  EXPECT_TRUE(b.changes(1 * kS).empty());
  b.sample("a", Reported::kOk, "", 1 * kS);
  auto c = b.changes(1 * kS);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].name, "a");
  EXPECT_EQ(c[0].status, Status::kUp);
  c = b.changes(5 * kS);  // a stale (heard 4 s ago), b down (never heard)
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].status, Status::kStale);
  EXPECT_EQ(c[1].status, Status::kDown);
  EXPECT_TRUE(b.changes(9 * kS).empty());  // "no health for 8.0 s" is the same stale
  b.sample("a", Reported::kDegraded, "no plan", 9 * kS);
  EXPECT_EQ(b.changes(9 * kS).size(), 1u);
  b.sample("a", Reported::kDegraded, "no plan", 10 * kS);
  EXPECT_TRUE(b.changes(10 * kS).empty());
  b.sample("a", Reported::kDegraded, "stale own state", 11 * kS);  // another reason: a change
  EXPECT_EQ(b.changes(11 * kS).size(), 1u);
}

TEST(HealthBoard, BadParametersAreRefused) {
  EXPECT_THROW(rt::HealthBoard({0.0, 3}), std::invalid_argument);
  EXPECT_THROW(rt::HealthBoard({1.0, 0}), std::invalid_argument);
}
