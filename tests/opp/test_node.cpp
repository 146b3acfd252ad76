// The planning component's logic without DDS (node.hpp) and the planning interface (registry,
// Planner::solve): what main.cpp used to do inline, tested here directly.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mpgc/opp/node.hpp"
#include "mpgc/opp/registry.hpp"
#include "mpgc/opp/rrtstar.hpp"
#include "mpgc/opp/scenarios.hpp"
#include "mpgc/opp/validity.hpp"
#include "mpgc/runtime/params.hpp"
#include "mpgc/testing_params.hpp"

namespace opp = mpgc::opp;

namespace {

// The planners' own parameters (plan.step, ...) are declared too, into planners it drops.
opp::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  std::vector<std::unique_ptr<opp::Planner>> planners;
  return mpgc::testing::declared<opp::NodeParams>(
      [&](mpgc::rt::ParamSet& ps, opp::NodeParams& p) { opp::declare(ps, p, planners); }, overrides);
}

TEST(OppNode, TargetsAreExtrapolatedOverTheirAge) {
  const auto t = opp::targets_at({{7, {100, 200}, {2, -1}, 30.0}, {9, {0, 0}, {0, 0}, std::nan("")}}, 10.0, 2.0);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].id, 7u);
  EXPECT_DOUBLE_EQ(t[0].p.x, 120);
  EXPECT_DOUBLE_EQ(t[0].p.y, 190);
  EXPECT_DOUBLE_EQ(t[0].v.x, 2);
  EXPECT_EQ(t[0].pinned.obligation, opp::Obligation::kNone);
  EXPECT_DOUBLE_EQ(t[0].margin, 60.0);  // 2 sigma
  EXPECT_DOUBLE_EQ(t[1].margin, 0.0);   // a NaN sigma adds nothing rather than poisoning the check
}

// A target whose track went unmeasured (its sigma grown by the obstacle manager) is passed wider:
// a path that keeps d_safety from it but not d_safety + 2 sigma is invalid, and the planner's path
// keeps the wider clearance.
TEST(OppNode, AGrownUncertaintyWidensTheClearanceOfThatTarget) {
  opp::Problem pb;
  pb.start = {0, 0};
  pb.heading = 0;
  pb.speed = 5;
  pb.goal.p = {8000, 0};
  pb.bounds = {-3000, -4000, 11000, 4000};
  // Stationary, 1050 m abeam of the straight line.
  pb.targets = {{1, {4000, 1050}, {0, 0}, {}, 0.0}};
  opp::ConstraintParams c;
  const std::vector<opp::Vec2> straight = {{0, 0}, {8000, 0}};
  EXPECT_EQ(opp::ValidityChecker(pb, c).check_path(straight, false), "");
  pb.targets[0].margin = 2 * 40.0;  // sigma 40 m after a silence
  EXPECT_NE(opp::ValidityChecker(pb, c).check_path(straight, false).find("target"), std::string::npos);
  opp::Params prm;
  prm.max_iterations = 3000;
  const opp::Result r = opp::plan(pb, prm);
  ASSERT_FALSE(r.path.empty()) << r.reason;
  std::vector<opp::Vec2> pts;
  for (const auto& w : r.path) pts.push_back(w.p);
  EXPECT_EQ(opp::ValidityChecker(pb, c).check_path(pts, false), "");
  double dmin = 1e18;
  for (size_t i = 0; i + 1 < pts.size(); ++i)
    dmin = std::min(dmin, mpgc::geom::point_segment_distance(pb.targets[0].p, pts[i], pts[i + 1]));
  EXPECT_GE(dmin, 1080.0 - 1e-6);
}

// A fuzz finding: a search box 1e16 m wide ground one plan for minutes. The problem is bounded.
TEST(OppNode, AProblemTooWideToSearchIsRefused) {
  opp::Problem pb;
  pb.speed = 5;
  pb.goal.p = {0, 2.6e6};
  pb.bounds = {-3000, -3000, 3000, 2.603e6};
  const opp::Result r = opp::plan(pb, opp::Params{});
  EXPECT_EQ(r.status, opp::Status::kInvalidInput);
  EXPECT_NE(r.reason.find("wider than 2500 km"), std::string::npos) << r.reason;
  pb.goal.p = {0, 2.4e6};
  pb.bounds.max_y = 2.403e6;
  EXPECT_EQ(opp::check_problem(pb, opp::ConstraintParams{}), "");
}

