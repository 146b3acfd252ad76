// Metrics of a recorded run on constructed cases with exact answers: distances (ships, polygons,
// circles), time below d_safety, goal arrival, path length, tracking RMSE, planning statistics,
// pass criteria, and rejection of bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "synthetic.hpp"

namespace sr = mpgc::scenario_runner;
using mpgc::geo::kPi;
using sr::synthetic::sail;

namespace {

// Own ship north along y = 0 at 10 m/s from x = -2000; a target at rest at (0, 500).
sr::RunRecord pass_by(double dt) {
  const auto t = sr::synthetic::times(400, dt);
  auto own = sail(0, 10, -2000, 0, 0, 10, {}, t);
  auto tgt = sail(7, 10, 0, 500, 0, 0, {}, t);
  auto r = sr::synthetic::run_of(t, own, {tgt}, 1000.0);
  r.goal = {2000, 0, 50};
  return r;
}

}  // namespace

TEST(Evaluation, PolygonDistanceIsExact) {
  const sr::Polygon sq{{{0, 0}, {0, 100}, {100, 100}, {100, 0}}};
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({50, 50}, sq), 0.0);     // inside
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({50, 130}, sq), 30.0);   // off an edge
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({-30, -40}, sq), 50.0);  // off a corner
  const sr::Polygon closed{{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {0, 0}}};  // closing vertex
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({-30, -40}, closed), 50.0);
  // Concave "U": the notch is outside.
  const sr::Polygon u{{{0, 0}, {100, 0}, {100, 30}, {20, 30}, {20, 70}, {100, 70}, {100, 100}, {0, 100}}};
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({60, 50}, u), 20.0);
  EXPECT_DOUBLE_EQ(sr::distance_to_polygon({10, 50}, u), 0.0);
  sr::FixedObstacles obs;
  obs.polygons.push_back(sq);
  obs.circles.push_back({{500, 0}, 50});
  EXPECT_DOUBLE_EQ(sr::distance_to_obstacles({500, 200}, obs), 150.0);
  EXPECT_DOUBLE_EQ(sr::distance_to_obstacles({200, 50}, obs), 100.0);
  EXPECT_TRUE(std::isinf(sr::distance_to_obstacles({0, 0}, sr::FixedObstacles{})));
  EXPECT_THROW(sr::distance_to_polygon({0, 0}, sr::Polygon{{{0, 0}, {1, 1}}}), std::invalid_argument);
}

// obstacle_manager's point set mixes densified polygon boundaries with point features: only the
// points off every polygon (outside, farther than the tolerance from its edges) become obstacles.
TEST(Evaluation, PointFeaturesAreKeptBoundaryPointsDropped) {
  sr::FixedObstacles obs;
  obs.polygons.push_back({{{0, 0}, {0, 100}, {100, 100}, {100, 0}}});
  const std::vector<mpgc::geom::Vec2> points{{0, 0},     {0, 20},  {50, 100.2},  // on the boundary (within 0.5 m)
                                       {50, 50},                          // inside
                                       {300, 300}, {50, 101}};            // point features
  EXPECT_EQ(sr::add_point_obstacles(obs, points, 0.5), 2u);
  ASSERT_EQ(obs.circles.size(), 2u);
  EXPECT_DOUBLE_EQ(obs.circles[0].centre.x, 300.0);
  EXPECT_DOUBLE_EQ(obs.circles[1].centre.y, 101.0);
  EXPECT_DOUBLE_EQ(obs.circles[1].radius, 0.0);
  EXPECT_DOUBLE_EQ(sr::distance_to_obstacles({300, 340}, obs), 40.0);
  sr::FixedObstacles none;  // no polygons: every point is a feature
  EXPECT_EQ(sr::add_point_obstacles(none, points, 0.5), points.size());
  EXPECT_THROW(sr::add_point_obstacles(none, {{std::nan(""), 0}}, 0.5), std::invalid_argument);
}

