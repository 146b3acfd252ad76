// The supervisor: modes, plan validation with the last good plan kept, stale plan and "no path" ->
// safe mode, and closed-loop path following on the Nomoto plant (straight leg, 90 deg turn, ILOS
// against current, re-plan mid-leg).
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

TEST(GuidanceController, NoPathPlanEntersSafeModeHoldingCourseAndSlowing) {
  Loop L;
  gc::GuidanceController c(L.params);
  c.on_plan(plan(1, {{0, 0}, {50000, 0}}), 0.0);
  L.run(c, 20);
  const double heading_at_entry = L.ship.psi;
  auto np = plan(2, {}, gc::PlanKind::NoPath);
  np.reason = "goal unreachable";
  ASSERT_EQ(c.on_plan(np, L.t), "");
  gc::Status last;
  L.run(c, 900, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
  EXPECT_NE(last.detail.find("no path: goal unreachable"), std::string::npos) << last.detail;
  EXPECT_DOUBLE_EQ(last.desired_speed, L.params.safe_speed);
  EXPECT_NEAR(last.desired_heading, heading_at_entry, 1e-9);
  EXPECT_NEAR(L.ship.psi, heading_at_entry, deg2rad(0.5));
  EXPECT_NEAR(L.ship.u, L.params.safe_speed, 0.3);
  // The next valid plan ends safe mode.
  c.on_plan(plan(3, {{L.ship.x, L.ship.y}, {L.ship.x + 10000, L.ship.y + 10000}}), L.t);
  L.run(c, 1, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::Following);
  EXPECT_EQ(last.plan_id, 3u);
}

TEST(GuidanceController, StalePlanEntersSafeMode) {
  Loop L;
  L.params.plan_timeout = 30.0;
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
  L2.params.plan_timeout = 30.0;
  gc::GuidanceController c2(L2.params);
  L2.run(c2, 40, [&](const gc::Status& s) { last = s; });
  EXPECT_EQ(last.mode, gc::Mode::SafeMode);
}

TEST(GuidanceController, NavigationLossAndBadNavigation) {
  Loop L;
  gc::GuidanceController c(L.params);
  auto cmd = c.step(0.0);
  EXPECT_EQ(cmd.status.mode, gc::Mode::SafeMode);
  EXPECT_EQ(cmd.status.detail, "no navigation state");
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
  EXPECT_NE(cmd.status.detail.find("old"), std::string::npos);
  EXPECT_EQ(cmd.rudder, 0.0);
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
