// COLREG geometry: CPA/TCPA against brute force, relative bearings, and the rule sectors on
// canonical encounters seen from both ships.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/testing.hpp"

namespace cr = mpgc::colreg;
using mpgc::geo::deg2rad;
using cr::EncounterType;

namespace {
cr::ShipKinematics ship(double x, double y, double course_deg, double speed) {
  return cr::ShipKinematics::from_course(x, y, deg2rad(course_deg), speed);
}
}  // namespace

TEST(Cpa, HeadOnClosedForm) {
  const auto own = ship(0, 0, 0, 5), tgt = ship(4000, 100, 180, 5);
  const cr::Cpa c = cr::cpa(own, tgt);
  EXPECT_NEAR(c.tcpa, 400.0, 1e-9);
  EXPECT_NEAR(c.dcpa, 100.0, 1e-9);
  EXPECT_NEAR(c.range, std::hypot(4000.0, 100.0), 1e-9);
}

TEST(Cpa, NoRelativeMotionGivesRangeNow) {
  const cr::Cpa c = cr::cpa(ship(0, 0, 45, 6), ship(300, 400, 45, 6));
  EXPECT_EQ(c.tcpa, 0.0);
  EXPECT_NEAR(c.dcpa, 500.0, 1e-9);
}

TEST(Cpa, OpeningShipsHaveNegativeTcpa) {
  const cr::Cpa c = cr::cpa(ship(0, 0, 0, 5), ship(-1000, 50, 180, 5));
  EXPECT_LT(c.tcpa, 0.0);
  EXPECT_NEAR(c.dcpa, 50.0, 1e-9);
}

TEST(Cpa, AgreesWithBruteForceAndIsSymmetric) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> pos(-10000, 10000), crs(-180, 180), spd(0, 12);
  for (int k = 0; k < 200; ++k) {
    const auto a = ship(pos(rng), pos(rng), crs(rng), spd(rng));
    const auto b = ship(pos(rng), pos(rng), crs(rng), spd(rng));
    const cr::Cpa c = cr::cpa(a, b);
    // Minimum distance over a fine time grid around the analytic tcpa.
    double best = 1e300, t_best = 0;
    for (double t = c.tcpa - 50.0; t <= c.tcpa + 50.0; t += 0.01) {
      const double d = std::hypot(b.x + b.vx * t - a.x - a.vx * t, b.y + b.vy * t - a.y - a.vy * t);
      if (d < best) best = d, t_best = t;
    }
    EXPECT_NEAR(c.dcpa, best, 1e-3);
    EXPECT_NEAR(c.tcpa, t_best, 0.02);
    const cr::Cpa r = cr::cpa(b, a);
    EXPECT_NEAR(r.dcpa, c.dcpa, 1e-9);
    EXPECT_NEAR(r.tcpa, c.tcpa, 1e-9);
  }
}

TEST(Bearing, RelativeBearingAndAspect) {
  const auto own = ship(0, 0, 90, 5);      // heading east
  const auto tgt = ship(1000, 0, 180, 5);  // due north of own, heading south
  EXPECT_NEAR(cr::bearing(own, tgt), 0.0, 1e-12);
  EXPECT_NEAR(cr::relative_bearing(own, tgt), deg2rad(-90), 1e-12);  // on own port beam
  EXPECT_NEAR(cr::aspect(own, tgt), 0.0, 1e-12);                     // dead ahead of target
  // The heading, when known, is the reference instead of the course.
  auto own_h = own;
  own_h.heading = deg2rad(80);
  EXPECT_NEAR(cr::relative_bearing(own_h, tgt), deg2rad(-80), 1e-12);
}

struct Case {
  const char* name;
  cr::ShipKinematics own, tgt;
  EncounterType own_view, target_view;  // what each ship must see
};

