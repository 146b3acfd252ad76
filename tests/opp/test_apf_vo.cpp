// Seed 003's planner (apf_vo.hpp): the tangent force of eq. 9-10 against the typical APF's local
// minimum, Douglas-Peucker (Algorithm 1), the modified VO's side choice (eq. 19-21), the paper's
// own case (Tables 1-3) and bad input.
#include <gtest/gtest.h>

#include <cmath>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/opp/apf_vo.hpp"
#include "mpgc/opp/registry.hpp"
#include "mpgc/opp/validity.hpp"
#include "mpgc/runtime/params.hpp"
#include "problems.hpp"

namespace opp = mpgc::opp;
namespace geo = mpgc::geo;

namespace {

opp::Vec2 dir_of(double course) { return {std::cos(course), std::sin(course)}; }

// Independent of the planner's exact segment test: dense samples of every leg keep d_safety from
// every disc and from every target at its eq. 3 position at the time the ship is there.
double min_margin(const opp::Problem& pb, const std::vector<opp::Disc>& discs, const opp::Result& r,
                  double* to_targets = nullptr) {
  double m = 1e300, mt = 1e300;
  for (size_t i = 0; i + 1 < r.path.size(); ++i) {
    const opp::Vec2 a = r.path[i].p, b = r.path[i + 1].p;
    const int n = std::max(2, static_cast<int>(opp::norm(b - a) / 5.0));
    for (int k = 0; k <= n; ++k) {
      const double s = static_cast<double>(k) / n;
      const opp::Vec2 x = a + s * (b - a);
      const double t = r.path[i].t + s * (r.path[i + 1].t - r.path[i].t);
      for (const auto& d : discs) m = std::min(m, opp::norm(x - d.c) - d.r);
      for (const auto& tg : pb.targets) mt = std::min(mt, opp::norm(x - (tg.p + t * tg.v)));
    }
  }
  if (to_targets) *to_targets = mt;
  return m;
}

struct World {
  std::vector<opp::Disc> discs;
  opp::DiscObstacles obstacles;
  opp::Problem pb;
  opp::ConstraintParams c;
  explicit World(std::vector<opp::Disc> d) : discs(d), obstacles(std::move(d)) {
    pb.fixed = &obstacles;
    pb.speed = 5.0;
    pb.colreg = true;
  }
};

opp::Result solve(opp::ApfVo& planner, const opp::Problem& pb, const opp::ConstraintParams& c) {
  return planner.solve(opp::Request{pb, c, opp::ObjectiveParams{}, opp::Budget{}, {}});
}

// An obstacle straight between start and goal: attraction and repulsion on one line, opposed.
World symmetric_trap() {
  World w({{{10000, 0}, 500}});
  w.pb.start = {0, 0};
  w.pb.heading = 0.0;
  w.pb.goal.p = {20000, 0};
  w.pb.bounds = {-10000, -10000, 30000, 10000};
  w.c.safety_distance = 500;
  return w;
}

}  // namespace

TEST(ApfVo, IsInTheRegistryAndDeclaresItsParameters) {
  auto p = opp::make_planner("apf-vo");
  EXPECT_EQ(p->name(), "apf-vo");
  mpgc::rt::ParamSet ps;
  p->declare(ps);
  ps.validate_and_apply();
  auto* a = dynamic_cast<opp::ApfVo*>(p.get());
  ASSERT_NE(a, nullptr);
  EXPECT_DOUBLE_EQ(a->apf().step, 200.0);        // Table 4
  EXPECT_DOUBLE_EQ(a->apf().dp_epsilon, 500.0);  // Table 4
  EXPECT_TRUE(a->apf().tangent_force);
  mpgc::rt::ParamSet bad;
  p->declare(bad);
  bad.set_override("plan.apf.step=-5");
  EXPECT_ANY_THROW(bad.validate_and_apply());
}

