// Lockstep over DDS: the simulator process and an in-test participant (an mpgc::rt::Component
// on clock.source=sim). The simulator must never publish step k+1 before the participant has
// acted on step k, and bad actuator commands must be rejected while the last valid one holds.
#include <set>

#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <thread>

#include <spdlog/sinks/null_sink.h>

#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/ship_simulator/lockstep.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/text/list.hpp"
#include "mpgc/topics.hpp"

extern char** environ;

namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;
namespace sim = mpgc::ship_simulator;

TEST(LockstepBarrier, WaitsForEveryParticipant) {
  sim::LockstepBarrier b(mpgc::text::split_list(" guidance, opp ,,"));
  b.begin(4);
  EXPECT_FALSE(b.complete());
  EXPECT_EQ(b.ack("guidance", 3), sim::LockstepBarrier::Ack::Stale);
  EXPECT_EQ(b.ack("nobody", 4), sim::LockstepBarrier::Ack::Unknown);
  EXPECT_EQ(b.ack("guidance", 4), sim::LockstepBarrier::Ack::Counted);
  EXPECT_EQ(b.ack("guidance", 4), sim::LockstepBarrier::Ack::Duplicate);
  EXPECT_FALSE(b.complete());
  EXPECT_EQ(b.missing(), std::vector<std::string>{"opp"});
  EXPECT_EQ(b.ack("opp", 4), sim::LockstepBarrier::Ack::Counted);
  EXPECT_TRUE(b.complete());
  b.begin(5);
  EXPECT_FALSE(b.complete());
  EXPECT_THROW(sim::LockstepBarrier({"a", "a"}), std::invalid_argument);
}

TEST(LockstepBarrier, GoesOnWithoutADroppedParticipantAndReadmitsItOnItsNextAck) {
  sim::LockstepBarrier b({"guidance", "opp"});
  b.begin(7);
  EXPECT_EQ(b.ack("guidance", 7), sim::LockstepBarrier::Ack::Counted);
  EXPECT_TRUE(b.drop("opp"));
  EXPECT_FALSE(b.drop("opp"));
  EXPECT_FALSE(b.drop("nobody"));
  EXPECT_TRUE(b.complete());
  EXPECT_EQ(b.present(), 1u);
  EXPECT_EQ(b.absent(), std::set<std::string>{"opp"});
  b.begin(8);
  EXPECT_TRUE(b.missing() == std::vector<std::string>{"guidance"});
  // A restarted opp acks the step it first saw: an old one, so it owes the current one.
  EXPECT_EQ(b.ack("opp", 3), sim::LockstepBarrier::Ack::Readmitted);
  EXPECT_TRUE(b.absent().empty());
  EXPECT_EQ(b.ack("guidance", 8), sim::LockstepBarrier::Ack::Counted);
  EXPECT_FALSE(b.complete());
  EXPECT_EQ(b.ack("opp", 8), sim::LockstepBarrier::Ack::Counted);
  EXPECT_TRUE(b.complete());
  // Re-admitted by an ack of the current step: counted at once.
  b.begin(9);
  b.drop("guidance");
  EXPECT_EQ(b.ack("guidance", 9), sim::LockstepBarrier::Ack::Readmitted);
  EXPECT_EQ(b.missing(), std::vector<std::string>{"opp"});
}

namespace {
using mpgc::testing::spawn;
using mpgc::testing::wait_child;
}  // namespace

TEST(LockstepBarrier, TheEarliestTimerOfThePresentParticipantsSetsTheNextClock) {
  sim::LockstepBarrier b({"guidance", "opp"});
  EXPECT_EQ(b.due_ns(), 0);  // nobody has said yet
  b.begin(0);
  b.ack("guidance", 0, 500);
  EXPECT_EQ(b.due_ns(), 0);  // opp has not
  b.ack("opp", 0, 300);
  EXPECT_EQ(b.due_ns(), 300);
  b.ack("opp", 0, -7);  // a negative one: at once
  EXPECT_EQ(b.due_ns(), 0);
  b.ack("opp", 0, std::numeric_limits<int64_t>::max());  // no timer at all
  EXPECT_EQ(b.due_ns(), 500);
  b.drop("guidance");  // an absent one is not waited for
  EXPECT_EQ(b.due_ns(), std::numeric_limits<int64_t>::max());
  // A Clock at the due step and the one before it, or after kMaxStepsWithoutClock without one.
  EXPECT_FALSE(sim::clock_due(300, 100, 500, 0));
  EXPECT_TRUE(sim::clock_due(400, 100, 500, 0));
  EXPECT_TRUE(sim::clock_due(500, 100, 500, 0));
  EXPECT_TRUE(sim::clock_due(700, 100, 500, 0));
  EXPECT_FALSE(sim::clock_due(100, 100, std::numeric_limits<int64_t>::max(), sim::kMaxStepsWithoutClock - 1));
  EXPECT_TRUE(sim::clock_due(100, 100, std::numeric_limits<int64_t>::max(), sim::kMaxStepsWithoutClock));
}