TEST(Evaluation, MinDistanceAndSafetyViolationAreExact) {
  // dt = 7 s: no sample at the closest approach, which is found between samples anyway.
  for (double dt : {1.0, 7.0}) {
    SCOPED_TRACE(dt);
    const auto r = pass_by(dt);
    const auto m = sr::evaluate(r, {}, {});
    ASSERT_EQ(m.min_distance_targets.size(), 1u);
    EXPECT_EQ(m.min_distance_targets[0].target_id, 7u);
    EXPECT_NEAR(m.min_distance_targets[0].min_distance, 500.0, 1e-9);
    EXPECT_NEAR(m.min_distance_targets[0].t_min, 200.0, 1e-9);
    EXPECT_NEAR(m.min_distance, 500.0, 1e-9);
    EXPECT_TRUE(std::isnan(m.min_distance_fixed));
    // Below 1000 m while |x| < sqrt(1000^2 - 500^2) = 866.03 m: 173.205 s at 10 m/s. The
    // distance is interpolated linearly between samples (error O(dt^2)).
    EXPECT_NEAR(m.safety_violation_s, 2.0 * std::sqrt(1000.0 * 1000.0 - 500.0 * 500.0) / 10.0, dt < 2 ? 1e-2 : 0.3);
    EXPECT_DOUBLE_EQ(m.safety_distance, 1000.0);
    EXPECT_FALSE(m.passed);  // 500 m < d_safety
    ASSERT_EQ(m.failures.size(), 2u);  // min distance and time below d_safety (goal reached)
  }
}

// Near misses and likely collisions (r_nm 50 m, r_col_cpa 30 m unscaled): a target stopped 40 m
// off the own track, one 20 m off and one 1200 m off. The least distances fall between samples
// (dt = 7 s), and a likely collision is a near miss too.
TEST(Evaluation, NearMissesAndLikelyCollisionsPerTarget) {
  const auto t = sr::synthetic::times(400, 7.0);
  auto own = sail(0, 10, -2000, 0, 0, 10, {}, t);
  auto near = sail(1, 10, 0, 40, 0, 0, {}, t);
  auto hit = sail(2, 10, 500, -20, 0, 0, {}, t);
  auto far = sail(3, 10, -500, 1200, 0, 0, {}, t);
  auto r = sr::synthetic::run_of(t, own, {near, hit, far}, 100.0);
  sr::PassCriteria c;
  c.goal_required = false;
  c.max_safety_violation_s = 1e6;
  const auto m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.min_distance_targets.size(), 3u);
  EXPECT_NEAR(m.min_distance_targets[0].min_distance, 40.0, 1e-9);
  EXPECT_TRUE(m.min_distance_targets[0].near_miss);
  EXPECT_FALSE(m.min_distance_targets[0].likely_collision);
  EXPECT_NEAR(m.min_distance_targets[1].min_distance, 20.0, 1e-9);
  EXPECT_TRUE(m.min_distance_targets[1].near_miss);
  EXPECT_TRUE(m.min_distance_targets[1].likely_collision);
  EXPECT_FALSE(m.min_distance_targets[2].near_miss);
  EXPECT_FALSE(m.min_distance_targets[2].likely_collision);
  EXPECT_EQ(m.near_miss_targets(), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_EQ(m.likely_collision_targets(), (std::vector<std::uint32_t>{2}));
  EXPECT_DOUBLE_EQ(m.r_nm, 50.0);
  EXPECT_DOUBLE_EQ(m.r_col_cpa, 30.0);
  // d_safety 100 m must be kept: the run fails on the distance, and the likely collision with
  // target 2 is named; the near miss of target 1 is not a failure of its own.
  EXPECT_FALSE(m.passed);
  ASSERT_EQ(m.failures.size(), 2u);
  EXPECT_NE(m.failures[0].find("min distance 20.0 m < 100.0 m"), std::string::npos) << m.failures[0];
  EXPECT_EQ(m.failures[1], "target 2: likely collision (least distance 20.0 m < r_col_cpa 30.0 m)");
  // Scaled to a 320 m ship (r_nm 1600 m, r_col_cpa 960 m) every target is a near miss, targets 1
  // and 2 likely collisions.
  const auto big = sr::evaluate(r, sr::EvaluationParams::scaled_to(320.0), c);
  EXPECT_EQ(big.near_miss_targets(), (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(big.likely_collision_targets(), (std::vector<std::uint32_t>{1, 2}));
  EXPECT_DOUBLE_EQ(big.r_nm, 1600.0);
}

// A likely collision fails the run only where the safety criterion already asks for that
// distance: with d_safety 10 m a pass at 20 m is reported (below r_col_cpa 30 m), not failed.
TEST(Evaluation, LikelyCollisionFailsOnlyWhereDSafetyAsksForIt) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto own = sail(0, 10, -2000, 0, 0, 10, {}, t);
  auto hit = sail(2, 10, 0, -20, 0, 0, {}, t);
  auto r = sr::synthetic::run_of(t, own, {hit}, 10.0);
  sr::PassCriteria c;
  c.goal_required = false;
  auto m = sr::evaluate(r, {}, c);
  EXPECT_EQ(m.likely_collision_targets(), (std::vector<std::uint32_t>{2}));
  EXPECT_TRUE(m.passed) << (m.failures.empty() ? "" : m.failures[0]);
  // d_safety 25 m with 10 % tolerance (limit 22.5 m): 20 m fails on both counts.
  r.safety_distance = 25.0;
  c.safety_tolerance = 0.1;
  c.max_safety_violation_s = 1e6;
  m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.failures.size(), 2u);
  EXPECT_NE(m.failures[1].find("target 2: likely collision"), std::string::npos) << m.failures[1];
  // A likely collision beyond the near-miss range is a contradiction: rejected.
  sr::EvaluationParams p;
  p.r_col_cpa = 60.0;
  EXPECT_THROW(sr::evaluate(r, p, c), std::invalid_argument);
  p.r_col_cpa = 50.0;  // equal is allowed
  EXPECT_NO_THROW(sr::evaluate(r, p, c));
}

