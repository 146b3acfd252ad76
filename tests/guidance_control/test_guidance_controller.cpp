// The supervisor: modes, plan validation with the last good plan kept, "no path" and stale plans
// (the last valid plan kept while young, then safe mode), own state lost (rudder amidships), late
// plans held until their effective time, actuator limits, and closed-loop path following on the
// Nomoto plant (straight leg, 90 deg turn, ILOS against current, re-plan mid-leg).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/guidance_control/guidance_control.hpp"
#include "mpgc/ship/actuator_limits.hpp"
#include "nomoto_plant.hpp"

namespace gc = mpgc::guidance_control;
using mpgc::geo::deg2rad;
using mpgc::geo::rad2deg;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

gc::PlanInput plan(uint32_t id, std::vector<gc::PathPoint> wps, gc::PlanKind kind = gc::PlanKind::Ok) {
  gc::PlanInput p;
  p.plan_id = id;
  p.kind = kind;
  p.stamp = kNaN;
  p.waypoints = std::move(wps);
  return p;
}

gc::NavInput nav_of(const gc::test::NomotoPlant& s) { return {s.x, s.y, mpgc::geo::wrap_pi(s.psi), s.u, s.r}; }

// The Mariner plant with an autopilot tuned for it by pole placement (README "Tuning").
struct Loop {
  gc::test::NomotoPlant ship;
  gc::GuidanceControlParams params;
  double t = 0.0, dt = 0.5;
  // The planner re-sends its plan every replan_period (seed 000 section 7: 15 s), as opp does.
  std::optional<gc::PlanInput> current;
  double replan_period = 15.0, last_send = 0.0;

  Loop() {
    const auto row = gc::test::read_nomoto("Mariner");
    ship.K = row.K;
    ship.T = row.T;
    ship.u = 7.0;
    ship.rpm = 7.0 * ship.rpm_per_mps;
    params.heading = gc::tune_heading_pid({row.K, row.T}, 0.05, 0.9);
    params.follower.default_speed = 7.0;
    // Guidance scaled by ship length as the README says: lookahead 2.5 L, acceptance radius 2 L.
    params.follower.lookahead = 2.5 * row.L;
    params.follower.acceptance_radius = 2.0 * row.L;
  }
  void send(gc::GuidanceController& c, const gc::PlanInput& p) {
    EXPECT_EQ(c.on_plan(p, t), "");
    current = p;
    last_send = t;
  }
  // Runs the loop for `seconds`, calling `each(status)` after every step.
  void run(gc::GuidanceController& c, double seconds, const std::function<void(const gc::Status&)>& each = {}) {
    const int n = static_cast<int>(seconds / dt);
    for (int i = 0; i < n; ++i) {
      if (current && t - last_send >= replan_period) send(c, *current);
      EXPECT_EQ(c.on_nav(nav_of(ship), t), "");
      const auto cmd = c.step(t);
      ship.step(dt, cmd.rudder, cmd.propeller_rpm);
      t += dt;
      if (each) each(cmd.status);
    }
  }
};

}  // namespace

TEST(GuidanceController, IdleHoldsHeadingThenFollowsAPlan) {
  Loop L;
  L.ship.psi = deg2rad(20);
  gc::GuidanceController c(L.params);
  L.run(c, 10);
  EXPECT_EQ(c.mode(), gc::Mode::Idle);
  EXPECT_NEAR(L.ship.psi, deg2rad(20), deg2rad(0.5));
  EXPECT_EQ(c.on_plan(plan(1, {{0, 0}, {20000, 0}}), L.t), "");
  gc::Status last;
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_EQ(last.plan_id, 1u);
  EXPECT_EQ(last.active_waypoint, 1u);
}

