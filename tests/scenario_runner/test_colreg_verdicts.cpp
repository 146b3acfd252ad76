// COLREG verdicts from ground truth on synthetic two-ship encounters (NTNU scale, s = 1: stage
// ranges 2500 / 1100 / 200 m, minimum CPA 100 m) and on the five NTNU canonical scenarios.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <string>

#include "mpgc/testing.hpp"
#include "synthetic.hpp"

namespace sr = mpgc::scenario_runner;
using mpgc::colreg::EncounterType;
using mpgc::colreg::Role;
using mpgc::geo::deg2rad;
using mpgc::geo::kPi;
using sr::Side;
using sr::Verdict;
using sr::synthetic::Order;
using sr::synthetic::sail;

namespace {

sr::EncounterResult one(const sr::RunRecord& run, const sr::EvaluationParams& p = {}) {
  const auto e = sr::evaluate_encounters(run, p);
  EXPECT_EQ(e.size(), 1u);
  return e.at(0);
}

// Head-on: own ship north from the origin, target south from 4 km ahead, both 7 m/s. The own
// ship alters 35 deg at t = 120 s (range 2320 m, after the encounter started at 2500 m).
sr::RunRecord head_on(double turn) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{120, turn, 7}}, t);
  auto tgt = sail(1, 10, 4000, 0, kPi, 7, {}, t);
  return sr::synthetic::run_of(t, own, {tgt});
}

}  // namespace

TEST(ColregVerdicts, HeadOnStarboardTurnIsCompliant) {
  const auto e = one(head_on(deg2rad(35)));
  EXPECT_TRUE(e.encountered);
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_EQ(e.role, Role::kBothGiveWay);
  EXPECT_NEAR(e.t_start, 108.0, 1.0);  // range 4000 - 14 t < 2500
  EXPECT_EQ(e.manoeuvre_side, Side::kStarboard);
  EXPECT_NEAR(e.max_starboard_change, deg2rad(35), 1e-9);
  EXPECT_EQ(e.turned_starboard, Verdict::kPass);
  EXPECT_EQ(e.passing_side, Side::kPort);
  EXPECT_EQ(e.passed_port_to_port, Verdict::kPass);
  EXPECT_GT(e.cpa, 100.0);
  EXPECT_TRUE(e.compliant);
}

TEST(ColregVerdicts, HeadOnPortTurnIsNotCompliant) {
  const auto e = one(head_on(deg2rad(-35)));
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_EQ(e.manoeuvre_side, Side::kPort);
  EXPECT_EQ(e.turned_starboard, Verdict::kFail);
  EXPECT_EQ(e.passing_side, Side::kStarboard);
  EXPECT_EQ(e.passed_port_to_port, Verdict::kFail);
  EXPECT_FALSE(e.compliant);
}

TEST(ColregVerdicts, HeadOnWithoutManoeuvreIsNotCompliant) {
  const auto t = sr::synthetic::times(400, 1.0);
  // Offset 150 m to port of the target's line: passes safely but without turning.
  auto own = sail(0, 10, 0, 0, 0, 7, {}, t);
  auto tgt = sail(1, 10, 4000, -150, kPi, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_EQ(e.manoeuvre_side, Side::kNone);
  EXPECT_TRUE(std::isnan(e.t_manoeuvre));
  EXPECT_EQ(e.turned_starboard, Verdict::kFail);
  EXPECT_EQ(e.passed_port_to_port, Verdict::kPass);
  EXPECT_NEAR(e.cpa, 150.0, 1e-6);
  EXPECT_FALSE(e.compliant);
}

// Crossing: own ship north from the origin, target west from (2000, 2000): collision course at
// 7 m/s each; the target is 45 deg on the own starboard bow, so the own ship gives way.
TEST(ColregVerdicts, GiveWayCrossingPassingAsternIsCompliant) {
  const auto t = sr::synthetic::times(700, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{40, deg2rad(60), 7}}, t);
  auto tgt = sail(1, 10, 2000, 2000, -kPi / 2, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kCrossingGiveWay);
  EXPECT_EQ(e.role, Role::kGiveWay);
  EXPECT_NEAR(e.dcpa_start, 0.0, 1e-6);
  EXPECT_EQ(e.turned_starboard, Verdict::kPass);
  EXPECT_FALSE(e.bow_crossing > 0.0);
  EXPECT_EQ(e.not_crossed_ahead, Verdict::kPass);
  EXPECT_TRUE(e.compliant);
}

