// The §5 predicate on canonical two-ship geometries (own ship at the origin heading north).
#include <gtest/gtest.h>

#include <random>

#include "mpgc/opp/colreg.hpp"

namespace opp = mpgc::opp;

namespace {
const opp::ColregParams kP;
const opp::Vec2 kOwn{0, 0}, kNorth{6, 0};
}  // namespace

TEST(Colreg, HeadOnRequiresTargetOnPort) {
  // Target ahead, reciprocal course, slightly to starboard -> non-compliant (eq. 19).
  auto c = opp::colreg_check(kOwn, kNorth, {2000, 50}, {-6, 0}, kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_FALSE(c.compliant);
  c = opp::colreg_check(kOwn, kNorth, {2000, -50}, {-6, 0}, kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_TRUE(c.compliant);
  // 30 deg off reciprocal is beyond head_on_sector = 22.5 deg: no head-on.
  c = opp::colreg_check(kOwn, kNorth, {2000, 50}, {-6 * std::cos(0.52), -6 * std::sin(0.52)}, kP);
  EXPECT_NE(c.situation, mpgc::colreg::EncounterType::kHeadOn);
}

TEST(Colreg, CrossingFromStarboardGivesWay) {
  // Target from starboard heading west; meets own route at N = 1000.
  // Own first at x_c (target still 1500 m east) -> non-compliant (eq. 18).
  auto c = opp::colreg_check(kOwn, kNorth, {1000, 1500}, {0, -6}, kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kCrossingGiveWay);
  EXPECT_FALSE(c.compliant);
  // Target first (only 300 m from x_c) -> own passes astern: compliant.
  c = opp::colreg_check(kOwn, kNorth, {1000, 300}, {0, -6}, kP);
  EXPECT_TRUE(c.compliant);
}

TEST(Colreg, CrossingFromPortStandsOn) {
  // Target from port heading east: own first is the compliant case.
  auto c = opp::colreg_check(kOwn, kNorth, {1000, -1500}, {0, 6}, kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kCrossingStandOn);
  EXPECT_TRUE(c.compliant);
  c = opp::colreg_check(kOwn, kNorth, {1000, -300}, {0, 6}, kP);
  EXPECT_FALSE(c.compliant);
}

TEST(Colreg, OvertakingMustNotCrossAhead) {
  // Own heading 10 deg to starboard, a slower target ahead to starboard on a northerly course:
  // routes meet ahead, own first -> crossing the overtaken vessel's route ahead: non-compliant.
  const opp::Vec2 v{6 * std::cos(0.17), 6 * std::sin(0.17)};
  auto c = opp::colreg_check(kOwn, v, {300, 200}, {3, 0}, kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kOvertaking);
  EXPECT_FALSE(c.compliant);
  // Parallel courses never cross: compliant.
  c = opp::colreg_check(kOwn, kNorth, {300, 200}, {3, 0}, kP);
  EXPECT_TRUE(c.compliant);
}

TEST(Colreg, StoppedTargetHasNoRoute) {
  auto c = opp::colreg_check(kOwn, kNorth, {1000, 0}, {0, 0}, kP);
  EXPECT_TRUE(c.compliant);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kNone);
}

// --- obligations pinned for the whole encounter (colreg_check_pinned) ------------------------------

namespace {
opp::Vec2 heading(double deg, double speed = 6.0) {
  const double r = deg * 3.14159265358979323846 / 180.0;
  return {speed * std::cos(r), speed * std::sin(r)};
}
opp::PinnedEncounter pinned(opp::Obligation o, double course0_deg = 0.0, int side = 0) {
  return {o, course0_deg * 3.14159265358979323846 / 180.0, side};
}
}  // namespace

TEST(ColregPinned, HeadOnStaysHeadOnAfterAPortTurn) {
  // The target ahead on a reciprocal course, slightly to starboard: non-compliant head-on for the
  // per-leg model. After a 30 deg turn to port it is no head-on for that model (beyond head_on_sector)
  // and the routes no longer meet ahead: "compliant", to be passed starboard to starboard.
  const opp::Vec2 v = heading(-30), w{-6, 0}, y{4000, 300};
  EXPECT_FALSE(opp::colreg_check(kOwn, kNorth, y, w, kP).compliant);
  EXPECT_TRUE(opp::colreg_check(kOwn, v, y, w, kP).compliant);
  const auto c = opp::colreg_check_pinned(kOwn, v, y, w, pinned(opp::Obligation::kHeadOn), kP);
  EXPECT_EQ(c.situation, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_FALSE(c.compliant);
  // To starboard with the target on the port side: compliant; the target on starboard: not.
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(30), {4000, -100}, w, pinned(opp::Obligation::kHeadOn), kP).compliant);
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(30), {4000, 3000}, w, pinned(opp::Obligation::kHeadOn), kP).compliant);
  // Within the port tolerance (5 deg) of the pinned course: still compliant.
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-4), {4000, -800}, w, pinned(opp::Obligation::kHeadOn), kP).compliant);
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-6), {4000, -800}, w, pinned(opp::Obligation::kHeadOn), kP).compliant);
}