TEST(GuidanceController, BadPlansRejectedLastGoodPlanKept) {
  Loop L;
  gc::GuidanceController c(L.params);
  ASSERT_EQ(c.on_plan(plan(1, {{0, 0}, {5000, 0}, {5000, 5000}}), 0.0), "");
  L.run(c, 5);
  ASSERT_EQ(c.mode(), gc::Mode::Following);
  const auto good = c.follower().path();
  EXPECT_NE(c.on_plan(plan(2, {{0, 0}, {kNaN, 100}}), L.t).find("waypoint 1"), std::string::npos);
  EXPECT_NE(c.on_plan(plan(3, {}), L.t).find("empty"), std::string::npos);
  EXPECT_NE(c.on_plan(plan(4, {{100, 100}}), L.t).find("single"), std::string::npos);
  auto old = plan(5, {{0, 0}, {100, 0}});
  old.stamp = L.t - 1000.0;
  EXPECT_NE(c.on_plan(old, L.t).find("old"), std::string::npos);
  gc::Status last;
  L.run(c, 5, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_EQ(last.plan_id, 1u);
  ASSERT_EQ(c.follower().path().size(), good.size());
  for (std::size_t i = 0; i < good.size(); ++i) EXPECT_EQ(c.follower().path()[i].x, good[i].x);
}

// "No path" while a valid plan is young: keep following it (degraded, with the reason), then, once
// it is plan_max_age old, hold the heading of that moment and slow to the safe speed.
TEST(GuidanceController, NoPathKeepsTheLastValidPlanWhileFreshThenSafeMode) {
  Loop L;
  L.params.plan_max_age = 60.0;
  gc::GuidanceController c(L.params);
  c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0);  // received at t = 0, never re-sent
  L.run(c, 20);
  auto np = plan(2, {}, gc::PlanKind::NoPath);
  np.reason = "goal unreachable";
  ASSERT_EQ(c.on_plan(np, L.t), "");
  gc::Status last;
  double entered = -1, heading_at_entry = 0;
  bool degraded_while_following = true;
  L.run(c, 900, [&](const gc::Status& s) {
    if (s.mode == gc::Mode::Following) degraded_while_following = degraded_while_following && s.degraded;
    if (s.mode == gc::Mode::SafeMode && entered < 0) entered = L.t, heading_at_entry = L.ship.psi;
    last = s;
  });
  EXPECT_TRUE(degraded_while_following);
  EXPECT_NEAR(entered, 60.5, 0.6) << "kept plan 1 until it was plan_max_age old";
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
  EXPECT_TRUE(last.degraded);
  EXPECT_NE(last.detail.find("no path: goal unreachable"), std::string::npos) << last.detail;
  EXPECT_NE(last.detail.find("no valid plan"), std::string::npos) << last.detail;
  EXPECT_DOUBLE_EQ(last.desired_speed, L.params.safe_speed);
  EXPECT_NEAR(mpgc::geo::angle_diff(last.desired_heading, heading_at_entry), 0.0, deg2rad(0.6));
  EXPECT_NEAR(mpgc::geo::angle_diff(L.ship.psi, heading_at_entry), 0.0, deg2rad(1.0));
  EXPECT_NEAR(L.ship.u, L.params.safe_speed, 0.3);
  // The next valid plan ends safe mode and the degraded state.
  c.on_plan(plan(3, {{L.ship.x, L.ship.y}, {L.ship.x + 10000, L.ship.y + 10000}}), L.t);
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_FALSE(last.degraded);
  EXPECT_EQ(last.plan_id, 3u);
}

// The last valid plan's age counts from its stamp (when it was computed), not from its receipt.
TEST(GuidanceController, PlanAgeCountsFromItsStamp) {
  Loop L;
  L.params.plan_max_age = 60.0;
  gc::GuidanceController c(L.params);
  auto p1 = plan(1, {{0, 0}, {50000, 0}});
  p1.stamp = -40.0;  // computed 40 s before it arrived
  ASSERT_EQ(c.on_plan(p1, 0.0), "");
  double entered = -1;
  L.run(c, 40, [&](const gc::Status& s) {
    if (s.mode == gc::Mode::SafeMode && entered < 0) entered = L.t;
  });
  EXPECT_NEAR(entered, 20.5, 0.6);
}

// "No path" with nothing valid to follow: safe mode at once.
TEST(GuidanceController, NoPathWithoutAPlanEntersSafeModeAtOnce) {
  Loop L;
  gc::GuidanceController c(L.params);
  L.run(c, 5);
  const double psi0 = L.ship.psi;
  auto bad = plan(7, {}, gc::PlanKind::InvalidInput);
  bad.reason = "start inside land";
  ASSERT_EQ(c.on_plan(bad, L.t), "");
  gc::Status last;
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
  EXPECT_TRUE(last.degraded);
  EXPECT_NE(last.detail.find("invalid input: start inside land"), std::string::npos) << last.detail;
  EXPECT_NEAR(last.desired_heading, psi0, deg2rad(0.5));
}