TEST(Evaluation, FixedObstacleDistanceBetweenSamples) {
  auto r = pass_by(7.0);
  r.targets.clear();
  // A square 800 m east of the track, and a circle; the closest point (x = 0) is between samples.
  r.obstacles.polygons.push_back({{{-100, 800}, {100, 800}, {100, 1000}, {-100, 1000}}});
  r.obstacles.circles.push_back({{3000, -2000}, 100});
  const auto m = sr::evaluate(r, {}, {});
  EXPECT_NEAR(m.min_distance_fixed, 800.0, 1e-9);
  EXPECT_NEAR(m.min_distance, 800.0, 1e-9);
  // Below 1000 m while hypot(|x| - 100, 800) < 1000, i.e. |x| < 700 m: 140 s at 10 m/s.
  EXPECT_NEAR(m.safety_violation_s, 140.0, 0.5);
  const auto ds = sr::distance_series(r);
  ASSERT_EQ(ds.fixed.size(), r.t.size());
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double x = r.own.states[i].x;
    const double expect = std::fabs(x) <= 100 ? 800.0 : std::hypot(std::fabs(x) - 100.0, 800.0);
    EXPECT_NEAR(ds.fixed[i], std::min(expect, std::hypot(x - 3000, 2000) - 100), 1e-9);
  }
}

TEST(Evaluation, GoalArrivalAndPathLength) {
  const auto t = sr::synthetic::times(200, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 10, {}, t);
  auto r = sr::synthetic::run_of(t, own, {});
  r.goal = {1000.5, 0, 100};  // entered at x = 900.5, between samples
  const auto m = sr::evaluate(r, {}, {});
  EXPECT_TRUE(m.goal_reached);
  EXPECT_NEAR(m.t_goal, 90.05, 1e-9);
  EXPECT_NEAR(m.path_length, 910.0, 1e-9);  // up to the first sample inside the circle
  EXPECT_NEAR(m.straight_line, 1000.5, 1e-12);
  EXPECT_DOUBLE_EQ(m.sim_s, 200.0);
  EXPECT_TRUE(std::isnan(m.min_distance));  // nothing to be near
  EXPECT_TRUE(m.passed);
  r.goal = {0, 5000, 100};
  const auto miss = sr::evaluate(r, {}, {});
  EXPECT_FALSE(miss.goal_reached);
  EXPECT_FALSE(miss.passed);
  ASSERT_EQ(miss.failures.size(), 1u);
  EXPECT_NE(miss.failures[0].find("goal not reached"), std::string::npos);
  sr::PassCriteria no_goal;
  no_goal.goal_required = false;
  EXPECT_TRUE(sr::evaluate(r, {}, no_goal).passed);
}