// Beyond the region obstacles/fixed was published for, the water is unknown: no leg comes within
// d_safety of the region's edge, a goal it does not cover makes the node wait, and no chart at all
// makes it wait unless plan.require_chart is off.
TEST(OppNode, WaterBeyondTheChartedRegionIsUnknown) {
  const opp::NodeParams p = declared();
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};
  const opp::GoalSpec goal{{8000, 0}, std::nan(""), 0, 5, 1000, true};
  opp::NoFixedObstacles water;
  // The region ends 1500 m north of the straight line's end... and the goal is 800 m from its edge.
  const opp::Setup near_edge = opp::build_setup(p, own, goal, {}, {&water, opp::Bounds{-5000, -5000, 8800, 5000}}, 0);
  EXPECT_NE(opp::chart_wait(p, near_edge, true).find("goal outside the charted region"), std::string::npos);
  EXPECT_NE(opp::check_problem(near_edge.problem, near_edge.constraints).find("charted region"), std::string::npos);
  EXPECT_EQ(opp::chart_wait(p, near_edge, false), "no chart yet (obstacles/fixed)");
  EXPECT_EQ(opp::chart_wait(declared({"plan.require_chart=false"}), near_edge, false), "");

  // A region with room for the goal: the sampling box is cut to it, and the path keeps d_safety
  // from its southern edge (at y = -600 the straight line is fine, a detour south is not).
  const opp::Setup s = opp::build_setup(p, own, goal, {}, {&water, opp::Bounds{-5000, -1100, 12000, 5000}}, 0);
  EXPECT_EQ(opp::chart_wait(p, s, true), "");
  EXPECT_DOUBLE_EQ(s.problem.bounds.min_y, -1100);
  const opp::ValidityChecker v(s.problem, s.constraints);
  EXPECT_EQ(v.check_path({{0, 0}, {8000, 0}}, false), "");
  EXPECT_NE(v.check_path({{0, 0}, {4000, -500}, {8000, 0}}, false).find("unknown water"), std::string::npos);
  EXPECT_DOUBLE_EQ(v.fixed_clearance({4000, -600}), 500);
  // A chart published whole (infinite region) is complete everywhere.
  const double inf = std::numeric_limits<double>::infinity();
  const opp::Setup whole = opp::build_setup(p, own, goal, {}, {&water, opp::Bounds{-inf, -inf, inf, inf}}, 0);
  EXPECT_EQ(opp::chart_wait(p, whole, true), "");
  EXPECT_EQ(opp::check_problem(whole.problem, whole.constraints), "");
  EXPECT_DOUBLE_EQ(whole.problem.bounds.min_y, -3000);
}

