// Integration over DDS (own domain, loopback): the real mpgc_guidance_control process takes own
// state and plans, publishes actuator commands and status; a bad plan is rejected (counted in
// health) while the last good plan is kept; a stale plan and a "no path" plan give safe mode.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <thread>

#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

extern char** environ;

namespace msg = mpgc::msg;
using mpgc::dds::QosProfile;

namespace {

using mpgc::testing::Process;

msg::Path path(uint32_t id, std::vector<std::pair<double, double>> pts, msg::PlanStatus st = msg::PlanStatus::PLAN_OK) {
  msg::Path p;
  p.plan_id = id;
  p.status = st;
  for (auto& [x, y] : pts) {
    msg::Waypoint w;
    w.x = x;
    w.y = y;
    w.speed = 7.0;
    p.waypoints.push_back(w);
  }
  return p;
}

struct Rig {
  mpgc::dds::Participant part;
  mpgc::dds::Topic<msg::NavState> nav_t;
  mpgc::dds::Topic<msg::Path> path_t;
  mpgc::dds::Topic<msg::ActuatorCommand> cmd_t;
  mpgc::dds::Topic<msg::GuidanceStatus> status_t;
  mpgc::dds::Topic<msg::ComponentHealth> health_t;
  mpgc::dds::Writer<msg::NavState> nav;
  mpgc::dds::Writer<msg::Path> plan;
  mpgc::dds::Reader<msg::ActuatorCommand> cmd;
  mpgc::dds::Reader<msg::GuidanceStatus> status;
  mpgc::dds::Reader<msg::ComponentHealth> health;
  msg::GuidanceStatus last_status;
  msg::ActuatorCommand last_cmd;
  uint64_t rejected = 0;
  msg::HealthState health_state = msg::HealthState::HEALTH_STARTING;
  std::string health_detail;
  int n_cmd = 0;
  std::function<void(const msg::GuidanceStatus&)> on_status;

  explicit Rig(int domain)
      : part(static_cast<uint32_t>(domain)),
        nav_t(part, mpgc::topics::kOwnState),
        path_t(part, mpgc::topics::kPath),
        cmd_t(part, mpgc::topics::kActuators),
        status_t(part, mpgc::topics::kGuidanceStatus),
        health_t(part, mpgc::topics::kHealth),
        nav(part, nav_t, QosProfile::state()),
        plan(part, path_t, QosProfile::latched()),
        cmd(part, cmd_t, QosProfile::command()),
        status(part, status_t, QosProfile::state()),
        health(part, health_t, QosProfile::latched(8)) {}

  // Publishes own state (ship at (0, 100) heading north at 7 m/s) at 10 Hz for up to `seconds`,
  // collecting outputs, until `done` holds.
  bool pump(double seconds, const std::function<bool()>& done) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      msg::NavState s;
      s.x = 0;
      s.y = 100;
      s.heading = 0;
      s.u = 7;
      s.sog = 7;
      s.valid_mask = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID | msg::NAV_RATE_VALID;
      nav.write(s);
      for (auto& c : cmd.take()) last_cmd = c.value, ++n_cmd;
      for (auto& st : status.take()) {
        last_status = st.value;
        if (on_status) on_status(st.value);
      }
      for (auto& h : health.take())
        if (h.value.component == "guidance_control") {
          rejected = h.value.rejected_inputs;
          health_state = h.value.state;
          health_detail = h.value.detail;
        }
      if (done && done()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
  }
};

}  // namespace