// Rule 8(b): the 60 deg alteration is readily apparent (>= 30 deg); a 15 deg one is not, and the
// encounter is then not compliant, though it turned to starboard and passed astern.
TEST(ColregVerdicts, GiveWayAlterationIsReadilyApparentOnlyWhenLarge) {
  const auto t = sr::synthetic::times(700, 1.0);
  auto tgt = sail(1, 10, 2000, 2000, -kPi / 2, 7, {}, t);
  const auto big = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{40, deg2rad(60), 7}}, t), {tgt}));
  EXPECT_EQ(big.readily_apparent, Verdict::kPass);
  const auto small = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{40, deg2rad(15), 7}}, t), {tgt}));
  EXPECT_EQ(small.readily_apparent, Verdict::kFail);
  EXPECT_EQ(small.turned_starboard, Verdict::kPass);
  EXPECT_FALSE(small.compliant);
  // A speed reduction of 60 % is apparent too.
  const auto slow = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{40, 0, 2.8}}, t), {tgt}));
  EXPECT_EQ(slow.readily_apparent, Verdict::kPass);
  // Stand-on: not a give-way situation.
  const auto so = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {}, t), {sail(1, 10, 2000, -2000, kPi / 2, 7, {}, t)}));
  EXPECT_EQ(so.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(so.readily_apparent, Verdict::kNotApplicable);
}

TEST(ColregVerdicts, GiveWayCrossingAheadIsNotCompliant) {
  const auto t = sr::synthetic::times(700, 1.0);
  // Speeds up to 14 m/s at t = 40 s and crosses the target's line 2000 - 7 * 162.9 = 860 m ahead.
  auto own = sail(0, 10, 0, 0, 0, 7, {{40, 0, 14}}, t);
  auto tgt = sail(1, 10, 2000, 2000, -kPi / 2, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kCrossingGiveWay);
  EXPECT_NEAR(e.bow_crossing, 2000.0 - 7.0 * (40.0 + (2000.0 - 280.0) / 14.0), 1.0);
  EXPECT_EQ(e.not_crossed_ahead, Verdict::kFail);
  EXPECT_EQ(e.turned_starboard, Verdict::kFail);
  EXPECT_FALSE(e.compliant);
}

// Crossing stand-on: target from (2000, -2000) heading east, on the own port bow.
sr::EncounterResult stand_on(const std::vector<Order>& orders) {
  const auto t = sr::synthetic::times(500, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, orders, t);
  auto tgt = sail(1, 10, 2000, -2000, kPi / 2, 7, {}, t);
  return one(sr::synthetic::run_of(t, own, {tgt}));
}

TEST(ColregVerdicts, StandOnHoldingCourseUntilStage3IsCompliant) {
  // Range falls below r_colregs_3_max = 400 m at t = (2828 - 400) / 9.9 = 245 s; the own ship
  // turns at 250 s.
  const auto e = stand_on({{250, deg2rad(40), 7}});
  EXPECT_EQ(e.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e.role, Role::kStandOn);
  EXPECT_EQ(e.held_course_and_speed, Verdict::kPass);
  EXPECT_EQ(e.turned_starboard, Verdict::kNotApplicable);
  EXPECT_TRUE(e.compliant);
}

TEST(ColregVerdicts, StandOnChangingCourseEarlyIsFlagged) {
  const auto e = stand_on({{60, deg2rad(20), 7}});  // range 2240 m: stage 2
  EXPECT_EQ(stand_on({{190, deg2rad(40), 7}}).held_course_and_speed, Verdict::kFail);  // 947 m: not yet stage 3
  EXPECT_EQ(e.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e.held_course_and_speed, Verdict::kFail);
  EXPECT_FALSE(e.compliant);
}