TEST(OppNode, SetupDeadReckonsTheOwnShipAndTakesTheGoalsSpeedAndSafetyDistance) {
  opp::NodeParams p = declared();
  const opp::OwnReport own{{1000, 2000}, 0.1, 4.0, 0.0, 5.0};  // 4 m/s due north, 5 s old
  opp::GoalSpec goal{{9000, 2000}, std::nan(""), 0.3, 6.0, 1500.0, true};
  const opp::Setup s = opp::build_setup(p, own, goal, {}, {}, 3);
  EXPECT_DOUBLE_EQ(s.problem.start.x, 1020);
  EXPECT_DOUBLE_EQ(s.problem.start.y, 2000);
  EXPECT_DOUBLE_EQ(s.problem.heading, 0.1);
  EXPECT_DOUBLE_EQ(s.problem.speed, 6.0);                        // the goal's cruise speed
  EXPECT_DOUBLE_EQ(s.problem.goal.heading_tolerance, M_PI);      // any arrival heading
  EXPECT_DOUBLE_EQ(s.constraints.safety_distance, 1500);        // the goal's d_safety
  EXPECT_DOUBLE_EQ(s.constraints.colreg_distance, 3000);
  EXPECT_EQ(s.budget.seed, 1u + 3u);                             // plan.seed + plan index
  EXPECT_DOUBLE_EQ(s.problem.bounds.min_x, 1020 - 3000);
  EXPECT_DOUBLE_EQ(s.problem.bounds.max_x, 9000 + 3000);
  EXPECT_FALSE(s.arrived);
  EXPECT_DOUBLE_EQ(s.own.vx, 4.0);
  EXPECT_TRUE(opp::check_problem(s.problem, s.constraints).empty());

  goal.cruise_speed = 0;
  goal.safety_distance = 5000;  // beyond d_COLREG: d_COLREG follows it
  EXPECT_DOUBLE_EQ(opp::build_setup(p, own, goal, {}, {}, 0).problem.speed, 4.0);  // own speed
  EXPECT_DOUBLE_EQ(opp::build_setup(p, own, goal, {}, {}, 0).constraints.colreg_distance, 5000);
  const opp::OwnReport stopped{{1000, 2000}, 0.1, std::nan(""), std::nan(""), 5.0};
  const opp::Setup s2 = opp::build_setup(p, stopped, goal, {}, {}, 0);
  EXPECT_DOUBLE_EQ(s2.problem.start.x, 1000);             // unknown speed: no dead reckoning
  EXPECT_DOUBLE_EQ(s2.problem.speed, p.default_speed);
  goal.p = {1050, 2000};
  EXPECT_TRUE(opp::build_setup(p, own, goal, {}, {}, 0).arrived);
}

TEST(OppNode, EncounterParamsAndReportsUseTheRuleSectors) {
  opp::NodeParams p = declared({"plan.encounter_cpa=1.5"});
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};
  // A target dead ahead on the reciprocal course: head-on; and one with a NaN velocity.
  std::vector<opp::Target> tg = {{4, {2500, 10}, {-5, 0}, {}}, {5, {3000, 3000}, {std::nan(""), 0}, {}}};
  const opp::Setup s = opp::build_setup(p, own, {{20000, 0}, std::nan(""), 0, 5, 0, true}, tg, {}, 0);
  const opp::EncounterMemoryParams ep = opp::encounter_params(p, s);
  EXPECT_DOUBLE_EQ(ep.cpa_risk, 1500);
  EXPECT_DOUBLE_EQ(ep.tcpa_max, 20000.0 / 5.0);  // the straight-line time to the goal
  EXPECT_DOUBLE_EQ(ep.abaft_beam, p.sector_abaft_beam);
  std::vector<std::string> rejected;
  const auto rep = opp::report_encounters(p, s, &rejected);
  ASSERT_EQ(rep.size(), 1u);
  EXPECT_EQ(rep[0].id, 4u);
  EXPECT_EQ(rep[0].assessment.type, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_NEAR(rep[0].assessment.cpa.tcpa, 250, 1);
  ASSERT_EQ(rejected.size(), 1u);
}

TEST(OppNode, ThePlannerIsChosenByNameAndAnUnknownOneIsRefused) {
  EXPECT_EQ(opp::planner_names().front(), "rrtstar");
  EXPECT_EQ(opp::make_planner("rrtstar")->name(), "rrtstar");
  try {
    opp::make_planner("astar");
    FAIL() << "unknown planner accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("known: rrtstar"), std::string::npos) << e.what();
  }
  EXPECT_THROW(declared({"plan.planner=astar"}), mpgc::rt::ParamError);
  EXPECT_THROW(declared({"plan.step=0"}), mpgc::rt::ParamError);  // the planner's own range
  EXPECT_EQ(declared({"plan.planner=rrtstar"}).planner, "rrtstar");
}

