// EncounterMemory: obligations pinned when the risk of collision appears, kept through the own
// ship's manoeuvre, released once the target is passed.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "mpgc/opp/encounters.hpp"
#include "mpgc/opp/memory.hpp"

namespace opp = mpgc::opp;
namespace colreg = mpgc::colreg;

namespace {
constexpr double kDeg = 3.14159265358979323846 / 180.0;

colreg::ShipKinematics own_at(double x, double y, double course_deg, double speed = 6.0) {
  return colreg::ShipKinematics::from_course(x, y, course_deg * kDeg, speed);
}
opp::Target target(uint32_t id, double x, double y, double course_deg, double speed = 6.0) {
  return {id, {x, y}, {speed * std::cos(course_deg * kDeg), speed * std::sin(course_deg * kDeg)}, {}};
}
opp::EncounterMemoryParams params() {
  opp::EncounterMemoryParams p;
  p.cpa_risk = 1000;
  p.tcpa_max = 1800;
  p.release_range = 3000;
  return p;
}
}  // namespace

TEST(EncounterMemory, PinsAtRiskFarOutsideTheColregZone) {
  opp::EncounterMemory mem;
  // Head-on 12 km ahead (TCPA 1000 s), crossing from starboard, one far abeam with no risk.
  std::vector<opp::Target> ts{target(1, 12000, -200, 180), target(2, 6000, 6000, -90), target(3, 0, 20000, 0)};
  mem.update(params(), own_at(0, 0, 0), ts);
  EXPECT_EQ(ts[0].pinned.obligation, opp::Obligation::kHeadOn);
  EXPECT_EQ(ts[1].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  EXPECT_EQ(ts[1].pinned.track_side, -1);  // the own ship is south of the westbound target's track
  EXPECT_EQ(ts[2].pinned.obligation, opp::Obligation::kNone);
  EXPECT_NEAR(ts[0].pinned.course0, 0.0, 1e-12);
  EXPECT_EQ(mem.size(), 2u);
}

TEST(EncounterMemory, KeepsTheSituationThroughAManoeuvre) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 8000, -200, 180)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kHeadOn);
  // The own ship has turned 40 deg to port: re-assessed from scratch this is no head-on any more.
  std::vector<opp::Target> later{target(1, 6000, -200, 180)};
  mem.update(params(), own_at(500, -400, -40), later);
  EXPECT_EQ(later[0].pinned.obligation, opp::Obligation::kHeadOn);
  EXPECT_NEAR(later[0].pinned.course0, 0.0, 1e-12);  // the course at the encounter's start
}

TEST(EncounterMemory, ReleasesPassedTargetsAndForgetsLostTracks) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 8000, -200, 180), target(2, 6000, 6000, -90)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(mem.size(), 2u);
  // Target 1 passed down the port side and is opening abaft the beam; target 2 no longer tracked.
  std::vector<opp::Target> later{target(1, 3000, -1200, 180)};
  mem.update(params(), own_at(4000, 0, 0), later);
  EXPECT_EQ(later[0].pinned.obligation, opp::Obligation::kNone);
  EXPECT_EQ(mem.size(), 0u);
}

TEST(EncounterMemory, GiveWayHeldUntilAcrossTheTrackAstern) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(2, 6000, 6000, -90)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  // Own ship turned hard to starboard, range opening but still south of the track: held.
  std::vector<opp::Target> t1{target(2, 6000, 2000, -90)};
  mem.update(params(), own_at(4000, 1800, 120), t1);
  EXPECT_EQ(t1[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  // Across the track, astern of the target and opening: released.
  std::vector<opp::Target> t2{target(2, 6000, 0, -90)};
  mem.update(params(), own_at(6500, 2500, 30), t2);
  EXPECT_EQ(t2[0].pinned.obligation, opp::Obligation::kNone);
}

TEST(EncounterMemory, BadInputThrowsAndLeavesTheMemoryUnchanged) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 8000, -200, 180)};
  mem.update(params(), own_at(0, 0, 0), ts);
  std::vector<opp::Target> bad{target(1, 7000, -200, 180), target(9, std::nan(""), 0, 0)};
  EXPECT_THROW(mem.update(params(), own_at(0, 0, 0), bad), std::invalid_argument);
  EXPECT_EQ(mem.find(1).obligation, opp::Obligation::kHeadOn);
  auto p = params();
  p.cpa_risk = -1;
  EXPECT_THROW(mem.update(p, own_at(0, 0, 0), ts), std::invalid_argument);
  p = params();
  p.tcpa_max = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mem.update(p, own_at(0, 0, 0), ts), std::invalid_argument);
  EXPECT_EQ(mem.size(), 1u);
}