TEST(ColregVerdicts, StandOnChangingSpeedEarlyIsFlagged) {
  const auto e = stand_on({{60, 0, 4}});
  EXPECT_EQ(e.held_course_and_speed, Verdict::kFail);
  EXPECT_FALSE(e.compliant);
  // A small speed change (10 % < delta_speed_md = 20 %) is not a manoeuvre.
  EXPECT_EQ(stand_on({{60, 0, 6.3}}).held_course_and_speed, Verdict::kPass);
}

// Stage 3 is a time too: overtaken from 300 m astern (inside r_colregs_3_max = 400 m) by a ship
// 1 m/s faster, the CPA is 300 s away, far more than the 57 s the own ship takes to sail 400 m:
// the stand-on holds until then.
TEST(ColregVerdicts, OvertakenSlowlyFromCloseAsternStillHolds) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto tgt = sail(1, 10, -300, 0, 0, 8, {}, t);
  auto hold = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{250, deg2rad(40), 7}}, t), {tgt}));
  EXPECT_EQ(hold.situation, EncounterType::kOvertaken);
  EXPECT_NEAR(hold.tcpa_start, 300.0, 1e-6);
  EXPECT_EQ(hold.held_course_and_speed, Verdict::kPass);  // turned at TCPA 50 s
  auto early = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{100, deg2rad(40), 7}}, t), {tgt}));
  EXPECT_EQ(early.held_course_and_speed, Verdict::kFail);  // turned at TCPA 200 s
}

TEST(ColregVerdicts, OvertakingKeepsClearOnlyWithEnoughCpa) {
  const auto t = sr::synthetic::times(600, 1.0);
  auto tgt = sail(1, 10, 1000, 0, 0, 3, {}, t);
  // Straight behind: collision course; then a 20 deg alteration at 30 s gives a wide pass.
  auto straight = sail(0, 10, 0, 0, 0, 8, {}, t);
  auto e = one(sr::synthetic::run_of(t, straight, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kOvertaking);
  EXPECT_EQ(e.role, Role::kGiveWay);
  EXPECT_LT(e.cpa, 1.0);
  EXPECT_EQ(e.kept_clear, Verdict::kFail);
  auto wide = sail(0, 10, 0, 0, 0, 8, {{30, deg2rad(20), 8}, {120, 0, 8}}, t);
  e = one(sr::synthetic::run_of(t, wide, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kOvertaking);
  EXPECT_GT(e.cpa, 100.0);
  EXPECT_EQ(e.kept_clear, Verdict::kPass);
  EXPECT_EQ(e.passing_side, Side::kPort);
  // Clear, but 20 deg is not "readily apparent" (rule 8(b), delta_course_app 30 deg).
  EXPECT_EQ(e.readily_apparent, Verdict::kFail);
  EXPECT_FALSE(e.compliant);
  auto apparent = sail(0, 10, 0, 0, 0, 8, {{30, deg2rad(35), 8}, {120, 0, 8}}, t);
  e = one(sr::synthetic::run_of(t, apparent, {tgt}));
  EXPECT_EQ(e.kept_clear, Verdict::kPass);
  EXPECT_EQ(e.readily_apparent, Verdict::kPass);
  EXPECT_TRUE(e.compliant);
}

TEST(ColregVerdicts, FarOrOpeningTargetsAreNoEncounter) {
  const auto t = sr::synthetic::times(100, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {}, t);
  auto far = sail(1, 10, 10000, 0, kPi, 7, {}, t);       // never inside 2500 m
  auto opening = sail(2, 10, -500, 0, kPi, 7, {}, t);    // astern, going away
  const auto e = sr::evaluate_encounters(sr::synthetic::run_of(t, own, {far, opening}), {});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_FALSE(e[0].encountered);
  EXPECT_NEAR(e[0].cpa, 10000.0 - 1400.0, 1e-6);
  EXPECT_TRUE(e[1].encountered);
  EXPECT_EQ(e[1].situation, EncounterType::kNone);
  EXPECT_TRUE(e[1].compliant);
  EXPECT_EQ(e[1].turned_starboard, Verdict::kNotApplicable);
}

TEST(ColregVerdicts, ScaledToKvlcc2) {
  const auto p = sr::EvaluationParams::scaled_to(320.0);
  EXPECT_DOUBLE_EQ(p.scale, 32.0);
  EXPECT_DOUBLE_EQ(p.r_min_cpa, 3200.0);  // = d_safety = 10 Lpp of seed 000
  EXPECT_DOUBLE_EQ(p.r_colregs_2_max, 80000.0);
  EXPECT_DOUBLE_EQ(p.r_colregs_3_max, 12800.0);  // 4 r_min_cpa = 40 Lpp
  EXPECT_NEAR(p.manoeuvre_window(), 2.0 / 0.3 * 32.0, 1e-9);
  EXPECT_DOUBLE_EQ(p.colreg.d_colreg, 80000.0);
  EXPECT_DOUBLE_EQ(p.delta_course_md, deg2rad(2.0));  // angles do not scale
  EXPECT_THROW(sr::EvaluationParams::scaled_to(0.0), std::invalid_argument);
  EXPECT_THROW(sr::EvaluationParams::scaled_to(std::nan("")), std::invalid_argument);

  // The head-on case at 32 x the size and the same speeds: same verdicts.
  const double s = 32.0;
  const auto t = sr::synthetic::times(400 * s, 10.0);
  auto own = sail(0, 320, 0, 0, 0, 7, {{120 * s, deg2rad(35), 7}}, t, deg2rad(3.0) / s);
  auto tgt = sail(1, 320, 4000 * s, 0, kPi, 7, {}, t, deg2rad(3.0) / s);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}, 3200.0), p);
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_EQ(e.turned_starboard, Verdict::kPass);
  EXPECT_EQ(e.passed_port_to_port, Verdict::kPass);
}