TEST(ColregPinned, OpeningLegIsClear) {
  // The head-on target has passed down the port side: any leg on which the range opens is clear,
  // also one back to port.
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-40), {-1500, -800}, {-6, 0}, pinned(opp::Obligation::kHeadOn), kP)
                  .compliant);
}

TEST(ColregPinned, GiveWayMayNotCrossAheadNorTurnToPort) {
  // Target from starboard heading west, meeting the own route at N = 1000; own first at x_c.
  const opp::Vec2 w{0, -6}, y{1000, 1500};
  const auto gw = pinned(opp::Obligation::kCrossingGiveWay, 0.0, -1);
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, kNorth, y, w, gw, kP).compliant);
  // A port turn: the per-leg model sees the target on its starboard quarter, routes meeting
  // ahead of both with own first... pinned, any port alteration is refused.
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-45), y, w, gw, kP).compliant);
  // Starboard, towards the target's stern (routes do not meet ahead of both): compliant.
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(60), y, w, gw, kP).compliant);
  // Once across the target's track astern of it, the obligation is met: even a port leg is clear.
  const opp::Vec2 own_across{1100, 1600};  // north of the target's track (it was south), behind it (east)
  EXPECT_TRUE(opp::colreg_check_pinned(own_across, heading(-60), {1000, 500}, w, gw, kP).compliant);
}

TEST(ColregPinned, OvertakingMustNotCrossAhead) {
  const opp::Vec2 v{6 * std::cos(0.17), 6 * std::sin(0.17)};
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, v, {300, 200}, {3, 0}, pinned(opp::Obligation::kOvertaking), kP).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, kNorth, {300, 200}, {3, 0}, pinned(opp::Obligation::kOvertaking), kP).compliant);
}

TEST(ColregPinned, NoneIsThePerLegModel) {
  for (const opp::Vec2 y : {opp::Vec2{2000, 50}, opp::Vec2{2000, -50}, opp::Vec2{1000, 1500}})
    EXPECT_EQ(opp::colreg_check_pinned(kOwn, kNorth, y, {-6, 0}, {}, kP).compliant,
              opp::colreg_check(kOwn, kNorth, y, {-6, 0}, kP).compliant);
}