// The interface adds nothing to the RRT*: solve() through it is plan() bit for bit.
TEST(OppNode, SolveThroughTheInterfaceIsThePlanBitForBit) {
  opp::Scenario sc = opp::paper_scenario(1);
  sc.params.max_iterations = 1500;
  sc.params.seed = 11;
  const opp::Result direct = opp::plan(sc.problem, sc.params);
  opp::RrtStar rrt;
  rrt.params() = sc.params;  // its RrtStarParams part
  const opp::Result via = rrt.solve({sc.problem, sc.params, sc.params, sc.params, {}});
  ASSERT_EQ(direct.path.size(), via.path.size());
  for (size_t i = 0; i < via.path.size(); ++i) {
    EXPECT_EQ(direct.path[i].p.x, via.path[i].p.x);
    EXPECT_EQ(direct.path[i].p.y, via.path[i].p.y);
  }
  EXPECT_EQ(direct.cost.total, via.cost.total);
  EXPECT_EQ(direct.stats.edge_checks, via.stats.edge_checks);
  // Bad input comes back as a status, not an exception.
  opp::Problem bad = sc.problem;
  bad.speed = std::nan("");
  const opp::Result r = rrt.solve({bad, sc.params, sc.params, sc.params, {}});
  EXPECT_EQ(r.status, opp::Status::kInvalidInput);
  EXPECT_NE(r.reason.find("speed"), std::string::npos);
}

// connect_goal = false: goal edges only from goal samples (as OMPL's RRTstar); still solves, with
// its first solution found later (a node near the goal waits for a goal sample).
TEST(OppNode, ConnectGoalOffConnectsOnlyFromGoalSamples) {
  opp::Scenario sc = opp::disc_world();
  sc.params.max_iterations = 3000;
  const opp::Result on = opp::plan(sc.problem, sc.params);
  sc.params.connect_goal = false;
  const opp::Result off = opp::plan(sc.problem, sc.params);
  ASSERT_EQ(on.status, opp::Status::kOk);
  ASSERT_EQ(off.status, opp::Status::kOk);
  EXPECT_GT(off.stats.first_solution_iteration, on.stats.first_solution_iteration);
}

}  // namespace

