// The guidance component's configuration and news without DDS (node.hpp): what main.cpp used to
// do inline, tested here directly.
#include <gtest/gtest.h>

#include "mpgc/guidance_control/node.hpp"
#include "mpgc/testing_params.hpp"

namespace gc = mpgc::guidance_control;

namespace {

gc::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  return mpgc::testing::declared<gc::NodeParams>(gc::declare, overrides);
}

TEST(GuidanceNode, DefaultsAreTheControllersAndTheSpeedMapIsParsed) {
  const gc::NodeParams p = declared();
  const gc::GuidanceControlParams d;
  EXPECT_DOUBLE_EQ(p.rate, 2.0);
  EXPECT_DOUBLE_EQ(p.gc.follower.lookahead, d.follower.lookahead);
  EXPECT_EQ(p.speed_map, gc::format_speed_map(d.speed));
  const gc::GuidanceControlParams c = gc::controller_params(declared({"speed.map=0:0,4:50,8:100"}));
  EXPECT_EQ(c.speed.map_speed, (std::vector<double>{0, 4, 8}));
  EXPECT_EQ(c.speed.map_rpm, (std::vector<double>{0, 50, 100}));
  EXPECT_DOUBLE_EQ(c.heading.kp, d.heading.kp);  // no Nomoto K: the gains as given
  EXPECT_THROW(gc::controller_params(declared({"speed.map=fast"})), std::invalid_argument);
}

TEST(GuidanceNode, NomotoKPlacesTheHeadingPid) {
  const gc::NodeParams p = declared({"heading.nomoto_K=0.05", "heading.nomoto_T=60", "heading.omega_n=0.05"});
  const gc::GuidanceControlParams c = gc::controller_params(p);
  const auto expected = gc::tune_heading_pid({0.05, 60}, 0.05, 1.0, p.gc.heading, 20.0);
  EXPECT_DOUBLE_EQ(c.heading.kp, expected.kp);
  EXPECT_DOUBLE_EQ(c.heading.ki, expected.ki);
  EXPECT_NE(c.heading.kp, p.gc.heading.kp);
}

TEST(GuidanceNode, ModeOrDetailChangesAreNewsOnce) {
  gc::ModeNews news;
  gc::Status s;
  EXPECT_FALSE(news.changed(s));  // idle, as at the start
  s.mode = gc::Mode::Following;
  EXPECT_TRUE(news.changed(s));
  EXPECT_FALSE(news.changed(s));
  s.detail = "no plan";
  EXPECT_TRUE(news.changed(s));
}

}  // namespace
