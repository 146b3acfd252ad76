// The rule-following target helmsman (helmsman.hpp, behaviour: colreg): head-on to starboard
// (rule 14), crossing give-way to starboard and astern (rules 15, 16), stand-on keeps course and
// speed (17(a)(i)), acts alone to starboard when close (17(b), 17(c)), back to the route when
// passed and clear, and the world-file opt-in with its errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/ship_simulator/helmsman.hpp"
#include "mpgc/ship_simulator/targets.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/testing.hpp"

namespace sim = mpgc::ship_simulator;
namespace geo = mpgc::geo;
namespace colreg = mpgc::colreg;

namespace {

constexpr double kDt = 0.5;            // [s]
const double kSpeed = 10.0 * geo::kKnot;  // [m/s]

// A rule-following target at the origin heading north at 10 kn on one leg (its route).
sim::TargetConfig colreg_target(double route_course = 0.0) {
  sim::TargetConfig c;
  c.mmsi = 257000010;
  c.name = "rules";
  c.course0 = route_course;
  c.speed0 = kSpeed;
  c.legs = {{route_course, kSpeed, 0.0}};
  c.max_turn_rate = geo::deg2rad(1.0);
  c.max_accel = 0.05;
  c.waypoint_radius = 200.0;
  c.length = 100.0;
  c.beam = 20.0;
  c.behaviour = sim::TargetBehaviour::kColreg;
  return c;
}

// The other ship sails a straight line at constant velocity (it does nothing: the target's rules
// alone are tested).
struct Straight {
  double x, y, course, speed;
  colreg::ShipKinematics at(double t) const {
    return colreg::ShipKinematics::from_course(x + speed * t * std::cos(course), y + speed * t * std::sin(course), course,
                                               speed, course);
  }
};

struct Trace {
  double min_range = 1e18;
  double max_starboard = 0.0;  // [rad] largest course change to starboard of the route course
  double max_port = 0.0;       // [rad] largest to port
  double beta_at_cpa = 0.0;    // [rad] the other ship's relative bearing at the closest approach
  bool gave_way = false, stood_on = false, acted_alone = false;
};

Trace sail(sim::TargetShip& tg, const Straight& other, double t_end, double route_course = 0.0) {
  Trace tr;
  for (double t = 0.0; t < t_end; t += kDt) {
    const auto o = other.at(t);
    tg.step(t, kDt, {{0, o}});
    const auto& s = tg.state();
    const double d = geo::angle_diff(s.course, route_course);
    tr.max_starboard = std::max(tr.max_starboard, d);
    tr.max_port = std::max(tr.max_port, -d);
    const auto me = colreg::ShipKinematics::from_course(s.x, s.y, s.course, s.speed, s.course);
    const double r = std::hypot(o.x - s.x, o.y - s.y);
    if (r < tr.min_range) {
      tr.min_range = r;
      tr.beta_at_cpa = colreg::relative_bearing(me, o);
    }
    tr.gave_way |= tg.helm_mode() == sim::HelmMode::kGiveWay;
    tr.stood_on |= tg.helm_mode() == sim::HelmMode::kStandOn;
    tr.acted_alone |= tg.helm_mode() == sim::HelmMode::kActAlone;
  }
  return tr;
}

}  // namespace

// Rule 14: a ship dead ahead on the reciprocal course; the target alters to starboard by a readily
// apparent amount (rule 8(b)), never to port, and passes port to port at a safe distance.
TEST(Helmsman, HeadOnTurnsToStarboardAndPassesPortToPort) {
  sim::TargetShip tg(colreg_target());
  const Straight own{9000.0, 20.0, geo::kPi, kSpeed};
  const Trace tr = sail(tg, own, 1200.0);
  EXPECT_TRUE(tr.gave_way);
  EXPECT_GE(tr.max_starboard, geo::deg2rad(35.0) - 1e-9);
  EXPECT_LT(tr.max_port, geo::deg2rad(0.5));
  EXPECT_LT(tr.beta_at_cpa, 0.0) << "the other ship must pass on the target's port side";
  EXPECT_GT(tr.min_range, 0.9 * sim::HelmsmanParams{}.cpa_risk);
}