TEST(EncounterMemory, ATargetThatTurnsStartsANewEncounter) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(2, 6000, 6000, -90)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  // 10 deg is the same encounter; 60 deg, now heading straight for the own ship, is a new one.
  std::vector<opp::Target> t1{target(2, 5900, 5500, -100)};
  mem.update(params(), own_at(500, 0, 0), t1);
  EXPECT_EQ(t1[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  std::vector<opp::Target> t2{target(2, 6000, 500, 180)};
  mem.update(params(), own_at(1000, 0, 0), t2);
  EXPECT_EQ(t2[0].pinned.obligation, opp::Obligation::kHeadOn);
}

// Rule 8(b) by speed: a slow-down begun for a ship it gives way to (head-on) marks the action as
// begun; halved, as made; back to speed on the meeting course with the risk remaining, given up.
TEST(EncounterMemory, ASlowDownIsAnActionBegunMadeAndGivenUp) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 8000, -200, 180)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kHeadOn);
  std::vector<opp::Target> t1{target(1, 7000, -200, 180)};
  mem.update(params(), own_at(100, 0, 0, 5.0), t1);  // 17 %: within what a turn loses
  EXPECT_FALSE(t1[0].pinned.acted);
  std::vector<opp::Target> t2{target(1, 6500, -200, 180)};
  mem.update(params(), own_at(200, 0, 0, 4.2), t2);  // 30 %: begun, not yet apparent
  EXPECT_TRUE(t2[0].pinned.acted);
  EXPECT_FALSE(t2[0].pinned.completed);
  std::vector<opp::Target> t3{target(1, 6000, -200, 180)};
  mem.update(params(), own_at(300, 0, 0, 2.9), t3);  // 52 %: made
  EXPECT_TRUE(t3[0].pinned.completed);
  std::vector<opp::Target> t4{target(1, 5000, -200, 180)};
  mem.update(params(), own_at(400, 0, 0, 6.0), t4);  // back to speed, still closing 200 m off
  EXPECT_FALSE(t4[0].pinned.completed);
  EXPECT_TRUE(t4[0].pinned.acted);
  // Disabled (0): a slow-down is no action by itself.
  opp::EncounterMemoryParams off = params();
  off.acted_slowdown = off.apparent_slowdown = 0.0;
  opp::EncounterMemory mem2;
  std::vector<opp::Target> u0{target(1, 8000, -200, 180)};
  mem2.update(off, own_at(0, 0, 0), u0);
  std::vector<opp::Target> u1{target(1, 6000, -200, 180)};
  mem2.update(off, own_at(300, 0, 0, 2.9), u1);
  EXPECT_FALSE(u1[0].pinned.acted);
  EXPECT_FALSE(u1[0].pinned.completed);
}

