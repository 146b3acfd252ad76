#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/nav/jump_gate.hpp"

using namespace mpgc::geo;

TEST(Angles, WrapPiRangeAndIdentity) {
  EXPECT_DOUBLE_EQ(wrap_pi(kPi), kPi);  // (-pi, pi]: +pi stays
  EXPECT_DOUBLE_EQ(wrap_pi(-kPi), kPi);
  EXPECT_NEAR(wrap_pi(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_pi(-0.5), -0.5, 1e-15);
  EXPECT_NEAR(wrap_pi(2 * kPi + 0.25), 0.25, 1e-12);
  EXPECT_TRUE(std::isnan(wrap_pi(NAN)));
  EXPECT_TRUE(std::isnan(wrap_pi(INFINITY)));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-100, 100);
  for (int i = 0; i < 10000; ++i) {
    const double a = u(rng);
    const double w = wrap_pi(a);
    ASSERT_GT(w, -kPi);
    ASSERT_LE(w, kPi);
    ASSERT_NEAR(std::remainder(a - w, 2 * kPi), 0.0, 1e-9);
  }
}

TEST(Angles, DiffAndCourse) {
  EXPECT_NEAR(angle_diff(deg2rad(10), deg2rad(350)), deg2rad(20), 1e-12);
  EXPECT_NEAR(angle_diff(deg2rad(350), deg2rad(10)), deg2rad(-20), 1e-12);
  EXPECT_NEAR(course_of(1, 0), 0.0, 1e-15);          // north
  EXPECT_NEAR(course_of(0, 1), kPi / 2, 1e-15);      // east: clockwise from north
  EXPECT_NEAR(course_of(-1, 0), kPi, 1e-15);
  EXPECT_NEAR(course_of(0, -1), -kPi / 2, 1e-15);
}

TEST(Geodesy, NedAxesPointNorthAndEast) {
  const LocalNed ned({deg2rad(38.97), deg2rad(-76.45)});
  const auto north = ned.to_ned({deg2rad(38.98), deg2rad(-76.45)});
  EXPECT_NEAR(north.x, 1110.0, 5.0);  // 0.01 deg of latitude ~ 1.11 km
  EXPECT_NEAR(north.y, 0.0, 1e-6);
  const auto east = ned.to_ned({deg2rad(38.97), deg2rad(-76.44)});
  EXPECT_GT(east.y, 860.0);  // 0.01 deg of longitude at 39 N ~ 866 m
  EXPECT_LT(east.y, 870.0);
  EXPECT_NEAR(east.x, 0.0, 0.1);
}

TEST(Geodesy, RoundTripsExactlyOverFiftyKilometres) {
  const LocalNed ned({deg2rad(59.9), deg2rad(10.7)});  // Oslofjord, where the DNV set lives
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-50000, 50000);
  for (int i = 0; i < 2000; ++i) {
    const NorthEast p{u(rng), u(rng)};
    const auto back = ned.to_ned(ned.to_latlon(p));
    ASSERT_NEAR(back.x, p.x, 1e-6);
    ASSERT_NEAR(back.y, p.y, 1e-6);
  }
}

TEST(Geodesy, RejectsOutOfRangeAndNonFinite) {
  EXPECT_THROW(LocalNed({deg2rad(91), 0}), std::invalid_argument);
  const LocalNed ned({0.1, 0.1});
  EXPECT_THROW(ned.to_ned({NAN, 0}), std::invalid_argument);
  EXPECT_THROW(ned.to_ned({0, deg2rad(181)}), std::invalid_argument);
  EXPECT_THROW(ned.to_latlon({INFINITY, 0}), std::invalid_argument);
}

// nav/jump_gate.hpp: the state machine the bridge's fusion and guidance_control share.
TEST(JumpGate, RefusesImpossibleJumpsAndTakesAConfirmedNewPlace) {
  using mpgc::nav::JumpGate;
  JumpGate g({25.0, 30.0, 3.0});
  const int64_t s = 1'000'000'000;
  std::string why;
  EXPECT_EQ(g.check(0, 0, 0), JumpGate::Verdict::kTaken);  // the first fix is taken as it is
  EXPECT_EQ(g.check(50, 0, 1 * s), JumpGate::Verdict::kTaken);  // 50 m in 1 s <= 25 + 30
  EXPECT_EQ(g.check(50, 56, 2 * s, &why), JumpGate::Verdict::kJump);  // 56 m in 1 s > 55 m
  EXPECT_EQ(why, "position jumped 56.0 m (at most 55.0 m possible)");
  EXPECT_TRUE(g.jumped());
  EXPECT_EQ(g.check(50, 5, 2 * s), JumpGate::Verdict::kTaken);  // back where it can be
  // A jump that persists: refused while the last fix taken (2 s) is fresh, then confirmed.
  EXPECT_EQ(g.check(5000, 0, 5 * s), JumpGate::Verdict::kJump);
  EXPECT_EQ(g.check(5000, 0, 5 * s + s / 2, &why), JumpGate::Verdict::kUnconfirmed);
  EXPECT_NE(why.find("waiting for a second fix"), std::string::npos);
  EXPECT_EQ(g.check(5000, 0, 5 * s + s / 2), JumpGate::Verdict::kUnconfirmed);  // same time: no confirmation
  EXPECT_EQ(g.check(9000, 0, 6 * s), JumpGate::Verdict::kUnconfirmed);          // disagrees: a new candidate
  EXPECT_EQ(g.check(9010, 0, 7 * s), JumpGate::Verdict::kTaken);
  EXPECT_FALSE(g.jumped());
  // After a lost fix the next one is taken wherever it is.
  g.forget();
  EXPECT_EQ(g.check(-7000, 0, 8 * s), JumpGate::Verdict::kTaken);
  EXPECT_THROW(JumpGate({0.0, 30.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(JumpGate({25.0, -1.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(JumpGate({25.0, 30.0, NAN}), std::invalid_argument);
}