// Rule 8(b): hold the pinned course or alter by at least apparent_turn (30 deg) + its margin (2 deg)
// while closing.
TEST(ColregPinned, AnAlterationMustBeReadilyApparent) {
  const opp::Vec2 w{-6, 0}, y{6000, -300};  // head-on, slightly to port
  const auto ho = pinned(opp::Obligation::kHeadOn);
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, kNorth, y, w, ho, kP));      // holding course
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(4), y, w, ho, kP));  // within the tolerance
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(12), y, w, ho, kP));  // a small alteration
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(29), y, w, ho, kP));
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(31), y, w, ho, kP));  // short of the margin
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(33), y, w, ho, kP));
  // Opening: passed, any course back to the route.
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(12), {-2000, -800}, w, ho, kP));
  // Once the alteration has begun, it is completed: holding course0 is no longer enough.
  auto begun = ho;
  begun.acted = true;
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, kNorth, y, w, begun, kP));
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(20), y, w, begun, kP));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(33), y, w, begun, kP));
  // Once made, the band is lifted (e.g. back towards the route while still closing).
  begun.completed = true;
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(12), y, w, begun, kP));
  // Overtaking: either side, but apparent.
  const auto ot = pinned(opp::Obligation::kOvertaking);
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(-15), {3000, 0}, {3, 0}, ot, kP));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(-35), {3000, 0}, {3, 0}, ot, kP));
  // Disabled with apparent_turn = 0; no duty (per-leg model): nothing to check.
  opp::ColregParams off = kP;
  off.apparent_turn = 0.0;
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(12), y, w, ho, off));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(12), y, w, {}, kP));
}

// Rule 14(a): within act_range, a head-on leg that would pass within risk_cpa has altered to
// starboard by head_on_turn; holding course is enough only farther off or passing wider. Rule
// 8(b): a speed halved from the encounter's start is readily apparent at any course.
TEST(ColregPinned, AHeadOnShipNearAltersToStarboard) {
  const opp::Vec2 w{-6, 0}, y{1500, -150};  // head-on, 150 m to port, 1.5 km off
  auto ho = pinned(opp::Obligation::kHeadOn);
  ho.speed0 = 6.0;
  opp::ColregParams p = kP;
  p.risk_cpa = 200.0;
  p.act_range = 2000.0;
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, kNorth, y, w, ho, p));  // holding: would pass 150 m off
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(33), y, w, ho, p));
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(-3), y, w, ho, p));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, kNorth, {3000, -150}, w, ho, p));  // beyond act_range
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, kNorth, {1500, -400}, w, ho, p));  // passing 400 m off
  // Halved speed (and the 5 % margin): a 15 deg starboard turn is readily apparent; holding course at
  // half speed is still no alteration of course (rule 14).
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(15), y, w, ho, p));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(15, 2.6), y, w, ho, p));
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(15, 2.9), y, w, ho, p));  // 52 %: short of the margin
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(0, 2.9), y, w, ho, p));
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(15, 3.5), y, w, ho, p));
  p.apparent_slowdown = 0.0;
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(15, 2.6), y, w, ho, p));
  // An alteration made and given up near the ship: back on the meeting course, refused again.
  ho.acted = ho.completed = true;
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, kNorth, y, w, ho, p));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(15), y, w, ho, p));
}

