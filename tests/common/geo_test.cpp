#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"

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