TEST(Classify, CanonicalEncountersFromBothShips) {
  const cr::ColregParams p;
  const Case cases[] = {
      {"head-on", ship(0, 0, 0, 5), ship(3000, 50, 180, 5), EncounterType::kHeadOn, EncounterType::kHeadOn},
      {"crossing from starboard", ship(0, 0, 0, 5), ship(1500, 1500, 270, 5), EncounterType::kCrossingGiveWay,
       EncounterType::kCrossingStandOn},
      {"crossing from port", ship(0, 0, 0, 5), ship(1500, -1500, 90, 5), EncounterType::kCrossingStandOn,
       EncounterType::kCrossingGiveWay},
      {"overtaking", ship(0, 0, 0, 8), ship(1500, 10, 0, 3), EncounterType::kOvertaking, EncounterType::kOvertaken},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const cr::Assessment a = cr::assess(c.own, c.tgt, p);
    EXPECT_TRUE(a.risk);
    EXPECT_EQ(a.type, c.own_view) << cr::to_string(a.type);
    EXPECT_EQ(cr::classify(c.tgt, c.own, p), c.target_view);
  }
  EXPECT_EQ(cr::role_of(EncounterType::kHeadOn), cr::Role::kBothGiveWay);
  EXPECT_EQ(cr::role_of(EncounterType::kOvertaken), cr::Role::kStandOn);
}

TEST(Classify, NoRiskWhenOpeningFarWideOrLate) {
  cr::ColregParams p;
  // Opening: sector says head-on geometry behind us is impossible; use a target that passed.
  EXPECT_EQ(cr::classify(ship(0, 0, 0, 5), ship(-2000, 0, 0, 2), p), EncounterType::kNone);
  // Wide CPA (2 km > 0.7 NM) although the sector is head-on.
  const cr::Assessment wide = cr::assess(ship(0, 0, 0, 5), ship(3000, 2000, 180, 5), p);
  EXPECT_EQ(wide.type, EncounterType::kNone);
  EXPECT_FALSE(wide.risk);
  // Beyond d_COLREG.
  EXPECT_EQ(cr::classify(ship(0, 0, 0, 5), ship(20000, 0, 180, 5), p), EncounterType::kNone);
  p.d_colreg = std::numeric_limits<double>::infinity();
  p.tcpa_max = std::numeric_limits<double>::infinity();
  EXPECT_EQ(cr::classify(ship(0, 0, 0, 5), ship(20000, 0, 180, 5), p), EncounterType::kHeadOn);
}

TEST(Classify, SectorBoundariesFollowThetaH) {
  cr::ColregParams p;
  // Target 10 deg on the starboard bow, heading reciprocal-ish: head-on with head_on_sector = 22.5 deg,
  // a crossing with the DNV theta14 = 5 deg.
  const double b = deg2rad(10);
  const auto own = ship(0, 0, 0, 5);
  const auto tgt = ship(3000 * std::cos(b), 3000 * std::sin(b), 190, 5);
  EXPECT_EQ(cr::classify_sectors(cr::relative_bearing(own, tgt), cr::aspect(own, tgt), p), EncounterType::kHeadOn);
  p.head_on_sector = deg2rad(5);
  EXPECT_EQ(cr::classify_sectors(cr::relative_bearing(own, tgt), cr::aspect(own, tgt), p),
            EncounterType::kCrossingGiveWay);
}