// Rule 17(a)(i): a target crossing from port on a collision course (own ship stand-on) is held
// for: course and speed kept until it is stand_on_range x d_safety away, acting only from there.
TEST(OppNode, AStandOnShipHoldsCourseAndSpeedUntilItMayAct) {
  opp::NodeParams p = declared({"plan.max_iterations=3000"});
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};  // north at 5 m/s
  const opp::GoalSpec goal{{30000, 0}, std::nan(""), 0, 5, 1000, true};
  // Meets the own ship at (10000, 0) at t = 2000 s, from the port bow heading east.
  const std::vector<opp::Target> tg = {{3, {10000, -8000}, {0, 4}, {}}};
  opp::Setup s = opp::build_setup(p, own, goal, tg, {}, 0);
  const opp::StandOnHold h = opp::stand_on_hold(p, s);
  ASSERT_GT(h.time, 0.0) << h.why_not;
  EXPECT_EQ(h.target, 3u);
  EXPECT_NEAR(h.end.y, 0.0, 1e-6);                                 // along the present course
  const opp::Vec2 tgt_then = tg[0].p + h.time * tg[0].v;
  EXPECT_NEAR(opp::norm(h.end - tgt_then), 3500.0, 1e-6);          // 3.5 d_safety
  EXPECT_NEAR(h.end.x, 5.0 * h.time, 1e-6);                        // at the present speed

  auto planner = opp::make_planner("rrtstar");
  const opp::Result r = opp::solve_with_hold(*planner, s, p.objective, h, {}, {});
  ASSERT_FALSE(r.path.empty()) << r.reason;
  EXPECT_EQ(r.path[0].p.x, 0.0);
  EXPECT_EQ(r.path[1].p.x, h.end.x);
  EXPECT_DOUBLE_EQ(r.path[1].t, h.time);
  EXPECT_NE(r.reason.find("stand-on (rule 17(a))"), std::string::npos) << r.reason;
  EXPECT_LT(opp::norm(r.path.back().p - goal.p), 1.0);

  // The previous plan's hold: its course is kept, and its end while the new estimate is within
  // plan.stand_on_steady (60 s) of it.
  opp::StandOnHold prev = h;
  prev.time = h.time + 40.0;
  prev.course = 0.01;
  const opp::StandOnHold kept = opp::stand_on_hold(p, s, prev);
  EXPECT_DOUBLE_EQ(kept.time, h.time + 40.0);
  EXPECT_DOUBLE_EQ(kept.course, 0.01);
  prev.time = h.time + 90.0;
  EXPECT_NEAR(opp::stand_on_hold(p, s, prev).time, h.time, 20.0);  // re-estimated (course 0.01: a little different)
  // Overtaken from 2 km astern (inside 3.5 d_safety) by a ship 2 m/s faster: the CPA is 1000 s
  // away, the own ship sails 3 d_safety (plan.stand_on_time) in 600 s, so it holds 400 s.
  const opp::Setup ot = opp::build_setup(p, own, goal, {{6, {-2000, 0}, {7, 0}, {}}}, {}, 0);
  EXPECT_NEAR(opp::stand_on_hold(p, ot).time, 400.0, 1e-6);
  // Already within 3.5 d_safety: may act now, no hold.
  opp::Setup close = opp::build_setup(p, {{8000, 0}, 0.0, 5.0, 0.0, 0.0}, goal, {{3, {10000, -1600}, {0, 4}, {}}}, {}, 0);
  EXPECT_EQ(opp::stand_on_hold(p, close).time, 0.0);
  // Switched off.
  EXPECT_EQ(opp::stand_on_hold(declared({"plan.stand_on_range=0"}), s).time, 0.0);
  // Giving way to another ship (a pinned duty): rule 16 first, no hold, and why.
  s.problem.targets.push_back({4, {9000, 6000}, {0, -3}, {}});
  s.problem.targets.back().pinned.obligation = opp::Obligation::kCrossingGiveWay;
  const opp::StandOnHold g = opp::stand_on_hold(p, s);
  EXPECT_EQ(g.time, 0.0);
  EXPECT_NE(g.why_not.find("giving way to target 4"), std::string::npos) << g.why_not;
  // A ship crossing from starboard (own ship gives way) is no reason to hold.
  opp::Setup gw = opp::build_setup(p, own, goal, {{5, {10000, 8000}, {0, -4}, {}}}, {}, 0);
  EXPECT_EQ(opp::stand_on_hold(p, gw).time, 0.0);
  // Pinned stand-on and no risk any more: held until its CPA if it has acted (turned 90 deg to
  // starboard, passing 2.5 km off), not if the risk went because the own ship altered for others
  // while the other held on (DNV 40: the own ship heading 30 deg, the ship on the port bow east).
  opp::Target acted{3, {10000, -2500}, {-4, 0}, {}};
  acted.pinned = {opp::Obligation::kCrossingStandOn, 0.0, 0, 1.5707963267948966};  // it was heading east
  opp::Setup after = opp::build_setup(p, own, goal, {acted}, {}, 0);
  after.problem.targets[0].pinned = acted.pinned;
  EXPECT_GT(opp::stand_on_hold(p, after).time, 0.0);
  opp::Target held_on{3, {10000, -6000}, {0, 4}, {}};  // CPA 2.4 km in 2490 s: no risk
  opp::Setup diverted = opp::build_setup(p, {{0, 0}, 0.52, 5.0, 0.52, 0.0}, goal, {held_on}, {}, 0);
  diverted.problem.targets[0].pinned = acted.pinned;
  EXPECT_EQ(opp::stand_on_hold(p, diverted).time, 0.0);
}

namespace {
// A canal too narrow to overtake in (walls 1600 m apart; d_safety 500 m), 12 km to the goal at
// 5 m/s, and a ship 2 km ahead sailing the same way at 1.5 m/s.
opp::DiscObstacles narrow_canal() {
  std::vector<opp::Disc> walls;
  for (double x = -2000; x <= 14000; x += 200) {
    walls.push_back({{x, -900}, 100});
    walls.push_back({{x, 900}, 100});
  }
  return opp::DiscObstacles(walls);
}
opp::Setup ship_ahead_in(const opp::DiscObstacles& canal, const opp::NodeParams& p) {
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};
  const opp::GoalSpec goal{{12000, 0}, std::nan(""), 0, 5, 500, true};
  const std::vector<opp::Target> tg = {{7, {2000, 0}, {1.5, 0}, {}}};
  return opp::build_setup(p, own, goal, tg, {&canal, std::nullopt}, 0);
}
}  // namespace