// Rule 17(c): a crossing stand-on pinned: when the own ship acts, not to port for a ship on its
// port side; to starboard by a readily apparent amount.
TEST(ColregPinned, AStandOnShipActingDoesNotTurnToPort) {
  const opp::Vec2 w{0, 6}, y{3000, -2500};  // from the port bow, heading east
  const auto so = pinned(opp::Obligation::kCrossingStandOn);
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-30), y, w, so, kP).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(40), y, w, so, kP).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, kNorth, y, w, so, kP).compliant);
  // 17(c) binds the action for this ship, taken when it is near (port_turn_range): 3.9 km off, a
  // port turn (made for another ship) is not such action.
  opp::ColregParams near = kP;
  near.port_turn_range = 3000.0;
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-30), y, w, so, near).compliant);
  near.port_turn_range = 4000.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-30), y, w, so, near).compliant);
  // Ahead of the beam, a port leg is refused even where the range does not close (the ship 1 km on
  // the port bow: turning round its bow at constant range is turning toward it).
  const opp::Vec2 bow{866, -500}, w5{5, 0};
  ASSERT_LE(opp::dot(bow, heading(-75) - w5), 0.0);  // not closing
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-75), bow, w5, so, near).compliant);
  // ... if the leg passes it within risk_cpa (here the 1 km it is off), or it is a risk now
  // (or on the course held: its CPA there is 500 m).
  auto bow_wide = near;
  bow_wide.risk_cpa = 450.0;
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-75), bow, w5, so, bow_wide).compliant);
  auto so_risk = so;
  so_risk.at_risk_17c = true;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-75), bow, w5, so_risk, bow_wide).compliant);
  bow_wide.risk_cpa = 1100.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-75), bow, w5, so, bow_wide).compliant);
  // Crossed ahead to the starboard bow, or abaft the beam, it is passed: a port leg goes astern of it.
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-30), {866, 500}, {0, 7}, so, near).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-30), {-900, -300}, {0, 0.5}, so, near).compliant);
  // Altered 40 deg to starboard (for another ship) with the crossing ship closing on the port beam,
  // turning back toward the route is turning to port for it (DNV 27, 30): refused while it closes
  // on the port side of the course held, allowed along that course or once it is on the starboard side.
  auto held = so;
  held.held_17c = 40.0 * mpgc::geo::kPi / 180.0;
  const opp::Vec2 beam{1286, -1532}, wne{4, 5};  // 2 km on the port beam of course 40, heading north-east
  ASSERT_GT(opp::dot(beam, heading(20) - wne), 0.0);  // closing
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(20), beam, wne, so, near).compliant);  // no reference yet
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(20), beam, wne, held, near).compliant);
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(0), beam, wne, held, near).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(38), beam, wne, held, near).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(20), {1000, 2000}, {-5, -5}, held, near).compliant);
  // A port leg that passes it farther than risk_cpa (380 m here) is no turn for it.
  auto wide = near;
  wide.risk_cpa = 300.0;
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(20), beam, wne, held, wide).compliant);
  wide.risk_cpa = 500.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(20), beam, wne, held, wide).compliant);
  // ... unless the ship is a risk of collision now (on the course held): then any closing port leg is.
  held.at_risk_17c = true;
  wide.risk_cpa = 300.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(20), beam, wne, held, wide).compliant);
  // A port leg on which the range opens is judged as begun port_turn_lead earlier on the course
  // held, where the guidance starts the turn: 500 m on the port beam, opening at 6 m/s to the
  // west, a 45 deg port leg is clear where it begins but not 300 m earlier (the range then still
  // closing along it); 1200 m off it is clear from there too.
  const opp::Vec2 west{0, -6};
  auto lead = near;
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-45), {0, -500}, west, so, lead).compliant);
  lead.port_turn_lead = 300.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-45), {0, -500}, west, so, lead).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-45), {0, -1200}, west, so, lead).compliant);
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(10), {0, -500}, west, so, lead).compliant);  // not to port
  // A port leg that opens the range is still a turn for a ship at risk on the course held (its
  // CPA ahead within risk_cpa): 2 km ahead, 100 m to port, crossing to starboard at 5 m/s.
  auto ahead_risk = near;
  ahead_risk.risk_cpa = 1300.0;
  const opp::Vec2 crossing{2000, -100}, east5{0, 5};
  ASSERT_LE(opp::dot(crossing, heading(-100) - east5), 0.0);  // opening along the port leg
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-100), crossing, east5, so, ahead_risk).compliant);
  ahead_risk.risk_cpa = 300.0;  // its CPA on the course held, 1.2 km, is no risk then
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-100), crossing, east5, so, ahead_risk).compliant);
  // The course held is held at the encounter's speed (speed0): slowing to 1.5 m/s lets the ship
  // 1.9 km on the port bow pass ahead 1.1 km off, but at 6 m/s its CPA is 40 m: a port turn made
  // with the slowing is a turn for it.
  auto slow_p = near;
  slow_p.risk_cpa = 800.0;
  const opp::Vec2 bow2{1500, -1200}, e5{0, 5};
  EXPECT_TRUE(opp::colreg_check_pinned(kOwn, heading(-30, 1.5), bow2, e5, so, slow_p).compliant);  // speed0 unknown
  auto so6 = so;
  so6.speed0 = 6.0;
  EXPECT_FALSE(opp::colreg_check_pinned(kOwn, heading(-30, 1.5), bow2, e5, so6, slow_p).compliant);
  // Acting, its alteration is readily apparent too (rule 8(b) is for any action).
  EXPECT_FALSE(opp::colreg_check_apparent(kOwn, heading(12), y, w, so, kP));
  EXPECT_TRUE(opp::colreg_check_apparent(kOwn, heading(35), y, w, so, kP));
  EXPECT_FALSE(opp::is_duty(opp::Obligation::kCrossingStandOn));
  EXPECT_FALSE(opp::is_duty(opp::Obligation::kOvertaken));
  EXPECT_TRUE(opp::is_duty(opp::Obligation::kHeadOn));
}

