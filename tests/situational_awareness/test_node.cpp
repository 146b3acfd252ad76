// The situational awareness component's configuration and own-ship picture without DDS
// (node.hpp): what main.cpp used to do inline, tested here directly.
#include <gtest/gtest.h>

#include <cmath>

#include "mpgc/geo/angles.hpp"
#include "mpgc/testing_params.hpp"
#include "mpgc/situational_awareness/node.hpp"

namespace sa = mpgc::sa;

namespace {

sa::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  return mpgc::testing::declared<sa::NodeParams>(sa::declare, overrides);
}

TEST(SaNode, ColregSectorsAreGivenInDegrees) {
  const sa::NodeParams p = declared({"colreg.head_on_sector=5", "colreg.d_colreg=5000"});
  EXPECT_EQ(p.origin_source, "nav");
  const auto c = sa::colreg_params(p);
  EXPECT_DOUBLE_EQ(c.head_on_sector, mpgc::geo::deg2rad(5.0));
  EXPECT_DOUBLE_EQ(c.abaft_beam, mpgc::geo::deg2rad(22.5));
  EXPECT_DOUBLE_EQ(c.overtake_aspect, mpgc::geo::deg2rad(67.5));
  EXPECT_DOUBLE_EQ(c.d_colreg, 5000);
  EXPECT_DOUBLE_EQ(p.jump_gate().timeout, p.own_timeout);
}

TEST(SaNode, OwnShipIsPredictedOverItsAgeOrSaidStale) {
  const sa::NodeParams p = declared({"own.timeout=5"});
  EXPECT_EQ(sa::own_problem(p, false, 0), "no own state yet");
  EXPECT_EQ(sa::own_problem(p, true, 6), "own state stale");
  EXPECT_EQ(sa::own_problem(p, true, 5), "");
  const auto k = sa::own_at({100, 200, 4, M_PI / 2, 1.5, true, true}, 2.0);
  EXPECT_NEAR(k.x, 100, 1e-9);
  EXPECT_NEAR(k.y, 208, 1e-9);
  EXPECT_NEAR(k.vy, 4, 1e-9);
  EXPECT_DOUBLE_EQ(k.heading, 1.5);
  const auto still = sa::own_at({100, 200, 4, 0, 1.5, false, false}, 2.0);
  EXPECT_DOUBLE_EQ(still.x, 100);  // no valid velocity: not moved
  EXPECT_DOUBLE_EQ(still.vx, 0);
  EXPECT_TRUE(std::isnan(still.heading));
}

}  // namespace