TEST(ApfVo, TangentForceEscapesTheLocalMinimumOfTheTypicalApf) {
  World w = symmetric_trap();
  opp::ValidityChecker check(w.pb, w.c);
  opp::ApfParams typical;
  typical.tangent_force = false;
  std::string why;
  int steps = 0;
  EXPECT_TRUE(opp::apf_path(check, w.pb.start, w.pb.goal.p, typical, 5000, &steps, &why).empty());
  EXPECT_NE(why.find("local minimum"), std::string::npos) << why;

  opp::ApfParams improved;  // eq. 9-10
  why.clear();
  const auto path = opp::apf_path(check, w.pb.start, w.pb.goal.p, improved, 5000, &steps, &why);
  ASSERT_FALSE(path.empty()) << why;
  EXPECT_EQ(path.back().x, 20000.0);
  EXPECT_EQ(path.back().y, 0.0);
  for (size_t i = 0; i + 1 < path.size(); ++i)
    EXPECT_TRUE(check.fixed_clear(path[i], path[i + 1], w.c.safety_distance)) << "step " << i;
  // It went round: starboard (east, +y) of the attraction when the goal is straight behind.
  double ymax = 0;
  for (const auto& q : path) ymax = std::max(ymax, q.y);
  EXPECT_GT(ymax, 1000.0);

  // The same through the planner: the typical APF finds no path, the improved one does.
  opp::ApfVo planner;
  planner.apf().tangent_force = false;
  const opp::Result stuck = solve(planner, w.pb, w.c);
  EXPECT_EQ(stuck.status, opp::Status::kNoPath);
  EXPECT_NE(stuck.reason.find("local minimum"), std::string::npos) << stuck.reason;
  planner.apf().tangent_force = true;
  const opp::Result r = solve(planner, w.pb, w.c);  // within the 60 deg turn limit too
  ASSERT_EQ(r.status, opp::Status::kOk) << r.reason;
  EXPECT_GE(min_margin(w.pb, w.discs, r), w.c.safety_distance - 1e-6);
}

TEST(ApfVo, DouglasPeuckerKeepsEndpointsAndDropsCollinearPoints) {
  // Points within 10 m of a straight line and one corner 3 km off it.
  const std::vector<opp::Vec2> t = {{0, 0}, {1000, 5}, {2000, -8}, {3000, 0}, {4000, 3000}, {5000, 6001}, {6000, 9000}};
  const auto c = opp::douglas_peucker(t, 500.0);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.front().x, 0.0);
  EXPECT_EQ(c.back().x, 6000.0);
  EXPECT_EQ(c.back().y, 9000.0);
  EXPECT_EQ(c[1].x, 3000.0);  // the corner, the farthest point from the chord
  // Within tolerance: a straight line collapses to its endpoints.
  EXPECT_EQ(opp::douglas_peucker({{0, 0}, {1, 1}, {2, 2}, {3, 3}}, 0.5).size(), 2u);
  // A smaller epsilon keeps the 8 m wiggle.
  EXPECT_GT(opp::douglas_peucker(t, 1.0).size(), 3u);
  // A chord refused (an obstacle under it) keeps a point even within epsilon.
  const auto kept = opp::douglas_peucker({{0, 0}, {1, 1}, {2, 2}}, 10.0, [](opp::Vec2 a, opp::Vec2 b) {
    return !(a.x == 0 && b.x == 2);
  });
  EXPECT_EQ(kept.size(), 3u);
  EXPECT_EQ(opp::douglas_peucker({{1, 2}}, 1.0).size(), 1u);
}

namespace {
using opp::test::open_water;
double dcpa_on(const opp::Problem& pb, double course, const opp::Target& t) {
  const opp::Vec2 v = pb.speed * dir_of(course);
  return mpgc::colreg::cpa({0, 0, v.x, v.y}, {t.p.x, t.p.y, t.v.x, t.v.y}).dcpa;
}
}  // namespace