TEST(ColregVerdicts, DefaultsAreTheNtnuEvaluatorThresholds) {
  const YAML::Node y = YAML::LoadFile(mpgc::testing::shared_data("encounters/ntnu_canonical/evaluator.yaml"))["evaluator"];
  const sr::EvaluationParams p;
  EXPECT_DOUBLE_EQ(p.r_colregs_2_max, y["r_colregs_2_max"].as<double>());
  // The one departure (evaluation.hpp): the stand-on may act from 4 r_min_cpa, not NTNU's 11.
  EXPECT_DOUBLE_EQ(y["r_colregs_3_max"].as<double>(), 1100.0);
  EXPECT_DOUBLE_EQ(p.r_colregs_3_max, 4.0 * p.r_min_cpa);
  EXPECT_DOUBLE_EQ(p.r_colregs_4_max, y["r_colregs_4_max"].as<double>());
  EXPECT_DOUBLE_EQ(p.r_pref, y["r_pref"].as<double>());
  EXPECT_DOUBLE_EQ(p.r_min_cpa, y["r_min_cpa"].as<double>());
  EXPECT_DOUBLE_EQ(p.r_nm, y["r_nm"].as<double>());
  EXPECT_DOUBLE_EQ(p.r_col_cpa, y["r_col_cpa"].as<double>());
  EXPECT_DOUBLE_EQ(p.epsilon_d_course, deg2rad(y["epsilon_d_course"].as<double>()));
  EXPECT_DOUBLE_EQ(p.delta_course_md, deg2rad(y["delta_course_md"].as<double>()));
  EXPECT_DOUBLE_EQ(p.delta_speed_md, y["delta_speed_md"].as<double>());
  EXPECT_DOUBLE_EQ(p.delta_course_app, deg2rad(y["delta_course_app"].as<double>()));
  EXPECT_DOUBLE_EQ(p.delta_speed_reduction_app, y["delta_speed_reduction_app"].as<double>());
  EXPECT_DOUBLE_EQ(p.theta_sm_lim, deg2rad(y["theta_sm_lim"].as<double>()));
}