// Seed 000 §2: the speed is reduced when steering alone is not sufficient. In a canal too narrow
// to overtake in (walls 1600 m apart, d_safety 500 m), a ship 2 km ahead sails the same way at
// 1.5 m/s: at 5 m/s there is no path at all, at 25 % (1.25 m/s) the own ship follows it.
TEST(OppNode, SpeedIsReducedWhenSteeringAloneIsNotSufficient) {
  opp::NodeParams p = declared({"plan.max_iterations=4000", "plan.safety_distance=500", "plan.colreg_distance=2000"});
  const opp::DiscObstacles canal = narrow_canal();
  const opp::Setup s = ship_ahead_in(canal, p);
  auto planner = opp::make_planner("rrtstar");
  const opp::NodePlan np = opp::plan_node(*planner, p, s, p.objective, {}, {}, {});
  ASSERT_EQ(np.result.status, opp::Status::kOk) << np.result.reason;
  EXPECT_DOUBLE_EQ(np.speed_fraction, 0.25);
  EXPECT_NE(np.result.reason.find("speed reduced to 25 %"), std::string::npos) << np.result.reason;
  ASSERT_EQ(np.speeds.size(), np.result.path.size());
  EXPECT_DOUBLE_EQ(np.speeds.back(), np.speed_fraction * 5.0);
  // With no lower speed allowed there is no path.
  const opp::NodePlan fixed = opp::plan_node(*planner, declared({"plan.max_iterations=4000", "plan.safety_distance=500",
                                                                  "plan.colreg_distance=2000", "plan.speed_steps=0"}),
                                             s, p.objective, {}, {}, {});
  EXPECT_NE(fixed.result.status, opp::Status::kOk);
  EXPECT_TRUE(fixed.emergency);  // no path at the one speed: the emergency leg
}

// A stand-in for dijkstra-sv's choices, to test plan_node's: its own margin (the safe CPA) is kept
// only below 3 m/s, and it returns the previous path (warm) as it is while slower than that.
class MarginPlanner final : public opp::Planner {
 public:
  std::string name() const override { return "margin"; }
  void declare(mpgc::rt::ParamSet&) override {}
  bool keeps_plan() const override { return true; }
  opp::Result solve(const opp::Request& rq, const opp::Hooks&) override {
    const opp::Problem& pb = rq.problem;
    opp::Result r;
    r.status = opp::Status::kOk;
    r.margin_reduced = pb.speed >= 3.0;
    r.kept = !rq.warm.empty() && !r.margin_reduced;
    r.path = {{pb.start, 0.0}, {pb.goal.p, opp::norm(pb.goal.p - pb.start) / pb.speed}};
    return r;
  }
};

// Seed 000 §2 with dijkstra-sv's safe CPA: a plan that gives the margin up makes the node try the
// lower speeds, and one keeping it wins over an earlier arrival without it; a kept plan is re-asked
// at its own speed, not replaced, unless a faster one keeps the margin now.
TEST(OppNode, SpeedTriesPreferThePlannersOwnMarginAndKeepThePlanAtItsSpeed) {
  const opp::NodeParams p = declared();  // speeds 100, 75, 50, 25 %
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};
  const opp::GoalSpec goal{{12000, 0}, std::nan(""), 0, 5, 500, true};
  const opp::Setup s = opp::build_setup(p, own, goal, {}, {}, 0);
  ASSERT_TRUE(s.problem.colreg);
  MarginPlanner planner;
  const opp::NodePlan first = opp::plan_node(planner, p, s, p.objective, {}, {}, {});
  EXPECT_FALSE(first.result.margin_reduced) << first.result.reason;
  EXPECT_DOUBLE_EQ(first.speed_fraction, 0.5);  // 75 % is still 3.75 m/s: the fastest with the margin
  EXPECT_FALSE(first.result.kept);
  const std::vector<opp::Vec2> warm{{0, 0}, {12000, 0}};
  const opp::NodePlan again = opp::plan_node(planner, p, s, p.objective, {}, warm, {}, first.speed_fraction);
  EXPECT_TRUE(again.result.kept) << again.result.reason;
  EXPECT_DOUBLE_EQ(again.speed_fraction, 0.5);
  EXPECT_NE(again.result.reason.find("at 50 % speed"), std::string::npos) << again.result.reason;
  ASSERT_EQ(again.speeds.size(), 2u);
  EXPECT_DOUBLE_EQ(again.speeds.back(), 2.5);
  // Sailed at 25 % while 50 % now keeps the margin: the ship works back up (DNV 46 held 25 % for
  // 1000 s and ran out of time), to the fastest such speed.
  const opp::NodePlan raised = opp::plan_node(planner, p, s, p.objective, {}, warm, {}, 0.25);
  EXPECT_DOUBLE_EQ(raised.speed_fraction, 0.5);
  EXPECT_FALSE(raised.result.margin_reduced);
  EXPECT_NE(raised.result.reason.find("speed raised to 50 % from 25 %"), std::string::npos) << raised.result.reason;
}