TEST(Evaluation, TrackingRmseAgainstTheActivePath) {
  // 101 samples along x at y = 30 for t < 50 and y = -40 from t = 50.
  const auto t = sr::synthetic::times(100, 1.0);
  sr::ShipTrack own;
  own.length = 320;
  for (double ti : t) own.states.push_back({10.0 * ti, ti < 50 ? 30.0 : -40.0, 0, 0, 10});
  auto r = sr::synthetic::run_of(t, own, {});
  sr::PlanRecord p0;
  p0.t = 0;
  p0.plan_id = 1;
  p0.waypoints = {{0, 0, 0}, {5000, 0, 500}};
  p0.planning_time = 0.4;
  r.plans = {p0};
  auto m = sr::evaluate(r, {}, {});
  EXPECT_NEAR(m.tracking_rmse, std::sqrt((50 * 30.0 * 30.0 + 51 * 40.0 * 40.0) / 101.0), 1e-9);
  // A relaxed plan along y = -40 from t = 50 s: the second half tracks it exactly. A no-path
  // plan does not replace the active one.
  sr::PlanRecord p1 = p0, p2 = p0;
  p1.t = 50, p1.plan_id = 2, p1.status = sr::PlanStatus::kRelaxed, p1.planning_time = 0.6;
  p1.waypoints = {{0, -40, 0}, {2000, -40, 200}};
  p2.t = 60, p2.plan_id = 3, p2.status = sr::PlanStatus::kNoPath, p2.planning_time = 2.0;
  p2.waypoints.clear();
  r.plans = {p0, p1, p2};
  m = sr::evaluate(r, {}, {});
  EXPECT_NEAR(m.tracking_rmse, std::sqrt(50 * 30.0 * 30.0 / 101.0), 1e-9);
  EXPECT_EQ(m.replans, 3);
  EXPECT_EQ(m.relaxed_plans, 1);
  EXPECT_EQ(m.no_path_plans, 1);
  EXPECT_NEAR(m.planning.median_ms, 600.0, 1e-9);
  EXPECT_NEAR(m.planning.p95_ms, 600.0 + 0.9 * 1400.0, 1e-9);
  EXPECT_NEAR(m.planning.max_ms, 2000.0, 1e-9);
  const auto active = sr::active_plan_index(r);
  EXPECT_EQ(active[0], 0);
  EXPECT_EQ(active[49], 0);
  EXPECT_EQ(active[50], 1);
  EXPECT_EQ(active[100], 1);
  EXPECT_TRUE(std::isnan(sr::evaluate(sr::synthetic::run_of(t, own, {}), {}, {}).tracking_rmse));
}

TEST(Evaluation, PassCriteriaToleranceAndViolationTime) {
  const auto r = pass_by(1.0);
  sr::PassCriteria c;
  c.goal_required = false;
  c.safety_tolerance = 0.5;          // 500 m >= 1000 * (1 - 0.5)
  c.max_safety_violation_s = 180.0;  // 173 s
  auto m = sr::evaluate(r, {}, c);
  EXPECT_TRUE(m.passed) << (m.failures.empty() ? "" : m.failures[0]);
  c.max_safety_violation_s = 170.0;
  m = sr::evaluate(r, {}, c);
  EXPECT_FALSE(m.passed);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("below d_safety"), std::string::npos);
  c.required.push_back({42, mpgc::colreg::EncounterType::kHeadOn, true, true});
  EXPECT_THROW(sr::evaluate(r, {}, c), std::invalid_argument);  // no target 42
}

TEST(Evaluation, MinShipDistanceIsAPlannersClaimWithoutTolerance) {
  const auto r = pass_by(1.0);  // target 7 passed at 500 m
  sr::PassCriteria c;
  c.goal_required = false;
  c.safety_tolerance = 0.5;
  c.max_safety_violation_s = 1e6;
  c.min_ship_distance = 500.0;
  auto m = sr::evaluate(r, {}, c);
  EXPECT_TRUE(m.passed) << (m.failures.empty() ? "" : m.failures[0]);
  c.min_ship_distance = 501.0;
  m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("target 7: least distance 500.0 m < the required 501.0 m"), std::string::npos)
      << m.failures[0];
  c.min_ship_distance = std::nan("");
  EXPECT_THROW(sr::evaluate(r, {}, c), std::invalid_argument);
}