// The five NTNU canonical scenarios hold initial states only (csog_state = [north, east, speed,
// course deg], UTM metres): sail them on straight lines for t_end and check the classification
// at the start of the encounter against the file's type.
TEST(ColregVerdicts, NtnuCanonicalScenariosClassifiedAtStart) {
  const std::map<std::string, EncounterType> expected = {
      {"HO", EncounterType::kHeadOn},          {"CR_GW", EncounterType::kCrossingGiveWay},
      {"CR_SO", EncounterType::kCrossingStandOn}, {"OT_ing", EncounterType::kOvertaking},
      {"OT_en", EncounterType::kOvertaken}};
  for (const char* file : {"head_on", "crossing_give_way", "crossing_stand_on", "overtaking", "overtaken"}) {
    SCOPED_TRACE(file);
    const YAML::Node y =
        YAML::LoadFile(mpgc::testing::shared_data(std::string("encounters/ntnu_canonical/") + file + ".yaml"));
    const auto t = sr::synthetic::times(y["t_end"].as<double>(), y["dt_sim"].as<double>());
    std::vector<sr::ShipTrack> ships;
    for (const auto& s : y["ship_list"]) {
      const auto c = s["csog_state"].as<std::vector<double>>();
      ASSERT_EQ(c.size(), 4u);
      ships.push_back(sail(s["id"].as<std::uint32_t>(), 10, c[0], c[1], deg2rad(c[3]), c[2], {}, t));
    }
    ASSERT_EQ(ships.size(), 2u);
    ships[1].id = 1;
    const auto e = one(sr::synthetic::run_of(t, ships[0], {ships[1]}));
    EXPECT_TRUE(e.encountered);
    EXPECT_EQ(e.situation, expected.at(y["type"].as<std::string>()))
        << "classified " << mpgc::colreg::to_string(e.situation);
    EXPECT_LT(e.dcpa_start, 1.0);  // all five are set on collision courses
    // Straight lines: no manoeuvre, so every give-way situation is non-compliant and every
    // stand-on one compliant.
    EXPECT_EQ(e.compliant, e.role == Role::kStandOn || e.role == Role::kNone);
  }
}

TEST(ColregVerdicts, StandOnIsExcusedWhileGivingWayToAnother) {
  // Target 1 crosses from starboard (own ship gives way), target 2 from port (own ship stands
  // on). Turning to starboard early for target 1 is what the rules ask; it cannot also hold
  // course for target 2, so that verdict is not applicable rather than failed.
  const auto t = sr::synthetic::times(700, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{40, deg2rad(60), 7}}, t);
  auto gw = sail(1, 10, 2000, 2000, -kPi / 2, 7, {}, t);
  auto so = sail(2, 10, 2000, -2000, kPi / 2, 7, {}, t);
  const auto e = sr::evaluate_encounters(sr::synthetic::run_of(t, own, {gw, so}), {});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].situation, EncounterType::kCrossingGiveWay);
  EXPECT_EQ(e[0].turned_starboard, Verdict::kPass);
  EXPECT_TRUE(e[0].compliant);
  EXPECT_EQ(e[1].situation, EncounterType::kCrossingStandOn);
  EXPECT_TRUE(e[1].conflicting_obligation);
  EXPECT_EQ(e[1].held_course_and_speed, Verdict::kNotApplicable);
  // What is judged instead: passed at a safe distance (8(d)), not to port (17(c)).
  EXPECT_EQ(e[1].kept_clear, Verdict::kPass);
  EXPECT_EQ(e[1].not_turned_to_port, Verdict::kPass);
  EXPECT_TRUE(e[1].compliant);
  // The same conflict resolved by a port turn fails the give-way encounter (rule 15). Made 2.5 km
  // from the stand-on ship, beyond its stage 3 (400 m), it is no action under 17(a)(ii) for that
  // one, so not a 17(c) turn (StandOnTurningToPortInStage3FailsRule17c is one).
  auto port = sail(0, 10, 0, 0, 0, 7, {{40, deg2rad(-60), 7}}, t);
  const auto ep = sr::evaluate_encounters(sr::synthetic::run_of(t, port, {gw, so}), {});
  EXPECT_FALSE(ep[0].compliant);
  EXPECT_EQ(ep[1].not_turned_to_port, Verdict::kPass);
  // Alone, the same early turn fails the stand-on verdict.
  const auto alone = one(sr::synthetic::run_of(t, own, {so}));
  EXPECT_FALSE(alone.conflicting_obligation);
  EXPECT_EQ(alone.held_course_and_speed, Verdict::kFail);
}