// A refused plan keeps the good one but is reported (degraded) until the next valid plan.
TEST(GuidanceController, RejectedPlanIsReportedWhileTheGoodOneIsFollowed) {
  Loop L;
  gc::GuidanceController c(L.params);
  ASSERT_EQ(c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0), "");
  L.run(c, 5);
  EXPECT_NE(c.on_plan(plan(2, {{0, 0}, {kNaN, 0}}), L.t), "");
  gc::Status last;
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_EQ(last.plan_id, 1u);
  EXPECT_TRUE(last.degraded);
  EXPECT_NE(last.detail.find("plan 2 rejected"), std::string::npos) << last.detail;
  ASSERT_EQ(c.on_plan(plan(3, {{0, 0}, {50000, 0}}), L.t), "");
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_FALSE(last.degraded);
  EXPECT_EQ(last.detail, "following plan 3");
}

TEST(GuidanceController, StalePlanEntersSafeMode) {
  Loop L;
  L.params.plan_max_age = 30.0;
  gc::GuidanceController c(L.params);
  c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0);
  gc::Status last;
  double entered = -1;
  L.run(c, 60, [&](const gc::Status& s) {
    if (s.mode == gc::Mode::SafeMode && entered < 0) entered = L.t;
    last = s;
  });
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
  EXPECT_NE(last.detail.find("no valid plan"), std::string::npos) << last.detail;
  EXPECT_NEAR(entered, 30.5, 1.0);
  EXPECT_DOUBLE_EQ(last.desired_speed, L.params.safe_speed);
  // Also before any plan at all.
  Loop L2;
  L2.params.plan_max_age = 30.0;
  gc::GuidanceController c2(L2.params);
  L2.run(c2, 40, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
}

TEST(GuidanceController, NavigationLossAndBadNavigation) {
  Loop L;
  gc::GuidanceController c(L.params);
  auto cmd = c.step(0.0);
  EXPECT_EQ(cmd.status.mode, gc::Mode::SafeMode);
  EXPECT_TRUE(cmd.status.degraded);
  EXPECT_EQ(cmd.status.detail, "no own-ship state yet");
  EXPECT_EQ(cmd.rudder, 0.0);
  gc::NavInput n{0, 0, 0, 7, 0};
  n.heading = kNaN;
  EXPECT_NE(c.on_nav(n, 0.0).find("heading"), std::string::npos);
  n.heading = 0.0;
  n.x = std::numeric_limits<double>::infinity();
  EXPECT_NE(c.on_nav(n, 0.0).find("position"), std::string::npos);
  n.x = 0;
  EXPECT_EQ(c.on_nav(n, 0.0), "");
  EXPECT_EQ(c.step(0.5).status.mode, gc::Mode::Idle);
  cmd = c.step(10.0);  // own state now 10 s old
  EXPECT_EQ(cmd.status.mode, gc::Mode::SafeMode);
  EXPECT_NE(cmd.status.detail.find("no own-ship state for more than 5.0 s"), std::string::npos) << cmd.status.detail;
  EXPECT_EQ(cmd.rudder, 0.0);
}

// Own state lost while following a plan into a turn: rudder amidships at once, rpm reduced to the
// safe speed's (never raised), a detail that stays put during the outage; the next fresh state
// resumes the plan.
TEST(GuidanceController, OwnStateLostWhileTurningRudderAmidshipsThenResumes) {
  Loop L;
  L.params.plan_max_age = 1e4;  // the plan is not re-sent in this test
  gc::GuidanceController c(L.params);
  L.send(c, plan(1, {{0, 0}, {3000, 0}, {3000, 20000}}));
  gc::Command last{};
  const int n = static_cast<int>(500 / L.dt);
  for (int i = 0; i < n; ++i) {  // into the turn: rudder well off amidships
    ASSERT_EQ(c.on_nav(nav_of(L.ship), L.t), "");
    last = c.step(L.t);
    L.ship.step(L.dt, last.rudder, last.propeller_rpm);
    L.t += L.dt;
    if (std::abs(last.rudder) > deg2rad(5) && L.t > 60) break;
  }
  ASSERT_GT(std::abs(last.rudder), deg2rad(5)) << "the test wants the ship turning";
  const double rpm_before = last.propeller_rpm;
  const double t_lost = L.t;
  std::string detail;
  for (double t = t_lost; t < t_lost + 30.0; t += L.dt) {  // nav silent for 30 s
    const auto cmd = c.step(t);
    if (t - t_lost > L.params.nav_timeout + L.dt) {
      EXPECT_EQ(cmd.status.mode, gc::Mode::SafeMode);
      EXPECT_TRUE(cmd.status.degraded);
      EXPECT_EQ(cmd.rudder, 0.0);
      EXPECT_LE(cmd.propeller_rpm, rpm_before + 1e-9);
      EXPECT_LE(cmd.propeller_rpm, c.params().speed.max_rpm);
      if (detail.empty()) detail = cmd.status.detail;
      EXPECT_EQ(cmd.status.detail, detail) << "the detail must not change every cycle (log and health)";
    }
  }
  EXPECT_NE(detail.find("no own-ship state for more than"), std::string::npos) << detail;
  L.t = t_lost + 30.0;
  ASSERT_EQ(c.on_nav(nav_of(L.ship), L.t), "");
  const auto back = c.step(L.t);
  EXPECT_EQ(back.status.mode, gc::Mode::Following);
  EXPECT_FALSE(back.status.degraded);
  EXPECT_EQ(back.status.plan_id, 1u);
}