TEST(Params, DnvSettingsAndValidation) {
  const auto p = cr::ColregParams::from_dnv_settings(mpgc::testing::shared_data("encounters/dnv/encounter_settings.json"));
  EXPECT_NEAR(p.abaft_beam, deg2rad(22.5), 1e-12);
  EXPECT_NEAR(p.head_on_sector, deg2rad(5.0), 1e-12);
  EXPECT_NEAR(p.overtake_aspect, deg2rad(67.5), 1e-12);
  EXPECT_NEAR(p.crossing_aspect, deg2rad(5.0), 1e-12);
  EXPECT_THROW(cr::ColregParams::from_dnv_settings("/nonexistent/settings.json"), std::runtime_error);
  cr::ColregParams bad;
  bad.head_on_sector = std::nan("");
  try {
    bad.validate();
    FAIL() << "NaN head_on_sector accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("head_on_sector"), std::string::npos);
  }
  bad = cr::ColregParams{};
  bad.cpa_risk = -1;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(Classify, NonFiniteKinematicsThrow) {
  auto tgt = ship(1000, 0, 180, 5);
  tgt.vx = std::numeric_limits<double>::infinity();
  EXPECT_THROW(cr::assess(ship(0, 0, 0, 5), tgt, cr::ColregParams{}), std::invalid_argument);
}

// best_escape: the widest single manoeuvre bounds what a start allows (issue 18).
TEST(BestEscape, HeadOnShipIsKeptAtItsRangeByTurningAwayAtOnce) {
  const cr::ShipKinematics own{0, 0, 5, 0}, tgt{3704, 0, -5, 0};
  cr::EscapeParams p;
  const cr::Escape e = cr::best_escape(own, {tgt}, p);
  // Turned round instantly the own ship runs ahead of it at the same speed: the range never closes.
  EXPECT_NEAR(e.min_distance, 3704.0, 1e-6);
  EXPECT_NEAR(std::fabs(e.alteration), mpgc::geo::kPi, 1e-9);
  EXPECT_GT(e.alteration, 0.0);  // the tie of +-180 deg goes to starboard
  EXPECT_EQ(e.target, 0);
  // Holding on is a collision: the escape is the manoeuvre, not the course held.
  EXPECT_NEAR(cr::cpa(own, tgt).dcpa, 0.0, 1e-9);
}

TEST(BestEscape, ATurnThatTakesTimeAllowsLessThanAnInstantOne) {
  const cr::ShipKinematics own{0, 0, 5, 0}, a{3000, 800, -5, 0}, b{-2000, 2500, 4, -2};
  cr::EscapeParams p;
  p.speed_fractions = {1.0, 0.5};
  const double instant = cr::best_escape(own, {a, b}, p).min_distance;
  p.turn_radius = 600.0;
  const cr::Escape slow = cr::best_escape(own, {a, b}, p);
  EXPECT_LE(slow.min_distance, instant);
  EXPECT_GT(slow.min_distance, 0.0);
  // Starboard only: never a port alteration, and never more than with both sides.
  cr::EscapeParams stb = p;
  stb.starboard_only = true;
  const cr::Escape s = cr::best_escape(own, {a, b}, stb);
  EXPECT_GE(s.alteration, 0.0);
  EXPECT_LE(s.min_distance, slow.min_distance);
  // A planner's reach: no alteration beyond max_alteration, and never wider than without it.
  cr::EscapeParams reach = p;
  reach.max_alteration = mpgc::geo::deg2rad(30.0);
  const cr::Escape r = cr::best_escape(own, {a, b}, reach);
  EXPECT_LE(std::fabs(r.alteration), reach.max_alteration + 1e-9);
  EXPECT_LE(r.min_distance, slow.min_distance);
  reach.max_alteration = -0.1;
  EXPECT_THROW(cr::best_escape(own, {a, b}, reach), std::invalid_argument);
  // A start already inside a distance never allows more than the range now.
  const cr::ShipKinematics close{400, 0, -5, 0};
  EXPECT_LE(cr::best_escape(own, {a, close}, p).min_distance, 400.0 + 1e-9);
}

TEST(BestEscape, BadInputIsNamedAndNoTargetsIsOpenWater) {
  const cr::ShipKinematics own{0, 0, 5, 0};
  cr::EscapeParams p;
  EXPECT_TRUE(std::isinf(cr::best_escape(own, {}, p).min_distance));
  p.speed_fractions = {0.0};
  EXPECT_THROW(cr::best_escape(own, {}, p), std::invalid_argument);
  p = {};
  p.turn_radius = std::nan("");
  EXPECT_THROW(cr::best_escape(own, {}, p), std::invalid_argument);
  p = {};
  EXPECT_THROW(cr::best_escape(own, {cr::ShipKinematics{std::nan(""), 0, 0, 0}}, p), std::invalid_argument);
}