namespace {
// A world of one target for the lockstep runs; returns its file.
std::string lockstep_world(int domain) {
  const std::string world = ::testing::TempDir() + "/lockstep_world_" + std::to_string(domain) + ".yaml";
  std::ofstream w(world);
  w << "origin: {lat_deg: 38.9, lon_deg: -76.4}\nseed: 5\n"
    << "own_ship: {model: mmg, data_dir: \"" << mpgc::testing::shared_data("ship_models")
    << "\", heading_deg: 0, speed_kn: 15}\n"
    << "targets: [{mmsi: 257000001, x_m: 2000, y_m: 500, course_deg: 180, speed_kn: 10}]\n";
  return world;
}

// The in-test participant "peer" on simulated time.
rt::RuntimeParams peer_params(int domain) {
  rt::RuntimeParams rp;
  rp.domain = domain;
  rp.clock = "sim";
  return rp;
}
std::shared_ptr<spdlog::logger> quiet() {
  return std::make_shared<spdlog::logger>("peer", std::make_shared<spdlog::sinks::null_sink_mt>());
}
}  // namespace

TEST(LockstepDds, SimulatorNeverRunsAheadOfTheParticipant) {
  const int domain = mpgc::testing::unique_domain();
  const std::string world = lockstep_world(domain);
  rt::Component peer("peer", peer_params(domain), quiet());

  std::atomic<uint64_t> max_seen{0};
  peer.subscribe<msg::Clock>(topics::kClock, dds::QosProfile::command(16),
                             [&](const msg::Clock& c) { max_seen = std::max<uint64_t>(max_seen, c.step); });
  double last_rudder = std::nan(""), last_x = 0.0;
  peer.subscribe<msg::NavState>(topics::kOwnState, dds::QosProfile::state(), [&](const msg::NavState& n) {
    last_rudder = n.rudder;
    last_x = n.x;
  });
  uint64_t sim_rejected = 0;
  peer.subscribe<msg::ComponentHealth>(topics::kHealth, dds::QosProfile::latched(), [&](const msg::ComponentHealth& h) {
    if (h.component == "ship_simulator") sim_rejected = h.rejected_inputs;
  });
  auto& act = peer.publisher<msg::ActuatorCommand>(topics::kActuators, dds::QosProfile::command(16));
  std::vector<uint64_t> ticks;
  int ahead = 0;
  const double ten = mpgc::geo::deg2rad(10.0);
  peer.every(0.1, [&] {
    const uint64_t k = static_cast<uint64_t>(peer.now_ns() / 100'000'000);
    ticks.push_back(k);
    if (max_seen > k) ++ahead;  // a Clock beyond the step we are still acting on
    if (k % 7 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(3));  // a slow participant
    msg::ActuatorCommand a{peer.header(), ten, 80.0};
    if (k == 5) act.write(a);
    if (k == 10) {
      a.rudder = std::nan("");
      act.write(a);
    }
    if (k == 15) {
      a.rudder = 1.0;  // 57 deg: beyond the 35 deg limit, saturated to it
      act.write(a);
    }
  });
  std::thread spinner([&] { peer.spin(); });

  const pid_t pid = spawn({mpgc::testing::bin_dir() + "/mpgc_ship_simulator", "--domain", std::to_string(domain),
                           "--log-level", "warn", "--set", "world.file=" + world, "--set", "time.mode=lockstep",
                           "--set", "lockstep.participants=peer", "--set", "lockstep.ack_timeout=0.2", "--set",
                           "time.duration=30", "--set", "watchdog.timeout=60"});  // the orders stop at 1.5 s
  ASSERT_GT(pid, 0);
  const int rc = wait_child(pid, 120.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the final health sample
  peer.stop();
  spinner.join();

  EXPECT_EQ(rc, 0);
  ASSERT_EQ(ticks.size(), 301u);  // steps 0..300 of 30 s, each acted on exactly once
  for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_EQ(ticks[i], i);
  EXPECT_EQ(ahead, 0);
  EXPECT_NEAR(last_rudder, mpgc::geo::deg2rad(35.0), 1e-6);  // 57 deg saturated to the limit and held
  EXPECT_GT(last_x, 200.0);
  EXPECT_EQ(sim_rejected, 1u);  // only the NaN order
}

// A participant whose timer is due every 0.5 s: the simulator publishes the Clock of the due steps
// and of the steps just before them only, and the participant still sees every step's own state on
// that step's clock and acts on each due step exactly once.
TEST(LockstepDds, StepsAtWhichNoTimerIsDueGoWithoutAClock) {
  const int domain = mpgc::testing::unique_domain();
  const std::string world = lockstep_world(domain);
  rt::Component peer("peer", peer_params(domain), quiet());
  // The Clocks as published, on a reader of its own that keeps them all (the peer's delivers a
  // Clock at the next tick: the last one never).
  dds::Participant watcher(static_cast<uint32_t>(domain));
  dds::Topic<msg::Clock> clock_topic(watcher, topics::kClock);
  dds::Reader<msg::Clock> clock_reader(watcher, clock_topic, dds::QosProfile::command(1000));
  std::vector<std::pair<int64_t, int64_t>> nav;  // (now, stamp)
  peer.subscribe<msg::NavState>(topics::kOwnState, dds::QosProfile::state(),
                                [&](const msg::NavState& n) { nav.emplace_back(peer.now_ns(), n.header.stamp_ns); });
  std::vector<int64_t> ticks;
  peer.every(0.5, [&] { ticks.push_back(peer.now_ns()); });
  std::thread spinner([&] { peer.spin(); });
  const pid_t pid = spawn({mpgc::testing::bin_dir() + "/mpgc_ship_simulator", "--domain", std::to_string(domain),
                           "--log-level", "warn", "--set", "world.file=" + world, "--set", "time.mode=lockstep",
                           "--set", "lockstep.participants=peer", "--set", "time.duration=30"});
  ASSERT_GT(pid, 0);
  const int rc = wait_child(pid, 120.0);
  peer.stop();
  spinner.join();

  EXPECT_EQ(rc, 0);
  std::vector<uint64_t> clocks;
  for (const auto& c : clock_reader.take(100000))
    if (clocks.empty() || clocks.back() != c.value.step) clocks.push_back(c.value.step);  // not a resend
  std::vector<uint64_t> expected{0};
  for (uint64_t k = 4; k <= 300; k += 5) expected.insert(expected.end(), {k, k + 1});
  std::string seen;
  for (const uint64_t k : clocks) seen += std::to_string(k) + " ";
  EXPECT_EQ(clocks, expected) << "Clocks: " << seen;
  ASSERT_EQ(nav.size(), 301u);  // every step, on its own clock
  for (std::size_t i = 0; i < nav.size(); ++i) {
    EXPECT_EQ(nav[i].second, static_cast<int64_t>(i) * 100'000'000);
    EXPECT_EQ(nav[i].first, nav[i].second);
  }
  ASSERT_EQ(ticks.size(), 61u);
  for (std::size_t i = 0; i < ticks.size(); ++i) EXPECT_EQ(ticks[i], static_cast<int64_t>(i) * 500'000'000);
}

namespace {
std::string run(const std::string& cmd, int* rc) {
  std::string out;
  FILE* f = popen(cmd.c_str(), "r");
  if (f == nullptr) return out;
  char buf[4096];
  while (fgets(buf, sizeof(buf), f) != nullptr) out += buf;
  const int st = pclose(f);
  *rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}
}  // namespace

TEST(TrialExecutable, PrintsOneJsonObjectAndRejectsBadArguments) {
  const std::string exe = mpgc::testing::bin_dir() + "/mpgc_trial";
  int rc = -1;
  const std::string tc = run(exe + " turning-circle --rudder-deg 35 --side port 2>/dev/null", &rc);
  EXPECT_EQ(rc, 0);
  for (const char* key : {"\"advance_m\":", "\"transfer_m\":", "\"tactical_diameter_m\":", "\"steady_diameter_m\":",
                          "\"speed_ratio_steady\":"})
    EXPECT_NE(tc.find(key), std::string::npos) << key << " missing in " << tc;
  EXPECT_EQ(tc.front(), '{');
  EXPECT_EQ(tc.substr(tc.size() - 2), "}\n");
  const std::string zz = run(exe + " zigzag --angle-deg 20 --side starboard 2>/dev/null", &rc);
  EXPECT_EQ(rc, 0);
  EXPECT_NE(zz.find("\"first_overshoot_deg\":"), std::string::npos);
  EXPECT_NE(zz.find("\"second_overshoot_deg\":"), std::string::npos);
  run(exe + " zigzag --angle-deg 20 --side sideways 2>/dev/null", &rc);
  EXPECT_NE(rc, 0);
  run(exe + " table --out /nonexistent/dir/t.csv 2>/dev/null", &rc);
  EXPECT_NE(rc, 0);
  run(exe + " table --out /dev/null --rudders-deg 10,abc 2>/dev/null", &rc);
  EXPECT_NE(rc, 0);
}