// Rules 15, 16: the other ship crosses from the target's starboard side on a collision course; the
// target turns to starboard early and passes astern of it (crosses its track after it has passed).
TEST(Helmsman, CrossingGiveWayTurnsStarboardAndPassesAstern) {
  sim::TargetShip tg(colreg_target());
  const Straight own{5000.0, 5000.0, geo::deg2rad(-90.0), kSpeed};  // westbound, meets at (5000, 0)
  Trace tr;
  double crossing_y = std::nan(""), own_y_then = std::nan("");  // where and when the target crosses x = 5000
  double prev_x = 0.0;
  for (double t = 0.0; t < 1800.0; t += kDt) {
    const auto o = own.at(t);
    tg.step(t, kDt, {{0, o}});
    const auto& s = tg.state();
    tr.max_starboard = std::max(tr.max_starboard, geo::angle_diff(s.course, 0.0));
    tr.max_port = std::max(tr.max_port, -geo::angle_diff(s.course, 0.0));
    tr.min_range = std::min(tr.min_range, std::hypot(o.x - s.x, o.y - s.y));
    tr.gave_way |= tg.helm_mode() == sim::HelmMode::kGiveWay;
    if (prev_x < 5000.0 && s.x >= 5000.0) {
      crossing_y = s.y;
      own_y_then = own.at(t + kDt).y;
    }
    prev_x = s.x;
  }
  EXPECT_TRUE(tr.gave_way);
  EXPECT_GE(tr.max_starboard, geo::deg2rad(35.0) - 1e-9);
  EXPECT_LT(tr.max_port, geo::deg2rad(0.5));
  ASSERT_TRUE(std::isfinite(crossing_y)) << "the target never crossed the other ship's track";
  EXPECT_LT(own_y_then, crossing_y) << "crossed ahead of the other ship (rule 15)";
  EXPECT_GT(tr.min_range, 0.9 * sim::HelmsmanParams{}.cpa_risk);
}

// Rule 17(a)(i): the other ship crosses from the target's port side. The target keeps its course and
// speed, also against its own route (a leg change while standing on is not taken), until the
// give-way ship is close (17(a)(ii)/(b) is off here).
TEST(Helmsman, CrossingStandOnHoldsCourseAndSpeed) {
  sim::TargetConfig c = colreg_target();
  c.legs = {{0.0, kSpeed, 300.0}, {geo::deg2rad(-40.0), kSpeed, 0.0}};  // route turns to port at 300 s
  c.helmsman.act_alone = false;
  sim::TargetShip tg(c);
  const Straight own{5000.0, -5000.0, geo::deg2rad(90.0), kSpeed};  // eastbound from the port side
  for (double t = 0.0; t < 900.0; t += kDt) {
    tg.step(t, kDt, {{0, own.at(t)}});
    ASSERT_EQ(tg.helm_mode(), sim::HelmMode::kStandOn) << "at t = " << t;
    ASSERT_EQ(tg.state().course, 0.0) << "at t = " << t;
    ASSERT_EQ(tg.state().speed, kSpeed) << "at t = " << t;
  }
}

// Rule 17(a)(ii), (b), (c): the give-way ship keeps coming; when it is close and still on a
// collision course, the stand-on target acts itself, to starboard (never to port for a ship on its
// port side).
TEST(Helmsman, StandOnActsAloneToStarboardWhenClose) {
  sim::TargetShip tg(colreg_target());
  const Straight own{5000.0, -5000.0, geo::deg2rad(90.0), kSpeed};
  const Trace tr = sail(tg, own, 1200.0);
  EXPECT_TRUE(tr.stood_on);
  EXPECT_TRUE(tr.acted_alone);
  EXPECT_GE(tr.max_starboard, geo::deg2rad(35.0) - 1e-9);
  EXPECT_LT(tr.max_port, geo::deg2rad(0.5));
  EXPECT_GT(tr.min_range, 300.0);  // collision averted (it was a dead-on collision course)
}