TEST(ColregPinned, OneLegObjectAlongALegAnswersAsAFreshOneAtEachPoint) {
  // ValidityChecker checks a leg at many points with one PinnedLeg, whose course and directions are
  // taken on first use: the answers must not depend on which point (or which check) asked first.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  opp::ColregParams p = kP;
  p.port_turn_range = 6000;
  p.port_turn_lead = 400;
  p.risk_cpa = 1500;
  p.act_range = 5000;
  const opp::Obligation kinds[] = {opp::Obligation::kNone, opp::Obligation::kHeadOn, opp::Obligation::kCrossingGiveWay,
                                   opp::Obligation::kOvertaking, opp::Obligation::kCrossingStandOn,
                                   opp::Obligation::kOvertaken};
  int differing_answers = 0;
  for (int k = 0; k < 3000; ++k) {
    opp::PinnedEncounter e = pinned(kinds[k % 6], 180.0 * u(rng), u(rng) < 0 ? -1 : 1);
    e.speed0 = 4.0 + 2.0 * u(rng);
    e.acted = u(rng) < 0;
    e.at_risk_17c = u(rng) < -0.5;
    if (u(rng) < 0) e.held_17c = 0.5 * u(rng);
    const opp::Vec2 v = heading(180.0 * u(rng), 3.0 + 3.0 * u(rng)), w = heading(180.0 * u(rng), 3.0 + 3.0 * u(rng));
    const opp::PinnedLeg leg(v, e);
    bool first = true, first_apparent = true;
    for (int i = 0; i < 8; ++i) {
      const opp::Vec2 x{4000 * u(rng), 4000 * u(rng)}, y{4000 * u(rng), 4000 * u(rng)};
      // Every other leg asks its first question of a throwaway object: the shared one then meets
      // its first use at a later point, and by the other check.
      const auto shared = (i + k) % 2 ? opp::colreg_check_pinned(x, y, w, leg, p)
                                      : opp::colreg_check_pinned(x, y, w, opp::PinnedLeg(v, e), p);
      const auto fresh = opp::colreg_check_pinned(x, v, y, w, e, p);
      EXPECT_EQ(shared.compliant, fresh.compliant);
      EXPECT_EQ(shared.situation, fresh.situation);
      EXPECT_EQ(opp::colreg_check_apparent(x, y, w, leg, p), opp::colreg_check_apparent(x, v, y, w, e, p));
      if (i > 0 && shared.compliant != first) ++differing_answers;
      if (i > 0 && opp::colreg_check_apparent(x, y, w, leg, p) != first_apparent) ++differing_answers;
      if (i == 0) first = shared.compliant, first_apparent = opp::colreg_check_apparent(x, y, w, leg, p);
    }
  }
  EXPECT_GT(differing_answers, 1000);  // the points do reach different answers along one leg
}