// A position jump (a GNSS glitch, a spoofed fix): refused while the last state is fresh, so the
// ship is steered by the last good state and, if the jump persists, goes to safe mode after
// nav_timeout; the new place is then taken once a second state agrees with it.
TEST(GuidanceController, OwnPositionJumpIsRefusedThenSafeModeThenTakenWhenConfirmed) {
  Loop L;
  L.params.plan_max_age = 1e4;
  gc::GuidanceController c(L.params);
  L.send(c, plan(1, {{0, 0}, {20000, 0}}));
  for (double t = 0; t < 20.0; t += 0.5) {
    ASSERT_EQ(c.on_nav({7.0 * t, 0, 0, 7, 0}, t), "") << t;
    ASSERT_EQ(c.step(t).status.mode, gc::Mode::Following);
  }
  // 2 km east in 0.5 s: refused; a 40 m wobble (margin 30 m + 25 m/s x 0.5 s) is not.
  EXPECT_NE(c.on_nav({140.0, 2000.0, 0, 7, 0}, 20.0).find("position jumped"), std::string::npos);
  EXPECT_EQ(c.on_nav({143.5, 40.0, 0, 7, 0}, 20.5), "");
  double t = 21.0;
  for (; t <= 20.5 + L.params.nav_timeout; t += 0.5)  // while the last good state is fresh
    EXPECT_NE(c.on_nav({7.0 * t, 2000.0, 0, 7, 0}, t).find("position jumped"), std::string::npos) << t;
  const auto cmd = c.step(t);
  EXPECT_EQ(cmd.status.mode, gc::Mode::SafeMode) << cmd.status.detail;
  EXPECT_EQ(cmd.rudder, 0.0);
  // The last good state is stale: two agreeing states at the new place are needed.
  EXPECT_NE(c.on_nav({7.0 * t, 2000.0, 0, 7, 0}, t).find("waiting for a second fix"), std::string::npos);
  EXPECT_EQ(c.on_nav({7.0 * (t + 0.5), 2000.0, 0, 7, 0}, t + 0.5), "");
  EXPECT_EQ(c.step(t + 0.5).status.mode, gc::Mode::Following);
}