TEST(Evaluation, RequiredEncounterVerdicts) {
  // Head-on turning to port (see test_colreg_verdicts): required compliant -> fails with reasons.
  const auto t = sr::synthetic::times(400, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{120, -0.6, 7}}, t);
  auto tgt = sail(3, 10, 4000, 0, kPi, 7, {}, t);
  auto r = sr::synthetic::run_of(t, own, {tgt}, 50.0);
  sr::PassCriteria c;
  c.goal_required = false;
  c.required.push_back({3, mpgc::colreg::EncounterType::kHeadOn, true, false});
  EXPECT_TRUE(sr::evaluate(r, {}, c).passed);  // situation right, compliance not required
  c.required[0].compliant = true;
  auto m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("did not turn to starboard"), std::string::npos) << m.failures[0];
  EXPECT_NE(m.failures[0].find("did not pass port to port"), std::string::npos) << m.failures[0];
  c.required[0] = {3, mpgc::colreg::EncounterType::kCrossingGiveWay, true, false};
  m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("expected crossing-give-way"), std::string::npos) << m.failures[0];
  c.required.clear();
  c.all_encounters_compliant = true;
  EXPECT_FALSE(sr::evaluate(r, {}, c).passed);
}

// compliant: false is checked (a run without COLREG must be shown to break a rule, seed 000 Figs. 8
// and 12), and a required verdict that cannot be judged fails with the reason either way.
TEST(Evaluation, RequiredViolationAndUnjudgedVerdictsFail) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto tgt = sail(3, 10, 4000, 0, kPi, 7, {}, t);
  sr::PassCriteria c;
  c.goal_required = false;
  c.required.push_back({3, mpgc::colreg::EncounterType::kHeadOn, true, false});
  // Port turn: a violation, as required.
  auto port = sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{120, -0.6, 7}}, t), {tgt}, 50.0);
  auto m = sr::evaluate(port, {}, c);
  EXPECT_TRUE(m.passed) << (m.failures.empty() ? "" : m.failures[0]);
  // A readily apparent starboard turn: compliant, so the requirement of a violation fails.
  auto stbd = sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{120, 0.7, 7}}, t), {tgt}, 50.0);
  m = sr::evaluate(stbd, {}, c);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("a COLREG violation is required"), std::string::npos) << m.failures[0];
  c.required[0].compliant = true;
  EXPECT_TRUE(sr::evaluate(stbd, {}, c).passed);
  // A target that never comes within r_colregs_2_max: nothing to judge, so neither passes.
  auto far = sail(3, 10, 4000, 3000, kPi, 7, {}, t);
  auto r = sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {}, t), {far}, 50.0);
  c.required[0].check_situation = false;
  for (bool compliant : {true, false}) {
    c.required[0].compliant = compliant;
    m = sr::evaluate(r, {}, c);
    ASSERT_EQ(m.failures.size(), 1u);
    EXPECT_NE(m.failures[0].find("not judged: never within r_colregs_2_max"), std::string::npos) << m.failures[0];
  }
  // A stand-on target first met inside stage 3: no course and speed to hold; the ship may act, so
  // it is judged as one that acts: a safe distance (8(d)) and 17(c). Here it held on to a CPA of
  // 57 m < r_min_cpa.
  auto close = sail(3, 10, 300, -220, kPi / 2, 7, {}, t);  // range 372 m < 400 m, predicted CPA 57 m
  r = sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {}, t), {close}, 50.0);
  c.required[0].compliant = true;
  m = sr::evaluate(r, {}, c);
  ASSERT_EQ(m.encounters[0].situation, mpgc::colreg::EncounterType::kCrossingStandOn);
  EXPECT_EQ(m.encounters[0].held_course_and_speed, sr::Verdict::kNotApplicable);
  EXPECT_EQ(m.encounters[0].kept_clear, sr::Verdict::kFail);
  ASSERT_EQ(m.failures.size(), 1u);
  EXPECT_NE(m.failures[0].find("did not keep clear"), std::string::npos) << m.failures[0];
}