// The lower speeds are solved at once on their own threads: the plan is still a function of the
// request and the seed alone, bit for bit, and the same as each speed solved on its own.
TEST(OppNode, SpeedTriesSolvedAtOnceGiveTheSamePlan) {
  opp::NodeParams p = declared({"plan.max_iterations=3000", "plan.safety_distance=500", "plan.colreg_distance=2000"});
  const opp::DiscObstacles canal = narrow_canal();
  const opp::Setup s = ship_ahead_in(canal, p);
  auto planner = opp::make_planner("rrtstar");
  const opp::NodePlan a = opp::plan_node(*planner, p, s, p.objective, {}, {}, {});
  const opp::NodePlan b = opp::plan_node(*planner, p, s, p.objective, {}, {}, {});
  ASSERT_EQ(a.result.status, opp::Status::kOk) << a.result.reason;
  ASSERT_LT(a.speed_fraction, 1.0);
  ASSERT_EQ(a.result.path.size(), b.result.path.size());
  for (size_t i = 0; i < a.result.path.size(); ++i) {
    EXPECT_EQ(a.result.path[i].p.x, b.result.path[i].p.x);
    EXPECT_EQ(a.result.path[i].p.y, b.result.path[i].p.y);
  }
  EXPECT_EQ(a.result.cost.total, b.result.cost.total);
  // The chosen speed solved alone, sequentially, gives the same path.
  opp::Setup slow = s;
  slow.problem.speed = a.speed_fraction * s.problem.speed;
  const opp::Result alone = planner->solve(slow.request(p.objective, {}), {});
  ASSERT_EQ(alone.path.size(), a.result.path.size());
  for (size_t i = 0; i < alone.path.size(); ++i) EXPECT_EQ(alone.path[i].p.x, a.result.path[i].p.x);
  EXPECT_EQ(alone.cost.total, a.result.cost.total);
}

// A slower plan is charged the reduced speed only until it has passed the ships it meets: the
// time along it of the last closest approach within range.
TEST(OppNode, TheLastMeetingIsWhenThePlanHasPassedEveryShipItMeets) {
  opp::Result r;
  r.path = {{{0, 0}, 0.0}, {{1000, 0}, 200.0}, {{1000, 1000}, 400.0}};  // 5 m/s north, then east
  // Crossing from the west at 5 m/s on x = 600: nearest at 120 s on the first leg.
  const opp::Target crossing{1, {600, -600}, {0, 5}, {}};
  EXPECT_NEAR(opp::last_meeting(r, {crossing}, 500.0), 120.0, 1e-9);
  // One met on the second leg (waiting at (1000, 600)) comes later; one 5 km off is not met.
  const opp::Target waiting{2, {1000, 600}, {0, 0}, {}}, far{3, {-5000, 0}, {0, 0}, {}};
  EXPECT_NEAR(opp::last_meeting(r, {crossing, waiting, far}, 500.0), 320.0, 1e-9);
  EXPECT_NEAR(opp::last_meeting(r, {far}, 500.0), 0.0, 1e-12);
  // One crossing 300 m ahead is nearest (212 m) at 150 s: sailed at 5 m/s until then, at 10 m/s
  // after (still 50 m clear of it), 150 + 1250 m / 10 m/s. A ship followed along the second leg
  // (at 5 m/s east, 300 m ahead of it, nearest at 170 s on the first) is not passed: resuming
  // would run into it, so the plan's own 400 s.
  const opp::Target ahead{5, {900, -600}, {0, 5}, {}};
  EXPECT_NEAR(opp::last_meeting(r, {ahead}, 500.0), 150.0, 1e-9);
  EXPECT_NEAR(opp::resumed_arrival(r, {ahead}, 500.0, 50.0, 10.0), 275.0, 1e-9);
  const opp::Target followed{4, {1000, -700}, {0, 5}, {}};
  EXPECT_NEAR(opp::last_meeting(r, {followed}, 500.0), 170.0, 1e-9);
  EXPECT_NEAR(opp::resumed_arrival(r, {ahead, followed}, 500.0, 50.0, 10.0), 400.0, 1e-9);
  r.path.clear();
  EXPECT_EQ(opp::last_meeting(r, {crossing}, 500.0), 0.0);
  EXPECT_EQ(opp::resumed_arrival(r, {crossing}, 500.0, 100.0, 10.0), 0.0);
}