// Late plans (seed 000 section 6): a plan computed for a later time is held and replaces the one
// followed only when the clock reaches its effective time.
TEST(GuidanceController, LatePlanTakesEffectAtItsEffectiveTime) {
  Loop L;
  gc::GuidanceController c(L.params);
  ASSERT_EQ(c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0), "");
  L.run(c, 10);
  auto p2 = plan(2, {{0, 0}, {20000, 20000}});
  p2.effective = L.t + 3.0;
  const double due = p2.effective;
  ASSERT_EQ(c.on_plan(p2, L.t), "");
  ASSERT_TRUE(c.held_plan());
  EXPECT_EQ(c.held_plan()->first, 2u);
  double switched = -1;
  L.run(c, 6, [&](const gc::Status& s) {
    if (s.plan_id == 2 && switched < 0) switched = L.t - L.dt;  // the time the step ran at
  });
  EXPECT_GE(switched, due);
  EXPECT_LT(switched, due + L.dt + 1e-9);
  EXPECT_FALSE(c.held_plan());

  // A newer held plan replaces an older held one; plan 3 is never followed.
  auto p3 = plan(3, {{0, 0}, {0, 20000}});
  p3.effective = L.t + 2.0;
  auto p4 = plan(4, {{0, 0}, {-20000, 20000}});
  p4.effective = L.t + 4.0;
  ASSERT_EQ(c.on_plan(p3, L.t), "");
  ASSERT_EQ(c.on_plan(p4, L.t), "");
  bool saw3 = false;
  gc::Status last;
  L.run(c, 6, [&](const gc::Status& s) { saw3 = saw3 || s.plan_id == 3, last = s; });
  EXPECT_FALSE(saw3);
  EXPECT_EQ(last.plan_id, 4u);

  // effective 0 or in the past: at once; and it drops an older held plan.
  auto p5 = plan(5, {{0, 0}, {20000, 0}});
  p5.effective = L.t + 2.0;
  ASSERT_EQ(c.on_plan(p5, L.t), "");
  auto p6 = plan(6, {{0, 0}, {20000, -20000}});
  p6.effective = L.t - 1.0;
  ASSERT_EQ(c.on_plan(p6, L.t), "");
  EXPECT_FALSE(c.held_plan());
  bool saw5 = false;
  L.run(c, 5, [&](const gc::Status& s) { saw5 = saw5 || s.plan_id == 5, last = s; });
  EXPECT_FALSE(saw5) << "plan 5 is older than plan 6 and must not replace it";
  EXPECT_EQ(last.plan_id, 6u);
  auto p7 = plan(7, {{0, 0}, {20000, 0}});
  p7.effective = 0.0;
  ASSERT_EQ(c.on_plan(p7, L.t), "");
  L.run(c, 0.5, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.plan_id, 7u);

  // Bad effective times are refused with the reason.
  auto bad = plan(8, {{0, 0}, {20000, 0}});
  bad.effective = kNaN;
  EXPECT_NE(c.on_plan(bad, L.t).find("effective"), std::string::npos);
  bad.effective = L.t + 10 * L.params.plan_max_age;
  EXPECT_NE(c.on_plan(bad, L.t).find("takes effect in"), std::string::npos);
  EXPECT_FALSE(c.held_plan());
}

// A held "no path" also waits for its time; the plan followed is kept until then.
TEST(GuidanceController, LateNoPathWaitsForItsEffectiveTime) {
  Loop L;
  gc::GuidanceController c(L.params);
  ASSERT_EQ(c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0), "");
  L.run(c, 5);
  auto np = plan(2, {}, gc::PlanKind::NoPath);
  np.effective = L.t + 2.0;
  ASSERT_EQ(c.on_plan(np, L.t), "");
  gc::Status last;
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_FALSE(last.degraded);
  L.run(c, 2, [&](const gc::Status& s) { last = s; });
  EXPECT_TRUE(last.degraded);
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_EQ(last.plan_id, 1u);
}

// A heading error beyond what the rudder can give: the order is clipped to the ship's limit and
// flagged, and it is never beyond the limit the ship's actuators obey (the same description).
TEST(GuidanceController, RudderOrderSaturatesAtTheShipsLimit) {
  Loop L;
  L.params.heading.max_rudder_rate = 1.0;  // reach the angle limit in one step
  gc::GuidanceController c(L.params);
  ASSERT_EQ(c.on_plan(plan(1, {{0, 0}, {0, -50000}}), 0.0), "");  // due west, the ship heads north
  gc::Command cmd;
  for (double t : {0.0, 0.5, 1.0}) {  // the rate limit (1 rad/s) reaches 35 deg in the second step
    ASSERT_EQ(c.on_nav(nav_of(L.ship), t), "");
    cmd = c.step(t);
  }
  EXPECT_TRUE(cmd.rudder_saturated);
  EXPECT_DOUBLE_EQ(cmd.rudder, -L.params.heading.max_rudder);
  const auto o = mpgc::ship::saturate(mpgc::ship::kvlcc2_actuator_limits(), cmd.rudder, cmd.propeller_rpm);
  EXPECT_FALSE(o.rudder_saturated) << "the ship would clip GC's hard-over order: the limits disagree";
  EXPECT_FALSE(o.rpm_saturated);
}

TEST(GuidanceController, ActuatorLimitsAreValidatedByTheOneDescription) {
  gc::GuidanceControlParams p;
  EXPECT_DOUBLE_EQ(p.heading.max_rudder, mpgc::ship::kvlcc2_actuator_limits().max_rudder);
  EXPECT_DOUBLE_EQ(p.speed.max_rpm, mpgc::ship::kvlcc2_actuator_limits().max_rpm);
  p.heading.max_rudder_rate = 2.0;  // the autopilot alone would take it; no steering gear turns 115 deg/s
  try {
    gc::GuidanceController c(p);
    FAIL() << "accepted a rudder rate of 2 rad/s";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("actuator limits.max_rudder_rate"), std::string::npos) << e.what();
  }
}