// Rule 17(c): the stand-on ship acting in its stage 3 (from about 245 s here) for a ship crossing
// from port must not turn to port; a starboard turn there is what 17(c) leaves it.
TEST(ColregVerdicts, StandOnTurningToPortInStage3FailsRule17c) {
  const auto t = sr::synthetic::times(700, 1.0);
  auto so = sail(1, 10, 2000, -2000, kPi / 2, 7, {}, t);
  const auto port = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{250, deg2rad(-40), 7}}, t), {so}));
  ASSERT_EQ(port.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(port.held_course_and_speed, Verdict::kPass);
  EXPECT_EQ(port.not_turned_to_port, Verdict::kFail);
  EXPECT_FALSE(port.compliant);
  const auto stbd = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{250, deg2rad(40), 7}}, t), {so}));
  EXPECT_EQ(stbd.not_turned_to_port, Verdict::kPass);
}

// Rule 17(c) forbids a port turn "for a vessel on her own port side". A crossing ship that has
// crossed ahead (300 m) and is still closing on the starboard bow (from about 141 s here; CPA
// 119 m at 164 s) is no longer on the port side: a port turn at 150 s turns away from it.
TEST(ColregVerdicts, APortTurnOnceTheCrossingShipIsOnTheStarboardBowIsNot17c) {
  const auto t = sr::synthetic::times(500, 1.0);
  auto so = sail(1, 10, 2000, -700, 3 * kPi / 4, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{150, deg2rad(-40), 7}}, t), {so}));
  ASSERT_EQ(e.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e.held_course_and_speed, Verdict::kPass);
  EXPECT_EQ(e.not_turned_to_port, Verdict::kPass);
}

// The side is judged where the port turn begins, not at the manoeuvre detector's window start. With
// the window of the DNV suite's scale (60 s here: delta_course_md 2 deg at 2/60 deg/s) the window
// of the port turn above starts at 91 s, with the ship still 15 deg on the port bow; the turn
// begins at 150 s with it on the starboard bow: not 17(c). A turn begun with the ship on the port
// bow still is (the stage-3 case above, judged with the same long window).
TEST(ColregVerdicts, Rule17cJudgesTheSideWhereTheTurnBeginsNotAtTheDetectorsWindowStart) {
  sr::EvaluationParams p;
  p.epsilon_d_course = p.delta_course_md / 60.0;
  ASSERT_NEAR(p.manoeuvre_window(), 60.0, 1e-9);
  const auto t = sr::synthetic::times(500, 1.0);
  auto so = sail(1, 10, 2000, -700, 3 * kPi / 4, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {{150, deg2rad(-40), 7}}, t), {so}), p);
  ASSERT_EQ(e.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e.not_turned_to_port, Verdict::kPass);
  const auto t2 = sr::synthetic::times(700, 1.0);
  auto so2 = sail(1, 10, 2000, -2000, kPi / 2, 7, {}, t2);
  const auto port = one(sr::synthetic::run_of(t2, sail(0, 10, 0, 0, 0, 7, {{250, deg2rad(-40), 7}}, t2), {so2}), p);
  ASSERT_EQ(port.situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(port.not_turned_to_port, Verdict::kFail);
}