TEST(ApfVo, VoTurnsToStarboardHeadOnAndWhenGivingWayCrossing) {
  const opp::ConstraintParams c;  // d_safety 1000 m
  const opp::VoParams vp;
  // Head-on, 50 m to starboard of the own course line (a passing starboard to starboard would be
  // the shorter turn to port).
  const opp::Problem head_on = open_water({{1, {8000, 50}, {-5, 0}}});
  const opp::VoDecision h = opp::vo_decide(head_on, c, vp, head_on.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(h.risk);
  EXPECT_EQ(h.situation, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_EQ(h.side, opp::VoSide::kStarboard);
  EXPECT_GT(h.course, h.c1);  // eq. 20: the centre of VA_R, beyond the VO's edge C1
  EXPECT_LT(h.course, geo::deg2rad(90.0) + 1e-9);
  EXPECT_GE(dcpa_on(head_on, h.course, head_on.targets[0]), vp.dcpa_factor * c.safety_distance);

  // Crossing from starboard on a collision course: give way, astern of it.
  const opp::Problem crossing = open_water({{2, {4000, 4000}, {0, -5}}});
  const opp::VoDecision x = opp::vo_decide(crossing, c, vp, crossing.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(x.risk);
  EXPECT_EQ(x.situation, mpgc::colreg::EncounterType::kCrossingGiveWay);
  EXPECT_EQ(x.side, opp::VoSide::kStarboard);
  EXPECT_GT(x.course, 0.0);

  // Crossing from port: the own ship stands on (constraint 5).
  const opp::Problem stand_on = open_water({{3, {4000, -4000}, {0, 5}}});
  const opp::VoDecision s = opp::vo_decide(stand_on, c, vp, stand_on.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(s.risk);
  EXPECT_EQ(s.situation, mpgc::colreg::EncounterType::kCrossingStandOn);
  EXPECT_EQ(s.side, opp::VoSide::kNone);

  // No risk beyond the time threshold (VO set2 of Fig. 8).
  const opp::Problem far = open_water({{4, {20000, 0}, {-5, 0}}});
  EXPECT_FALSE(opp::vo_decide(far, c, vp, far.start, 0.0, 5.0, 0.0).risk);  // TCPA 2000 s > 900 s
}

// COLREG not required (a *_nocolreg scenario): no rule picks the side and no ship stands on; the
// smaller alteration out of the VO is taken.
TEST(ApfVo, VoWithoutColregTakesTheSmallerAlterationAndNeverStandsOn) {
  const opp::ConstraintParams c;
  const opp::VoParams vp;
  // Head-on, 50 m to starboard of the own course line: port (starboard to starboard) is shorter.
  opp::Problem head_on = open_water({{1, {8000, 50}, {-5, 0}}});
  head_on.colreg = false;
  const opp::VoDecision h = opp::vo_decide(head_on, c, vp, head_on.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(h.risk);
  EXPECT_EQ(h.side, opp::VoSide::kPort);
  EXPECT_LT(h.course, 0.0);
  EXPECT_GE(dcpa_on(head_on, h.course, head_on.targets[0]), vp.dcpa_factor * c.safety_distance);
  // A crossing ship on the port side: without COLREG the own ship does not stand on, it keeps clear.
  opp::Problem stand_on = open_water({{3, {4000, -4000}, {0, 5}}});
  stand_on.colreg = false;
  const opp::VoDecision s = opp::vo_decide(stand_on, c, vp, stand_on.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(s.risk);
  EXPECT_NE(s.side, opp::VoSide::kNone);
  EXPECT_GE(dcpa_on(stand_on, s.course, stand_on.targets[0]), vp.dcpa_factor * c.safety_distance);
}

TEST(ApfVo, VoKeepsClearWhenOvertakingOnTheWiderSide) {
  const opp::ConstraintParams c;
  const opp::VoParams vp;
  // A slower ship ahead, a little to starboard of the own course: the port set is the wider (eq. 21).
  const opp::Problem right = open_water({{1, {2500, 300}, {2, 0}}});
  const opp::VoDecision r = opp::vo_decide(right, c, vp, right.start, 0.0, 5.0, 0.0);
  ASSERT_TRUE(r.risk);
  EXPECT_EQ(r.situation, mpgc::colreg::EncounterType::kOvertaking);
  EXPECT_GT(r.width_port, r.width_starboard);
  EXPECT_EQ(r.side, opp::VoSide::kPort);
  EXPECT_LT(r.course, 0.0);
  const double d = dcpa_on(right, r.course, right.targets[0]);
  EXPECT_GE(d, vp.dcpa_factor * c.safety_distance);
  // Mirrored: starboard.
  const opp::Problem left = open_water({{1, {2500, -300}, {2, 0}}});
  const opp::VoDecision l = opp::vo_decide(left, c, vp, left.start, 0.0, 5.0, 0.0);
  EXPECT_EQ(l.side, opp::VoSide::kStarboard);
  EXPECT_GT(l.width_starboard, l.width_port);

  // The whole plan overtakes it clear by d_safety and reaches the goal.
  opp::ApfVo planner;
  const opp::Result p = solve(planner, right, c);
  ASSERT_TRUE(p.status == opp::Status::kOk || p.status == opp::Status::kRelaxed) << p.reason;
  double to_targets = 0;
  min_margin(right, {}, p, &to_targets);
  EXPECT_GE(to_targets, c.safety_distance - 1e-6);
}

// Stage 1 by the shared checker (plan.vo.checker_trigger): a slower ship 5.2 km on the port beam on
// a nearly parallel course is, for the checker's per-leg model (eq. 16), overtaken, and the course
// held crosses its route ahead of it; the rule sectors saw a crossing ship to stand on for, and the
// refused course was sailed: every full-speed plan relaxed (seed 003 case, TS3 once its pinned
// encounter was released). The decision follows the checker's encounter, and the plan is valid.
TEST(ApfVo, CheckerRefusedCourseIsAvoidedAsTheCheckersEncounter) {
  opp::ConstraintParams c;
  c.safety_distance = 1852;
  c.colreg_distance = 5556;
  const opp::VoParams vp;
  const opp::Problem pb = open_water({{3, {289, -5236}, {1.93, 0.146}}});
  const opp::ValidityChecker check(pb, c);
  ASSERT_EQ(check.moving(pb.start, 0.0, {463, 0}, 463, opp::ColregLevel::kFull), opp::ValidityChecker::kColreg);
  const opp::VoDecision d = opp::vo_decide(pb, c, vp, pb.start, 0.0, 5.0, 0.0, 0);
  EXPECT_EQ(d.situation, mpgc::colreg::EncounterType::kOvertaking);
  EXPECT_EQ(d.side, opp::VoSide::kStarboard);  // away from its route
  opp::ApfVo planner;
  const opp::Result r = solve(planner, pb, c);
  EXPECT_EQ(r.status, opp::Status::kOk) << r.reason;
}

TEST(ApfVo, HeadOnPlanPassesPortToPort) {
  opp::ConstraintParams c;
  const opp::Problem pb = open_water({{1, {12000, 0}, {-5, 0}}});
  opp::ApfVo planner;
  const opp::Result r = solve(planner, pb, c);
  ASSERT_TRUE(r.status == opp::Status::kOk || r.status == opp::Status::kRelaxed) << r.reason;
  double to_targets = 0;
  min_margin(pb, {}, r, &to_targets);
  EXPECT_GE(to_targets, c.safety_distance - 1e-6);
  // The first waypoint off the course line is to starboard (east): the target passes on the own
  // port side.
  double first_off = 0.0;
  for (const auto& w : r.path)
    if (std::fabs(w.p.y) > 1.0) {
      first_off = w.p.y;
      break;
    }
  EXPECT_GT(first_off, 0.0);
}

TEST(ApfVo, Seed003CaseClearsAllSixteenCircles) {
  // Table 3 as (north, east) = (y, x) of the table, radius; Table 1/2 through the project's NED.
  const double t3[16][3] = {{15703, 18214, 208}, {18838, 2589, 1037},  {22404, 30503, 572}, {23747, 6842, 713},
                            {29629, 7694, 834},  {32730, 33453, 338},  {34584, 11164, 373}, {41623, 33910, 1589},
                            {43259, 17334, 148}, {43597, 5022, 1525},  {44764, 23965, 2960}, {55805, 31632, 578},
                            {59791, 6447, 348},  {64252, 10445, 18},   {64276, 10743, 235}, {64508, 20377, 482}};
  std::vector<opp::Disc> discs;
  for (const auto& e : t3) discs.push_back({{e[1], e[0]}, e[2]});
  World w(discs);
  const geo::LocalNed ned({geo::deg2rad(10.9391), geo::deg2rad(120.71)});
  auto at = [&](double lat, double lon) { return ned.to_ned({geo::deg2rad(lat), geo::deg2rad(lon)}); };
  auto vel = [](double course_deg, double u) { return u * dir_of(geo::deg2rad(course_deg)); };
  w.pb.start = at(11.071, 120.762);
  w.pb.heading = geo::deg2rad(57);
  w.pb.goal.p = {43060, 52508};
  w.pb.bounds = {-5000, -5000, 70000, 70000};
  w.pb.targets = {{1, at(11.138, 120.872), vel(237, 5)},
                  {2, at(11.051, 120.905), vel(167, 6.7)},
                  {3, at(11.109, 120.825), vel(57, 2)}};
  w.c.safety_distance = 1852;
  w.c.colreg_distance = 5556;

  // The global path alone (APF + DP).
  const opp::ValidityChecker check(w.pb, w.c);
  std::string why;
  int steps = 0;
  const auto raw = opp::apf_path(check, w.pb.start, w.pb.goal.p, opp::ApfParams{}, 20000, &steps, &why);
  ASSERT_FALSE(raw.empty()) << why;
  const auto g = opp::douglas_peucker(raw, 500.0, [&](opp::Vec2 a, opp::Vec2 b) {
    return check.fixed_clear(a, b, w.c.safety_distance);
  });
  EXPECT_LT(g.size(), raw.size());
  opp::Result gr;
  for (const auto& p : g) gr.path.push_back({p, 0.0});
  EXPECT_GE(min_margin(w.pb, w.discs, gr), w.c.safety_distance - 1e-6);

  // The plan with the targets.
  opp::ApfVo planner;
  const opp::Result r = solve(planner, w.pb, w.c);
  ASSERT_TRUE(r.status == opp::Status::kOk || r.status == opp::Status::kRelaxed) << r.reason;
  double to_targets = 0;
  EXPECT_GE(min_margin(w.pb, w.discs, r, &to_targets), w.c.safety_distance - 1e-6);
  EXPECT_GE(to_targets, w.c.safety_distance - 1e-6);
  // TS1 (head-on) makes the one avoidance manoeuvre, to starboard.
  EXPECT_NE(r.reason.find("target 1 head-on: starboard"), std::string::npos) << r.reason;
  // Deterministic: the same request gives the same path.
  const opp::Result again = solve(planner, w.pb, w.c);
  ASSERT_EQ(again.path.size(), r.path.size());
  for (size_t i = 0; i < r.path.size(); ++i) EXPECT_EQ(again.path[i].p.x, r.path[i].p.x);
}

TEST(ApfVo, BadInputIsRejectedWithAReason) {
  World w = symmetric_trap();
  opp::ApfVo planner;
  opp::Problem nan_start = w.pb;
  nan_start.start.x = std::nan("");
  opp::Result r = solve(planner, nan_start, w.c);
  EXPECT_EQ(r.status, opp::Status::kInvalidInput);
  EXPECT_NE(r.reason.find("start"), std::string::npos) << r.reason;

  opp::Problem in_obstacle = w.pb;
  in_obstacle.goal.p = {10000, 100};
  r = solve(planner, in_obstacle, w.c);
  EXPECT_EQ(r.status, opp::Status::kInvalidInput);
  EXPECT_NE(r.reason.find("goal"), std::string::npos) << r.reason;

  opp::Problem nan_target = w.pb;
  nan_target.targets = {{5, {5000, 5000}, {std::nan(""), 0}}};
  r = solve(planner, nan_target, w.c);
  EXPECT_EQ(r.status, opp::Status::kInvalidInput);
  EXPECT_NE(r.reason.find("target"), std::string::npos) << r.reason;

  opp::ConstraintParams bad = w.c;
  bad.safety_distance = -1;
  EXPECT_EQ(solve(planner, w.pb, bad).status, opp::Status::kInvalidInput);

  // No fixed obstacles is open water (Problem::fixed == nullptr), not an error: straight to the goal.
  opp::Problem open = w.pb;
  open.fixed = nullptr;
  r = solve(planner, open, w.c);
  ASSERT_EQ(r.status, opp::Status::kOk) << r.reason;
  EXPECT_EQ(r.path.size(), 2u);
  EXPECT_DOUBLE_EQ(r.path.back().t, 20000.0 / 5.0);
}