// Closed loop on the Nomoto plant: straight leg from a 500 m offset, then a 90 deg turn.
TEST(GuidanceController, NomotoFollowsStraightLegAndNinetyDegreeTurn) {
  Loop L;
  L.ship.y = 500;  // 500 m starboard of the first leg
  gc::GuidanceController c(L.params);
  L.send(c, plan(1, {{0, 0}, {8000, 0}, {8000, 12000}}));
  double max_e_leg1 = 0, max_e_leg2 = 0, max_overshoot_turn = 0;
  gc::Status last;
  L.run(c, 3000, [&](const gc::Status& s) {
    last = s;
    if (s.active_waypoint == 1 && L.ship.x > 4000) max_e_leg1 = std::max(max_e_leg1, std::abs(s.cross_track_error));
    if (s.active_waypoint == 2) {
      max_overshoot_turn = std::max(max_overshoot_turn, L.ship.x - 8000);
      if (L.ship.y > 4000 && L.ship.y < 12000 - 2.0 * 161)
        max_e_leg2 = std::max(max_e_leg2, std::abs(s.cross_track_error));
    }
  });
  std::printf("[figure] Nomoto (Mariner) LOS: leg 1 |xte| after 4 km %.1f m; after the 90 deg turn overshoot %.0f m, "
              "|xte| from 4 km %.1f m\n", max_e_leg1, max_overshoot_turn, max_e_leg2);
  EXPECT_LT(max_e_leg1, 10.0);
  EXPECT_LT(max_e_leg2, 10.0);
  EXPECT_EQ(last.mode, gc::Mode::Arrived);
}

// Cross current of 0.5 m/s: ILOS removes the offset that plain LOS leaves.
TEST(GuidanceController, IntegralLosRemovesCurrentOffset) {
  auto offset = [](bool integral) {
    Loop L;
    L.ship.current_e = 0.5;
    L.params.follower.integral = integral;
    gc::GuidanceController c(L.params);
    L.send(c, plan(1, {{0, 0}, {40000, 0}}));
    double e = 0;
    L.run(c, 4000, [&](const gc::Status& s) { e = s.cross_track_error; });
    return e;
  };
  const double e_los = offset(false), e_ilos = offset(true);
  std::printf("[figure] 0.5 m/s cross current: steady cross-track LOS %.1f m, ILOS %.1f m\n", e_los, e_ilos);
  EXPECT_GT(std::abs(e_los), 20.0);  // analytic: lookahead * V_c / U = 400 * 0.5 / 7 = 29 m
  EXPECT_LT(std::abs(e_ilos), 5.0);
}

// A new plan arrives mid-leg: the ship joins it from where it is, with no jump in the desired
// heading beyond the new geometry's, and ends at the new goal.
TEST(GuidanceController, SwitchesToNewPlanMidLeg) {
  Loop L;
  gc::GuidanceController c(L.params);
  L.send(c, plan(1, {{0, 0}, {30000, 0}}));
  gc::Status prev;
  L.run(c, 600, [&](const gc::Status& s) { prev = s; });
  ASSERT_EQ(prev.mode, gc::Mode::Following);
  // Same line ahead, then a turn: desired heading must not move at the switch.
  const double x0 = L.ship.x;
  L.send(c, plan(2, {{x0 - 300, 0}, {x0 + 3000, 0}, {x0 + 3000, 8000}}));
  gc::Status first;
  bool got = false;
  double max_e_after = 0;
  L.run(c, 2500, [&](const gc::Status& s) {
    if (!got) first = s, got = true;
    if (s.active_waypoint == 2 && L.ship.y > 3000 && L.ship.y < 7000)
      max_e_after = std::max(max_e_after, std::abs(s.cross_track_error));
  });
  const double jump = rad2deg(std::abs(mpgc::geo::angle_diff(first.desired_heading, prev.desired_heading)));
  std::printf("[figure] re-plan mid-leg on the same line: desired heading jump %.3f deg; |xte| on the new "
              "leg %.1f m\n", jump, max_e_after);
  EXPECT_EQ(first.plan_id, 2u);
  EXPECT_EQ(first.active_waypoint, 1u);
  EXPECT_LT(jump, 0.1);
  EXPECT_LT(max_e_after, 10.0);
  EXPECT_NEAR(L.ship.x, x0 + 3000, 30.0);
  EXPECT_GT(L.ship.y, 7000);
}
