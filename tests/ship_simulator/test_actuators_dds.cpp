// The simulator process's actuator side over DDS, in lockstep with an in-test guidance stand-in:
// orders beyond the rudder limit are saturated and counted (not refused), a NaN order is refused,
// orders every 0.5 s never trip the watchdog, and a silence does: rudder amidships, health
// DEGRADED with the reason, one trip counted, back to OK with the next order.
#include <gtest/gtest.h>

#include <spawn.h>
#include <sys/wait.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <thread>

#include <spdlog/sinks/null_sink.h>

#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

extern char** environ;

namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;

namespace {
using mpgc::testing::spawn;
using mpgc::testing::wait_child;
}  // namespace

TEST(ActuatorsDds, SaturatesOrdersAndTripsTheWatchdogOnlyWhenOrdersStop) {
  const int domain = mpgc::testing::unique_domain();
  const std::string world = ::testing::TempDir() + "/actuators_world_" + std::to_string(domain) + ".yaml";
  {
    std::ofstream w(world);
    w << "origin: {lat_deg: 38.9, lon_deg: -76.4}\nseed: 5\n"
      << "own_ship: {model: mmg, data_dir: \"" << mpgc::testing::shared_data("ship_models")
      << "\", heading_deg: 0, speed_kn: 14}\n";
  }
  rt::RuntimeParams rp;
  rp.domain = domain;
  rp.clock = "sim";
  auto log = std::make_shared<spdlog::logger>("guidance", std::make_shared<spdlog::sinks::null_sink_mt>());
  rt::Component peer("guidance", rp, log);

  // Steps 0..199: hard over at the old GC limit (0.6109 rad > 35 deg) every 0.5 s, one NaN order
  // (the rudder reaches 35 deg after 15 s at 2.32 deg/s); 200..399: silence (guidance gone);
  // 400..: 0.1 rad every 0.5 s.
  std::mutex mu;
  double last_rudder = std::nan(""), min_rudder_silent = 1.0, max_rudder_loud = 0.0;
  int64_t k_amidships = -1;  // first step after the last order at which the rudder leaves hard over
  peer.subscribe<msg::NavState>(topics::kOwnState, dds::QosProfile::state(), [&](const msg::NavState& n) {
    std::lock_guard<std::mutex> l(mu);
    const int64_t k = n.header.stamp_ns / 100'000'000;
    last_rudder = n.rudder;
    if (k < 200) max_rudder_loud = std::max(max_rudder_loud, n.rudder);
    if (k > 200 && k < 400) min_rudder_silent = std::min(min_rudder_silent, std::abs(n.rudder));
    if (k > 195 && k_amidships < 0 && n.rudder < max_rudder_loud - 0.01) k_amidships = k;
  });
  std::map<std::string, uint64_t> counters;
  uint64_t rejected = 0;
  std::vector<msg::HealthState> states;  // the simulator's health stamps are wall time: order only
  std::string degraded_detail;
  peer.subscribe<msg::ComponentHealth>(topics::kHealth, dds::QosProfile::latched(16), [&](const msg::ComponentHealth& h) {
    if (h.component != "ship_simulator") return;
    std::lock_guard<std::mutex> l(mu);
    rejected = h.rejected_inputs;
    for (const auto& c : h.counters) counters[c.name] = c.value;
    if (states.empty() || states.back() != h.state) states.push_back(h.state);
    if (h.state == msg::HealthState::HEALTH_DEGRADED) degraded_detail = h.detail;
  });
  auto& act = peer.publisher<msg::ActuatorCommand>(topics::kActuators, dds::QosProfile::command(16));
  peer.every(0.5, [&] {
    const int64_t k = peer.now_ns() / 100'000'000;
    msg::ActuatorCommand a{peer.header(), 0.6109, 80.0};
    if (k == 50) a.rudder = std::nan("");
    if (k >= 200 && k < 400) return;
    if (k >= 400) a.rudder = 0.1;
    act.write(a);
  });
  std::thread spinner([&] { peer.spin(); });

  const pid_t pid = spawn({mpgc::testing::bin_dir() + "/mpgc_ship_simulator", "--domain", std::to_string(domain),
                           "--log-level", "error", "--set", "world.file=" + world, "--set", "time.mode=lockstep",
                           "--set", "lockstep.participants=guidance", "--set", "lockstep.ack_timeout=0.2", "--set",
                           "time.duration=50", "--set", "health.period=0.1"});
  ASSERT_GT(pid, 0);
  const int rc = wait_child(pid, 120.0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  peer.stop();
  spinner.join();
  EXPECT_EQ(rc, 0);

  std::lock_guard<std::mutex> l(mu);
  EXPECT_EQ(rejected, 1u) << "only the NaN order is refused";
  EXPECT_EQ(counters["saturated.rudder"], 39u) << "every order of steps 0..195 (every 5th) but the NaN one";
  EXPECT_EQ(counters["saturated.rpm"], 0u);
  EXPECT_NEAR(max_rudder_loud, 35.0 * M_PI / 180.0, 1e-6) << "saturated hard over, not refused";
  EXPECT_EQ(counters["watchdog_trips"], 1u);
  EXPECT_LT(min_rudder_silent, 1e-3) << "rudder amidships during the silence";
  EXPECT_NEAR(last_rudder, 0.1, 1e-3) << "orders followed again";
  EXPECT_NE(degraded_detail.find("actuator watchdog: no order for"), std::string::npos) << degraded_detail;
  // The last order came at t = 19.5 s: tripped at 21.6 s (2 s without an order), the servo then
  // leaves hard over within a few steps (0.23 deg per step at 2.32 deg/s).
  EXPECT_GE(k_amidships, 216);
  EXPECT_LE(k_amidships, 222);
  // Health: DEGRADED while tripped, OK again with the next order.
  bool degraded = false, ok_after = false;
  for (const auto s : states) {
    if (s == msg::HealthState::HEALTH_DEGRADED) degraded = true;
    if (s == msg::HealthState::HEALTH_OK && degraded) ok_after = true;
  }
  EXPECT_TRUE(degraded);
  EXPECT_TRUE(ok_after);
}