// Rule 17(b): no path at all (here: one iteration, no tree) gives the emergency leg, starboard
// first, at reduced speed unless the planned speed passes 10 % farther; to port when a fixed
// obstacle lies to starboard.
TEST(OppNode, NoPathAtAllGivesTheEmergencyLegStarboardFirst) {
  opp::NodeParams p = declared({"plan.max_iterations=1", "plan.warm_start=false"});
  const opp::OwnReport own{{0, 0}, 0.0, 5.0, 0.0, 0.0};
  const opp::GoalSpec goal{{20000, 0}, std::nan(""), 0, 5, 1000, true};
  const std::vector<opp::Target> tg = {{2, {6000, 0}, {-5, 0}, {}}};  // head-on
  const opp::Setup s = opp::build_setup(p, own, goal, tg, {}, 0);
  auto planner = opp::make_planner("rrtstar");
  const opp::NodePlan np = opp::plan_node(*planner, p, s, p.objective, {}, {}, {});
  ASSERT_TRUE(np.emergency) << np.result.reason;
  EXPECT_EQ(np.result.status, opp::Status::kRelaxed);
  ASSERT_EQ(np.result.path.size(), 2u);
  EXPECT_GT(np.result.path[1].p.y, 0.0);  // east of north: starboard
  EXPECT_NE(np.result.reason.find("emergency (rule 17(b))"), std::string::npos);
  // 6 km off, turning away at the planned speed opens the range more within the leg's time (2.2 km
  // at 25 %, 4.5 km at full speed): the speed that passes farther is taken.
  EXPECT_DOUBLE_EQ(np.speed_fraction, 1.0) << np.result.reason;
  EXPECT_DOUBLE_EQ(np.speeds[1], 5.0);
  // Land to starboard: the leg goes to port.
  const opp::DiscObstacles land({{{600, 900}, 400}});
  const opp::Setup s2 = opp::build_setup(p, own, goal, tg, {&land, std::nullopt}, 0);
  const opp::Result e = opp::emergency_path(p, s2, "test");
  ASSERT_EQ(e.path.size(), 2u);
  EXPECT_LT(e.path[1].p.y, 0.0);
  // Overtaken from close astern by a faster ship on the own track, slowing down brings it on sooner:
  // the leg keeps the planned speed (rule 8(e) slackens speed only where that helps).
  const std::vector<opp::Target> astern = {{3, {-1500, 0}, {10, 0}, {}}};
  const opp::NodePlan ot = opp::plan_node(*planner, p, opp::build_setup(p, own, goal, astern, {}, 0), p.objective, {}, {}, {});
  ASSERT_TRUE(ot.emergency) << ot.result.reason;
  EXPECT_DOUBLE_EQ(ot.speed_fraction, 1.0) << ot.result.reason;
  EXPECT_DOUBLE_EQ(ot.speeds[1], 5.0);
  EXPECT_GT(ot.result.path[1].p.y, 0.0) << ot.result.reason;
  // Switched off: the no-path plan stands.
  EXPECT_FALSE(opp::plan_node(*planner, declared({"plan.max_iterations=1", "plan.emergency=false"}), s, p.objective, {}, {}, {})
                   .emergency);
}