// The encounter begins with the risk of collision, not with the range: the own ship heads east,
// the target 2 km north sails south (no risk), then the own ship turns north onto the target's
// reciprocal (head-on) and later alters to starboard. Classified when the range first fell below
// r_colregs_2_max it was no encounter ("not judged"); now it is the head-on it became.
TEST(ColregVerdicts, AnEncounterBeginsWhenTheRiskOfCollisionDoes) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto tgt = sail(1, 10, 2000, 300, kPi, 7, {}, t);
  auto own = sail(0, 10, 0, 0, kPi / 2, 7, {{40, 0.0, 7}, {110, deg2rad(35), 7}}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_GT(e.t_start, 40.0);
  EXPECT_EQ(e.turned_starboard, Verdict::kPass);
  EXPECT_TRUE(e.compliant);
  // Holding on for the meeting without the starboard turn is judged, and fails.
  const auto held = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, kPi / 2, 7, {{40, 0.0, 7}}, t), {tgt}));
  EXPECT_EQ(held.situation, EncounterType::kHeadOn);
  EXPECT_EQ(held.turned_starboard, Verdict::kFail);
  // A target that never is a risk stays no encounter.
  const auto never = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, kPi / 2, 7, {}, t), {tgt}));
  EXPECT_EQ(never.situation, EncounterType::kNone);
}

// Each encounter is judged by the manoeuvre made for it: a small wobble is no manoeuvre (below
// theta_sm_lim), so the 40 deg starboard turn after a 4 deg port wobble is the one judged.
TEST(ColregVerdicts, AWobbleBeforeTheTurnIsNotTheManoeuvre) {
  const auto t = sr::synthetic::times(700, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{36, deg2rad(-4), 7}, {60, deg2rad(40), 7}}, t);
  auto tgt = sail(1, 10, 2000, 2000, -kPi / 2, 7, {}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kCrossingGiveWay);
  EXPECT_GE(e.manoeuvres, 2);
  EXPECT_EQ(e.manoeuvre_side, Side::kStarboard);
  EXPECT_GT(e.t_manoeuvre, 60.0);
  EXPECT_NEAR(e.max_starboard_change, deg2rad(44), deg2rad(0.5));  // from the course held before it
  EXPECT_EQ(e.turned_starboard, Verdict::kPass);
  EXPECT_TRUE(e.compliant);
}