// A target that turns as the rules ask of it (head-on: to starboard, rule 14) keeps the
// encounter: the own ship still owes its part. A turn to port is unexpected: re-assessed.
TEST(EncounterMemory, ATargetTurningAsTheRulesAskKeepsTheEncounter) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 8000, -200, 180)};
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kHeadOn);
  std::vector<opp::Target> stbd{target(1, 7000, -300, 180 + 35)};  // its starboard: course 215
  mem.update(params(), own_at(300, 0, 0), stbd);
  EXPECT_EQ(stbd[0].pinned.obligation, opp::Obligation::kHeadOn);
  EXPECT_NEAR(stbd[0].pinned.course0, 0.0, 1e-12);
  EXPECT_FALSE(stbd[0].pinned.acted);  // the own ship has not turned yet
  std::vector<opp::Target> after{target(1, 6500, -400, 180 + 35)};
  mem.update(params(), own_at(500, 50, 12), after);  // own course 12 deg: its alteration has begun
  EXPECT_TRUE(after[0].pinned.acted);
  EXPECT_FALSE(after[0].pinned.completed);
  std::vector<opp::Target> made{target(1, 6000, -500, 180 + 35)};
  mem.update(params(), own_at(700, 150, 31), made);  // 31 deg: the readily apparent alteration is made
  EXPECT_TRUE(made[0].pinned.completed);
  // Given up: back on course0 with the head-on ship still on a collision course, it is to be made again.
  std::vector<opp::Target> back{target(1, 5500, 1700, 180 + 35)};  // CPA 11 m in 422 s
  mem.update(params(), own_at(900, 150, 2), back);
  EXPECT_FALSE(back[0].pinned.completed);
  EXPECT_TRUE(back[0].pinned.acted);
  opp::EncounterMemory mem2;
  std::vector<opp::Target> t0{target(1, 8000, -200, 180)};
  mem2.update(params(), own_at(0, 0, 0), t0);
  std::vector<opp::Target> port{target(1, 7000, -300, 180 - 35)};  // to its port: course 145, no risk
  mem2.update(params(), own_at(300, 0, 0), port);
  EXPECT_EQ(port[0].pinned.obligation, opp::Obligation::kNone);
  // A crossing target from port (own ship stand-on) that gives way to starboard: still stood on.
  opp::EncounterMemory mem3;
  std::vector<opp::Target> so{target(3, 6000, -6000, 90)};
  mem3.update(params(), own_at(0, 0, 0), so);
  ASSERT_EQ(so[0].pinned.obligation, opp::Obligation::kCrossingStandOn);
  std::vector<opp::Target> gives{target(3, 5800, -5500, 90 + 60)};
  mem3.update(params(), own_at(500, 0, 0), gives);
  EXPECT_EQ(gives[0].pinned.obligation, opp::Obligation::kCrossingStandOn);
}

// Rule 17(c)'s reference course follows the most starboard course held while the crossing ship
// closes on the port side within port_turn_range, and not beyond that range.
TEST(EncounterMemory, TheRule17cReferenceIsTheMostStarboardCourseHeldNearTheShip) {
  auto p = params();
  p.port_turn_range = 5000;
  opp::EncounterMemory mem;
  std::vector<opp::Target> far{target(3, 6000, -6000, 90)};  // 8.5 km off: beyond the range
  mem.update(p, own_at(0, 0, 0), far);
  ASSERT_EQ(far[0].pinned.obligation, opp::Obligation::kCrossingStandOn);
  EXPECT_TRUE(std::isnan(far[0].pinned.held_17c));
  std::vector<opp::Target> near{target(3, 4000, -2400, 90)};
  mem.update(p, own_at(1000, 0, 35), near);  // altered 35 deg to starboard for another ship
  EXPECT_NEAR(near[0].pinned.held_17c, 35 * kDeg, 1e-9);
  EXPECT_TRUE(near[0].pinned.at_risk_17c);
  EXPECT_FALSE(far[0].pinned.at_risk_17c);
  std::vector<opp::Target> back{target(3, 4000, -2000, 90)};
  mem.update(p, own_at(1200, 150, 10), back);  // coming back: the reference stays
  EXPECT_NEAR(back[0].pinned.held_17c, 35 * kDeg, 1e-9);
  // No risk of collision (its predicted CPA, 740 m, beyond cpa_risk): the reference does not follow.
  opp::EncounterMemory mem2;
  std::vector<opp::Target> far2{target(3, 6000, -6000, 90)};
  mem2.update(p, own_at(0, 0, 0), far2);
  p.cpa_risk = 500;
  std::vector<opp::Target> near2{target(3, 4000, -2400, 90)};
  mem2.update(p, own_at(1000, 0, 35), near2);
  EXPECT_TRUE(std::isnan(near2[0].pinned.held_17c));
  // Within the range but converging slowly (CPA 260 m in 1480 s, beyond the 830 s the own ship
  // takes to sail port_turn_range): not yet; once the CPA is that near in time, it does.
  p.cpa_risk = 1000;
  opp::EncounterMemory mem3;
  std::vector<opp::Target> slow{target(3, 4000, -2400, 60)};
  mem3.update(p, own_at(1000, 0, 35), slow);
  ASSERT_EQ(slow[0].pinned.obligation, opp::Obligation::kCrossingStandOn);
  EXPECT_FALSE(slow[0].pinned.at_risk_17c);
  EXPECT_TRUE(std::isnan(slow[0].pinned.held_17c));
  std::vector<opp::Target> later{target(3, 4000 + 6 * std::cos(60 * kDeg) * 700, -2400 + 6 * std::sin(60 * kDeg) * 700, 60)};
  mem3.update(p, own_at(1000 + 6 * std::cos(35 * kDeg) * 700, 6 * std::sin(35 * kDeg) * 700, 35), later);
  EXPECT_TRUE(later[0].pinned.at_risk_17c);
  EXPECT_NEAR(later[0].pinned.held_17c, 0.0, 1e-9);
  p.port_turn_range = 0;
  EXPECT_THROW(mem.update(p, own_at(1200, 150, 10), back), std::invalid_argument);
}