// After the head-on ship is abaft the beam and opening, the target returns to its route: its leg,
// or without legs or waypoints its start course.
TEST(Helmsman, ReturnsToRouteWhenPassedAndClear) {
  for (const bool legs : {true, false}) {
    sim::TargetConfig c = colreg_target();
    if (!legs) c.legs.clear();
    sim::TargetShip tg(c);
    const Straight own{9000.0, 20.0, geo::kPi, kSpeed};
    bool left_route = false, back = false;
    for (double t = 0.0; t < 2400.0; t += kDt) {
      tg.step(t, kDt, {{0, own.at(t)}});
      if (tg.helm_mode() == sim::HelmMode::kGiveWay) left_route = true;
      if (left_route && tg.helm_mode() == sim::HelmMode::kRoute) back = true;
    }
    EXPECT_TRUE(left_route) << "legs " << legs;
    EXPECT_TRUE(back) << "legs " << legs;
    EXPECT_NEAR(tg.state().course, 0.0, 1e-9) << "legs " << legs;  // steering the route's course again
    EXPECT_EQ(tg.helm_mode(), sim::HelmMode::kRoute);
  }
}

// No risk of collision (the other ship passes 3 NM off): the route is followed, nothing else.
TEST(Helmsman, NoRiskFollowsTheRoute) {
  sim::TargetShip tg(colreg_target());
  const Straight own{9000.0, 3.0 * geo::kNauticalMile, geo::kPi, kSpeed};
  const Trace tr = sail(tg, own, 1200.0);
  EXPECT_FALSE(tr.gave_way || tr.stood_on || tr.acted_alone);
  EXPECT_EQ(tr.max_starboard, 0.0);
}

// A route target ignores the other ships (the default behaviour stays what it was).
TEST(Helmsman, RouteTargetIgnoresOtherShips) {
  sim::TargetConfig c = colreg_target();
  c.behaviour = sim::TargetBehaviour::kRoute;
  sim::TargetShip with(c), without(c);
  const Straight own{9000.0, 20.0, geo::kPi, kSpeed};
  for (double t = 0.0; t < 900.0; t += kDt) {
    with.step(t, kDt, {{0, own.at(t)}});
    without.step(t, kDt);
  }
  EXPECT_EQ(with.state().x, without.state().x);
  EXPECT_EQ(with.state().y, without.state().y);
  EXPECT_EQ(with.state().course, 0.0);
}