TEST(Evaluation, BadInputIsRejectedWithTheFieldNamed) {
  auto expect_error = [](const sr::RunRecord& r, const std::string& field) {
    try {
      sr::evaluate(r, {}, {});
      ADD_FAILURE() << "no error for " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  };
  const auto good = pass_by(1.0);
  auto r = good;
  r.t.clear();
  expect_error(r, "t is empty");
  r = good;
  r.t[5] = r.t[4];
  expect_error(r, "t[5]");
  r = good;
  r.own.states[3].x = std::nan("");
  expect_error(r, "own.states[3]");
  r = good;
  r.targets[0].states.pop_back();
  expect_error(r, "targets[0] (id 7).states");
  r = good;
  r.targets.push_back(r.targets[0]);
  expect_error(r, "duplicate target id");
  r = good;
  r.own.length = 0;
  expect_error(r, "own.length");
  r = good;
  r.safety_distance = std::numeric_limits<double>::infinity();
  expect_error(r, "safety_distance");
  r = good;
  r.goal.radius = 0;
  expect_error(r, "goal.radius");
  r = good;
  r.obstacles.polygons.push_back({{{0, 0}, {1, 1}}});
  expect_error(r, "obstacles.polygons[0]");
  r = good;
  r.plans.push_back({0, 1, sr::PlanStatus::kOk, {}, 0.1});
  expect_error(r, "plans[0] (plan_id 1) has no waypoints");
  r = good;
  r.plans.push_back({0, 1, sr::PlanStatus::kOk, {{0, 0, 0}}, -1});
  expect_error(r, "planning_time");
  sr::EvaluationParams p;
  p.r_min_cpa = -1;
  EXPECT_THROW(sr::evaluate(good, p, {}), std::invalid_argument);
  sr::PassCriteria c;
  c.safety_tolerance = 1.5;
  EXPECT_THROW(sr::evaluate(good, {}, c), std::invalid_argument);
}

TEST(Evaluation, GridIndexAgreesWithBruteForceOnManyPolygons) {
  // 40 random star-shaped polygons of 30 vertices and a random walk that crosses some of them.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  sr::FixedObstacles obs;
  for (int k = 0; k < 40; ++k) {
    const double cx = 20000 * U(rng), cy = 20000 * U(rng);
    sr::Polygon p;
    for (int i = 0; i < 30; ++i) {
      const double a = 2 * kPi * i / 30, r = 300 + 900 * U(rng);
      p.vertices.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
    }
    obs.polygons.push_back(p);
  }
  obs.circles.push_back({{10000, 10000}, 250});
  const auto t = sr::synthetic::times(3000, 2.0);
  sr::ShipTrack own;
  own.length = 100;
  double x = 10000, y = 10000, h = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    h += 0.2 * (U(rng) - 0.5);
    x += 16 * std::cos(h), y += 16 * std::sin(h);
    own.states.push_back({x, y, h, h, 8});
  }
  auto r = sr::synthetic::run_of(t, own, {});
  r.obstacles = obs;
  const auto ds = sr::distance_series(r);
  double brute_min = 1e300;
  int inside = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const mpgc::geom::Vec2 p{own.states[i].x, own.states[i].y};
    double d = std::max(0.0, std::hypot(p.x - 10000, p.y - 10000) - 250);
    for (const auto& poly : obs.polygons) d = std::min(d, sr::distance_to_polygon(p, poly));
    ASSERT_NEAR(ds.fixed[i], d, 1e-9) << "sample " << i;
    EXPECT_NEAR(sr::distance_to_obstacles(p, obs), d, 1e-9);
    brute_min = std::min(brute_min, d);
    inside += d == 0.0;
  }
  const auto m = sr::evaluate(r, {}, {});
  EXPECT_LE(m.min_distance_fixed, brute_min);
  EXPECT_GE(m.min_distance_fixed, brute_min - 16.0);  // within one step of the sampled minimum
  RecordProperty("samples_inside", inside);
}