TEST(GuidanceControlProcess, FollowsRejectsAndFallsBackToSafeMode) {
  const int domain = mpgc::testing::unique_domain();
  Process proc({mpgc::testing::bin_dir() + "/mpgc_guidance_control", "--domain", std::to_string(domain), "--set",
                "rate=10", "--set", "plan.max_age=3", "--set", "health.period=0.2", "--log-level", "warn"});
  Rig rig(domain);
  ASSERT_TRUE(rig.pump(15, [&] { return rig.n_cmd > 3 && rig.last_status.header.seq > 0; }))
      << "no commands from the process";
  ASSERT_TRUE(proc.running());
  EXPECT_EQ(rig.last_status.mode, msg::GuidanceMode::GUIDANCE_IDLE);

  // A valid plan north along y = 0; the ship is 100 m to starboard -> port rudder.
  rig.plan.write(path(1, {{-1000, 0}, {20000, 0}}));
  ASSERT_TRUE(rig.pump(5, [&] {
    return rig.last_status.mode == msg::GuidanceMode::GUIDANCE_FOLLOWING && rig.last_status.plan_id == 1 &&
           rig.last_cmd.rudder < 0;
  })) << "mode " << static_cast<int>(rig.last_status.mode) << " plan " << rig.last_status.plan_id;
  EXPECT_NEAR(rig.last_status.cross_track_error, 100.0, 1e-6);
  EXPECT_GT(rig.last_cmd.propeller_rpm, 0.0);

  // A plan with a NaN waypoint: rejected and counted, plan 1 kept.
  auto bad = path(2, {{0, 0}, {5000, 0}});
  bad.waypoints[1].x = std::nan("");
  rig.plan.write(bad);
  ASSERT_TRUE(rig.pump(5, [&] { return rig.rejected >= 1; })) << "rejection not counted in health";
  rig.plan.write(path(3, {{0, 0}}));  // one point
  ASSERT_TRUE(rig.pump(5, [&] { return rig.rejected >= 2; }));
  EXPECT_EQ(rig.last_status.mode, msg::GuidanceMode::GUIDANCE_FOLLOWING);
  EXPECT_EQ(rig.last_status.plan_id, 1u);

  // No valid plan for plan.max_age = 3 s -> safe mode: hold heading, slow down.
  ASSERT_TRUE(rig.pump(10, [&] { return rig.last_status.mode == msg::GuidanceMode::GUIDANCE_SAFE_MODE; }));
  EXPECT_NE(rig.last_status.detail.find("no valid plan"), std::string::npos) << rig.last_status.detail;
  EXPECT_DOUBLE_EQ(rig.last_status.desired_speed, 3.0);

  // A valid plan ends safe mode; the planner's "no path" starts it again.
  rig.plan.write(path(4, {{-1000, 0}, {20000, 0}}));
  ASSERT_TRUE(rig.pump(5, [&] { return rig.last_status.mode == msg::GuidanceMode::GUIDANCE_FOLLOWING && rig.last_status.plan_id == 4; }));

  // A late plan (effective_ns 1.5 s ahead) is held: plan 4 is followed until then.
  auto late = path(6, {{-1000, 0}, {20000, 0}});
  late.effective_ns = dds_time() + 1'500'000'000;
  int64_t first_stamp_6 = 0, last_stamp_4 = 0;
  rig.on_status = [&](const msg::GuidanceStatus& s) {
    if (s.plan_id == 6 && first_stamp_6 == 0) first_stamp_6 = s.header.stamp_ns;
    if (s.plan_id == 4) last_stamp_4 = s.header.stamp_ns;
  };
  rig.plan.write(late);
  ASSERT_TRUE(rig.pump(5, [&] { return first_stamp_6 != 0; })) << "the late plan never took effect";
  rig.on_status = nullptr;
  EXPECT_GE(first_stamp_6, late.effective_ns);
  EXPECT_GT(last_stamp_4, late.effective_ns - 600'000'000) << "plan 4 was not followed while plan 6 was held";

  // The planner's "no path": plan 6 is kept (degraded, on health too) until plan.max_age, then safe mode.
  auto none = path(5, {}, msg::PlanStatus::PLAN_NO_PATH);
  none.reason = "goal inside land";
  rig.plan.write(none);
  ASSERT_TRUE(rig.pump(5, [&] {
    return rig.last_status.mode == msg::GuidanceMode::GUIDANCE_FOLLOWING &&
           rig.last_status.detail.find("goal inside land") != std::string::npos &&
           rig.health_state == msg::HealthState::HEALTH_DEGRADED;
  })) << rig.last_status.detail << " / health " << static_cast<int>(rig.health_state);
  EXPECT_EQ(rig.last_status.plan_id, 6u);
  ASSERT_TRUE(rig.pump(5, [&] { return rig.last_status.mode == msg::GuidanceMode::GUIDANCE_SAFE_MODE; }));
  EXPECT_NE(rig.last_status.detail.find("goal inside land"), std::string::npos) << rig.last_status.detail;
  EXPECT_TRUE(proc.running());
}