TEST(Helmsman, BadParametersAreRejected) {
  auto bad = [](auto change, const std::string& needle) {
    sim::HelmsmanParams p;
    change(p);
    try {
      p.validate();
      ADD_FAILURE() << "accepted, expected an error naming " << needle;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  bad([](sim::HelmsmanParams& p) { p.alteration = geo::deg2rad(5.0); }, "alteration");
  bad([](sim::HelmsmanParams& p) { p.max_alteration = geo::deg2rad(20.0); }, "max_alteration");
  bad([](sim::HelmsmanParams& p) { p.d_colreg = std::nan(""); }, "d_colreg");
  bad([](sim::HelmsmanParams& p) { p.cpa_risk = 0.0; }, "cpa_risk");
  bad([](sim::HelmsmanParams& p) { p.cpa_risk = 2.0 * p.d_colreg; }, "cpa_risk");
  bad([](sim::HelmsmanParams& p) { p.tcpa_max = -1.0; }, "tcpa_max");
  bad([](sim::HelmsmanParams& p) { p.act_alone_cpa = 2.0 * p.cpa_risk; }, "act_alone_cpa");
  EXPECT_NO_THROW(sim::HelmsmanParams{}.validate());
  sim::TargetConfig c = colreg_target();
  c.helmsman.alteration_step = 0.0;
  EXPECT_THROW(sim::TargetShip{c}, std::invalid_argument);
  // Non-finite kinematics of the target itself are an error, of another ship skipped.
  sim::Helmsman h({});
  const auto me = colreg::ShipKinematics::from_course(0, 0, 0, kSpeed, 0);
  auto nan_ship = me;
  nan_ship.x = std::nan("");
  EXPECT_THROW(h.decide(nan_ship, 0.0, kSpeed, {}), std::invalid_argument);
  EXPECT_EQ(h.decide(me, 0.0, kSpeed, {{0, nan_ship}}).mode, sim::HelmMode::kRoute);
}

namespace {
std::string world(const std::string& target_extra) {
  return R"(
origin: {lat_deg: 58.76, lon_deg: 10.49}
own_ship: {model: nomoto, data_dir: ")" + mpgc::testing::shared_data("ship_models") + R"(", length_m: 122, beam_m: 20,
           heading_deg: 0, speed_kn: 10}
targets:
  - {mmsi: 257000001, name: head_on, x_m: 9000, y_m: 30, course_deg: 180, speed_kn: 10)" + target_extra + R"(}
)";
}
}  // namespace

TEST(Helmsman, WorldFileOptInAndErrors) {
  const auto c = sim::WorldConfig::from_yaml(world(", behaviour: colreg, helmsman: {alteration_deg: 40, d_colreg_m: 8000}"));
  ASSERT_EQ(c.targets.size(), 1u);
  EXPECT_EQ(c.targets[0].behaviour, sim::TargetBehaviour::kColreg);
  EXPECT_NEAR(c.targets[0].helmsman.alteration, geo::deg2rad(40.0), 1e-12);
  EXPECT_EQ(c.targets[0].helmsman.d_colreg, 8000.0);
  EXPECT_EQ(sim::WorldConfig::from_yaml(world("")).targets[0].behaviour, sim::TargetBehaviour::kRoute);
  auto expect_error = [](const std::string& yaml, const std::string& needle) {
    try {
      sim::WorldConfig::from_yaml(yaml, "w.yaml");
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error(world(", behaviour: zigzag"), "targets[0].behaviour");
  expect_error(world(", behaviour: zigzag"), "route or colreg");
  expect_error(world(", helmsman: {alteration_deg: 40}"), "targets[0].helmsman");
  expect_error(world(", behaviour: colreg, helmsman: {bogus: 1}"), "targets[0].helmsman.bogus");
  expect_error(world(", behaviour: colreg, helmsman: {alteration_deg: 5}"), "alteration");
  expect_error(world(", behaviour: colreg, helmsman: {act_alone: maybe}"), "targets[0].helmsman.act_alone");
}

// Wired through the world: the head-on target sees the own ship (which holds its course here) and
// turns to starboard; the same world with a route target does not.
TEST(Helmsman, WorldGivesTheTargetTheOwnShip) {
  for (const bool rules : {true, false}) {
    sim::World w(sim::WorldConfig::from_yaml(world(rules ? ", behaviour: colreg" : "")), 100'000'000);
    const sim::ShipCommand cmd = w.initial_command();
    for (int k = 0; k < 3000; ++k) w.step(cmd);  // 300 s
    const double course = w.target_truth()[0].cog;
    if (rules) {
      EXPECT_EQ(w.targets()[0].helm_mode(), sim::HelmMode::kGiveWay);
      EXPECT_GT(geo::angle_diff(course, geo::kPi), geo::deg2rad(30.0));  // to starboard of 180 deg
    } else {
      EXPECT_NEAR(geo::angle_diff(course, geo::kPi), 0.0, 1e-9);
    }
  }
}