// A turn made while a target was no risk of collision (it had turned away itself) is not judged
// for it: the head-on target turns 60 deg to its starboard early, then the own ship turns 40 deg
// to port for its route; before, that port turn was the head-on encounter's "manoeuvre".
TEST(ColregVerdicts, ATurnMadeWhenTheTargetWasNoRiskIsNotJudgedForIt) {
  const auto t = sr::synthetic::times(400, 1.0);
  auto own = sail(0, 10, 0, 0, 0, 7, {{140, deg2rad(-40), 7}}, t);
  auto tgt = sail(1, 10, 4000, 0, kPi, 7, {{115, kPi + deg2rad(60), 7}}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_EQ(e.situation, EncounterType::kHeadOn);
  EXPECT_EQ(e.manoeuvres, 0);
  EXPECT_TRUE(std::isnan(e.t_manoeuvre));
  EXPECT_EQ(e.manoeuvre_side, Side::kNone);
}

// Two ships crossing from port, both stand-on: the nearer reaches stage 3 first and the own ship
// acts for it; it cannot hold course for the farther one any longer, whose hold ends there too.
TEST(ColregVerdicts, ActingForOneStandOnTargetEndsTheHoldForAnother) {
  const auto t = sr::synthetic::times(700, 1.0);
  // Near: from (2000, -2000) heading east (stage 3 at 245 s). Far: from (2300, -2300), also on a
  // collision course (encounter from 76 s, stage 3 at 288 s). The own ship turns at 250 s.
  auto near = sail(1, 10, 2000, -2000, kPi / 2, 7, {}, t);
  auto far = sail(2, 10, 2300, -2300, kPi / 2, 7, {}, t);
  auto own = sail(0, 10, 0, 0, 0, 7, {{250, deg2rad(40), 7}}, t);
  const auto e = sr::evaluate_encounters(sr::synthetic::run_of(t, own, {near, far}), {});
  ASSERT_EQ(e.size(), 2u);
  EXPECT_EQ(e[0].situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e[0].held_course_and_speed, Verdict::kPass);
  ASSERT_EQ(e[1].situation, EncounterType::kCrossingStandOn);
  EXPECT_EQ(e[1].held_course_and_speed, Verdict::kPass);  // alone it would fail:
  EXPECT_LE(e[1].t_hold_end, e[0].t_hold_end + 1.0);
  const auto alone = one(sr::synthetic::run_of(t, own, {far}));
  EXPECT_EQ(alone.held_course_and_speed, Verdict::kFail);
}

// A stand-on target met already inside stage 3 (here a ship overtaking from 350 m astern, TCPA 50 s)
// may be acted for from the start, so the own ship no longer holds course for a crossing ship
// whose encounter overlaps it: the overtaken encounter's hold ends at its start (it had no end,
// and the crossing ship's hold was judged as if the own ship were free to keep it).
TEST(ColregVerdicts, AStandOnTargetInStage3FromTheStartEndsTheHoldForAnother) {
  const auto t = sr::synthetic::times(700, 1.0);
  auto astern = sail(1, 10, -350, 0, 0, 14, {}, t);
  auto crossing = sail(2, 10, 1700, -1700, kPi / 2, 7, {}, t);  // from port, collision course, stage 3 ~ 200 s
  auto own = sail(0, 10, 0, 0, 0, 7, {{10, deg2rad(40), 7}}, t);
  const auto e = sr::evaluate_encounters(sr::synthetic::run_of(t, own, {astern, crossing}), {});
  ASSERT_EQ(e.size(), 2u);
  ASSERT_EQ(e[0].situation, EncounterType::kOvertaken);
  EXPECT_NEAR(e[0].t_hold_end, 0.0, 1e-9);
  ASSERT_EQ(e[1].situation, EncounterType::kCrossingStandOn);
  EXPECT_TRUE(e[1].conflicting_obligation);
  EXPECT_EQ(e[1].held_course_and_speed, Verdict::kNotApplicable);
  EXPECT_EQ(e[1].not_turned_to_port, Verdict::kPass);
  // Alone, the crossing ship's hold fails on the same turn.
  EXPECT_EQ(one(sr::synthetic::run_of(t, own, {crossing})).held_course_and_speed, Verdict::kFail);
}

// The hold lasts until the CPA at the latest: a give-way ship that acted early may leave the range
// above stage 3 to the end, and past the CPA the stand-on ship is free to go on its way.
TEST(ColregVerdicts, TheHoldEndsAtTheClosestApproach) {
  const auto t = sr::synthetic::times(800, 1.0);
  // From the port bow on a collision course, it gives way at 60 s (60 deg to starboard, to 150
  // deg), passing astern at about 1 km; the own ship turns after the CPA.
  auto tgt = sail(1, 10, 2000, -2000, kPi / 2, 7, {{60, deg2rad(150), 7}}, t);
  const auto e0 = one(sr::synthetic::run_of(t, sail(0, 10, 0, 0, 0, 7, {}, t), {tgt}));
  ASSERT_EQ(e0.situation, EncounterType::kCrossingStandOn);
  auto own = sail(0, 10, 0, 0, 0, 7, {{e0.t_cpa + 20.0, deg2rad(40), 7}}, t);
  const auto e = one(sr::synthetic::run_of(t, own, {tgt}));
  EXPECT_GT(e.cpa, 400.0);
  EXPECT_LE(e.t_hold_end, e.t_cpa + 1.0);
  EXPECT_EQ(e.held_course_and_speed, Verdict::kPass);
  // Before the CPA the same turn fails.
  auto early = sail(0, 10, 0, 0, 0, 7, {{e0.t_cpa - 60.0, deg2rad(40), 7}}, t);
  EXPECT_EQ(one(sr::synthetic::run_of(t, early, {tgt})).held_course_and_speed, Verdict::kFail);
}
