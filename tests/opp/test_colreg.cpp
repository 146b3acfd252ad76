// The §5 predicate on canonical two-ship geometries (own ship at the origin heading north).
#include <gtest/gtest.h>

#include "mpgc/opp/colreg.hpp"

namespace opp = mpgc::opp;

namespace {
const opp::ColregParams kP;
const opp::Vec2 kOwn{0, 0}, kNorth{6, 0};
}  // namespace

TEST(Colreg, HeadOnRequiresTargetOnPort) {
  // Target ahead, reciprocal course, slightly to starboard -> non-compliant (eq. 19).
  auto c = opp::colreg_check(kOwn, kNorth, {2000, 50}, {-6, 0}, kP);
  EXPECT_EQ(c.situation, opp::ColregSituation::kHeadOn);
  EXPECT_FALSE(c.compliant);
  c = opp::colreg_check(kOwn, kNorth, {2000, -50}, {-6, 0}, kP);
  EXPECT_EQ(c.situation, opp::ColregSituation::kHeadOn);
  EXPECT_TRUE(c.compliant);
  // 30 deg off reciprocal is beyond theta_h = 22.5 deg: no head-on.
  c = opp::colreg_check(kOwn, kNorth, {2000, 50}, {-6 * std::cos(0.52), -6 * std::sin(0.52)}, kP);
  EXPECT_NE(c.situation, opp::ColregSituation::kHeadOn);
}

TEST(Colreg, CrossingFromStarboardGivesWay) {
  // Target from starboard heading west; meets own route at N = 1000.
  // Own first at x_c (target still 1500 m east) -> non-compliant (eq. 18).
  auto c = opp::colreg_check(kOwn, kNorth, {1000, 1500}, {0, -6}, kP);
  EXPECT_EQ(c.situation, opp::ColregSituation::kCrossing);
  EXPECT_FALSE(c.compliant);
  // Target first (only 300 m from x_c) -> own passes astern: compliant.
  c = opp::colreg_check(kOwn, kNorth, {1000, 300}, {0, -6}, kP);
  EXPECT_TRUE(c.compliant);
}

TEST(Colreg, CrossingFromPortStandsOn) {
  // Target from port heading east: own first is the compliant case.
  auto c = opp::colreg_check(kOwn, kNorth, {1000, -1500}, {0, 6}, kP);
  EXPECT_EQ(c.situation, opp::ColregSituation::kCrossing);
  EXPECT_TRUE(c.compliant);
  c = opp::colreg_check(kOwn, kNorth, {1000, -300}, {0, 6}, kP);
  EXPECT_FALSE(c.compliant);
}

TEST(Colreg, OvertakingMustNotCrossAhead) {
  // Own heading 10 deg to starboard, a slower target ahead to starboard on a northerly course:
  // routes meet ahead, own first -> crossing the overtaken vessel's route ahead: non-compliant.
  const opp::Vec2 v{6 * std::cos(0.17), 6 * std::sin(0.17)};
  auto c = opp::colreg_check(kOwn, v, {300, 200}, {3, 0}, kP);
  EXPECT_EQ(c.situation, opp::ColregSituation::kOvertaking);
  EXPECT_FALSE(c.compliant);
  // Parallel courses never cross: compliant.
  c = opp::colreg_check(kOwn, kNorth, {300, 200}, {3, 0}, kP);
  EXPECT_TRUE(c.compliant);
}

TEST(Colreg, StoppedTargetHasNoRoute) {
  auto c = opp::colreg_check(kOwn, kNorth, {1000, 0}, {0, 0}, kP);
  EXPECT_TRUE(c.compliant);
  EXPECT_EQ(c.situation, opp::ColregSituation::kNone);
}