TEST(EncounterMemory, AGiveWayManoeuvreThatOpensTheRangeDoesNotEndTheEncounter) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(2, 6000, 6000, -90)};  // range 8.5 km, beyond release_range
  mem.update(params(), own_at(0, 0, 0), ts);
  ASSERT_EQ(ts[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  // Turned away (south): opening at 5.4 km, beyond release_range but inside the pinning range.
  std::vector<opp::Target> t1{target(2, 6000, 4000, -90)};
  mem.update(params(), own_at(2000, 300, 180), t1);
  EXPECT_EQ(t1[0].pinned.obligation, opp::Obligation::kCrossingGiveWay);
  // Opening beyond the range it was pinned at: over.
  std::vector<opp::Target> t2{target(2, 6000, 3000, -90)};
  mem.update(params(), own_at(-4000, 1500, 180), t2);
  EXPECT_EQ(t2[0].pinned.obligation, opp::Obligation::kNone);
}

// A restarted opp reads its memory back (memory.hpp): the same obligations after the manoeuvre
// as if it had never died.
TEST(PlannerMemory, ARestartedPlannerHoldsTheSameObligations) {
  opp::EncounterMemory mem;
  std::vector<opp::Target> ts{target(1, 12000, -200, 180), target(2, 6000, 6000, -90)};
  mem.update(params(), own_at(0, 0, 0), ts);
  const opp::PlannerMemory saved{1, 7, 1, {{0.5, 1.0 / 3.0}, {1000, 2000}}, mem.records()};
  const std::string path = ::testing::TempDir() + "/opp_memory_test.yaml";
  opp::save_memory(path, saved);
  const auto back = opp::load_memory(path);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->plan_id, 7u);
  ASSERT_EQ(back->last_path.size(), 2u);
  EXPECT_EQ(back->last_path[0].y, 1.0 / 3.0);  // exact: 17 digits
  opp::EncounterMemory restarted;
  restarted.restore(back->pinned);
  // Both memories judge the situation after a turn to starboard alike.
  std::vector<opp::Target> a{target(1, 11000, -200, 180), target(2, 5500, 5500, -90)}, b = a;
  mem.update(params(), own_at(500, 300, 40), a);
  restarted.update(params(), own_at(500, 300, 40), b);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pinned.obligation, b[i].pinned.obligation);
    EXPECT_EQ(a[i].pinned.course0, b[i].pinned.course0);
  }
  EXPECT_FALSE(opp::load_memory(path + ".none").has_value());
  std::remove(path.c_str());
}

TEST(PlannerMemory, AMalformedMemoryIsRefusedByName) {
  EXPECT_THROW(opp::memory_from_yaml("goal_id: 1\nplan_id: x\n", "m.yaml"), std::invalid_argument);
  EXPECT_THROW(opp::memory_from_yaml("[1, 2]", "m.yaml"), std::invalid_argument);
  const std::string bad_pin =
      "goal_id: 1\nplan_id: 2\nwarm_goal: 1\nlast_path: []\npinned: [{id: 3, obligation: 9, course0: 0, track_side: 1, "
      "target_course: 0, range0: 10}]\n";
  try {
    opp::memory_from_yaml(bad_pin, "m.yaml");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("m.yaml"), std::string::npos);
  }
  EXPECT_THROW(opp::memory_from_yaml("goal_id: 1\nplan_id: 2\nwarm_goal: 1\nlast_path: [[.nan, 0]]\npinned: []\n", "m"),
               std::invalid_argument);
  opp::EncounterMemory m;
  opp::PinnedRecord r{4, {opp::Obligation::kHeadOn, 0.0, 1, 0.0}, 100};
  EXPECT_THROW(m.restore({r, r}), std::invalid_argument);  // twice
}
