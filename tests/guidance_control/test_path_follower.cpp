// Path follower: geometry signs, LOS law, waypoint switching, path validation, joining a new plan.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/guidance_control/path_follower.hpp"

namespace gc = mpgc::guidance_control;
using mpgc::geo::deg2rad;
using mpgc::geo::kPi;

TEST(LegGeometry, SignsAndDistances) {
  // Leg north; a ship east of it is to starboard (positive cross-track).
  auto g = gc::leg_geometry({0, 0}, {1000, 0}, 300, 40);
  EXPECT_NEAR(g.course, 0.0, 1e-12);
  EXPECT_NEAR(g.along, 300, 1e-9);
  EXPECT_NEAR(g.cross, 40, 1e-9);
  EXPECT_NEAR(g.to_end, std::hypot(700, 40), 1e-9);
  // Leg east; a ship south of it is to starboard.
  g = gc::leg_geometry({0, 0}, {0, 1000}, -40, 300);
  EXPECT_NEAR(g.course, kPi / 2, 1e-12);
  EXPECT_NEAR(g.cross, 40, 1e-9);
}

TEST(PathFollower, LosLaw) {
  gc::PathFollowerParams p;
  p.integral = false;
  gc::PathFollower f(p);
  f.set_path({{0, 0, 5}, {10000, 0, 5}}, 0, 0);
  auto o = f.update(2000, 0, 7.0, 1.0);
  EXPECT_NEAR(o.desired_heading, 0.0, 1e-12);
  EXPECT_NEAR(o.desired_speed, 5.0, 1e-12);
  o = f.update(2000, 200, 7.0, 1.0);  // starboard of the path -> steer to port
  EXPECT_NEAR(o.desired_heading, -std::atan(200.0 / p.lookahead), 1e-12);
  o = f.update(2000, -1e6, 7.0, 1.0);  // far to port -> nearly perpendicular, to starboard
  EXPECT_GT(o.desired_heading, deg2rad(89.9));
  EXPECT_LT(o.desired_heading, deg2rad(90.0));
}

TEST(PathFollower, SwitchesOnCircleOfAcceptanceOrAlongTrackPoint) {
  gc::PathFollowerParams p;
  p.acceptance_radius = 500;
  gc::PathFollower f(p);
  const std::vector<gc::PathPoint> path{{0, 0}, {5000, 0}, {5000, 5000}, {0, 5000}};
  f.set_path(path, 0, 0);
  EXPECT_EQ(f.update(4000, 0, 7.0, 1).active_waypoint, 1u);
  EXPECT_EQ(f.update(4510, 0, 7.0, 1).active_waypoint, 2u);  // inside the circle of acceptance of wp 1
  // Far outside the circle (1 km off the leg), the along-track point of wp 2 switches.
  EXPECT_EQ(f.update(4000, 4990, 7.0, 1).active_waypoint, 2u);  // 1000 m from wp 2: outside the circle
  EXPECT_EQ(f.update(6000, 5001, 7.0, 1).active_waypoint, 3u);   // passed the normal through wp 2
  // The last waypoint: arrival, desired speed 0, heading along the last leg.
  auto o = f.update(400, 5000, 7.0, 1);
  EXPECT_TRUE(o.arrived);
  EXPECT_DOUBLE_EQ(o.desired_speed, 0.0);
  EXPECT_NEAR(o.desired_heading, kPi, 1e-12);
}

TEST(PathFollower, DefaultAndClampedSpeeds) {
  gc::PathFollowerParams p;
  gc::PathFollower f(p);
  f.set_path({{0, 0, 0}, {5000, 0, 0}, {10000, 0, 99}}, 0, 0);
  EXPECT_DOUBLE_EQ(f.update(100, 0, 7.0, 1).desired_speed, p.default_speed);
  EXPECT_DOUBLE_EQ(f.update(6000, 0, 7.0, 1).desired_speed, p.max_speed);
}

TEST(CheckPath, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(gc::check_path({{0, 0}, {100, 0}}), "");
  EXPECT_NE(gc::check_path({}).find("empty"), std::string::npos);
  EXPECT_NE(gc::check_path({{0, 0}}).find("single"), std::string::npos);
  EXPECT_NE(gc::check_path({{0, 0}, {nan, 0}}).find("waypoint 1"), std::string::npos);
  EXPECT_NE(gc::check_path({{0, 0}, {5, inf}}).find("non-finite"), std::string::npos);
  EXPECT_NE(gc::check_path({{0, 0}, {5, 0, nan}}).find("speed"), std::string::npos);
  EXPECT_NE(gc::check_path({{0, 0}, {2e7, 0}}).find("1e7"), std::string::npos);
  EXPECT_NE(gc::check_path({{1, 1}, {1, 1}}).find("non-zero"), std::string::npos);
  EXPECT_NE(gc::check_path(std::vector<gc::PathPoint>(20000, {0, 0})).find("more than"), std::string::npos);
  gc::PathFollower f{gc::PathFollowerParams{}};
  EXPECT_THROW(f.set_path({{0, 0}}, 0, 0), std::invalid_argument);
  // Duplicates are merged, not rejected.
  f.set_path({{0, 0}, {0, 0}, {1000, 0}}, 0, 0);
  EXPECT_EQ(f.path().size(), 2u);
}

TEST(PathFollower, JoinsNewPathAtTheNearestLegAhead) {
  const std::vector<gc::PathPoint> path{{0, 0}, {3000, 0}, {3000, 3000}, {6000, 3000}, {6000, 6000}};
  EXPECT_EQ(gc::PathFollower::join_leg(path, 2000, 30), 1u);
  EXPECT_EQ(gc::PathFollower::join_leg(path, 3100, 1500), 2u);
  EXPECT_EQ(gc::PathFollower::join_leg(path, 4500, 3050), 3u);
  EXPECT_EQ(gc::PathFollower::join_leg(path, 9000, 9000), 4u);  // past everything: last leg
  EXPECT_EQ(gc::PathFollower::join_leg(path, -500, 0), 1u);      // before the start
  // The first leg's end is "ahead" along-track but 9 km abeam: the nearest leg is the last one.
  EXPECT_EQ(gc::PathFollower::join_leg(path, 2900, 9000), 4u);
  auto active_after_join = [&](double x, double y) {
    gc::PathFollowerParams p;
    p.acceptance_radius = 640;
    gc::PathFollower f(p);
    f.set_path(path, x, y);
    return f.update(x, y, 7.0, 0.0);
  };
  // The plan starts behind the ship (planned from where it was a while ago): not back to wp 0.
  EXPECT_EQ(active_after_join(2000, 30).active_waypoint, 1u);
  EXPECT_EQ(active_after_join(2500, 0).active_waypoint, 2u);  // inside wp 1's circle: next leg at once
  const auto done = active_after_join(6100, 6400);             // beyond the end: arrived, no turn back
  EXPECT_TRUE(done.arrived);
  EXPECT_EQ(done.active_waypoint, 4u);
}

// Replacing the plan with one that runs along the same line gives the same desired heading: the
// switch adds no jump of its own; the integral (current estimate) is carried over.
TEST(PathFollower, NewPlanOnTheSameLineGivesNoHeadingJump) {
  gc::PathFollowerParams p;
  gc::PathFollower f(p);
  f.set_path({{0, 0}, {20000, 0}, {20000, 20000}}, 0, 0);
  for (int i = 0; i < 300; ++i) f.update(10.0 * i, 60, 7.0, 1.0);  // build up some integral
  const double y_int = f.integral_state();
  ASSERT_NE(y_int, 0.0);
  const auto before = f.update(3000, 60, 7.0, 0.0);
  f.set_path({{2800, 0}, {9000, 0}, {9000, -4000}}, 3000, 60);
  const auto after = f.update(3000, 60, 7.0, 0.0);
  EXPECT_EQ(f.integral_state(), y_int);
  EXPECT_NEAR(after.desired_heading, before.desired_heading, 1e-12);
  EXPECT_NEAR(after.cross_track_error, before.cross_track_error, 1e-9);
}

// A new plan that leaves the old line: the desired heading after the switch is exactly what the new
// geometry gives for the ship's position (no transient from the old plan, no turn back to wp 0).
TEST(PathFollower, NewDivergingPlanGivesTheGeometryHeading) {
  gc::PathFollowerParams p;
  p.integral = false;
  gc::PathFollower f(p);
  f.set_path({{0, 0}, {20000, 0}}, 0, 0);
  f.update(5000, 0, 7.0, 1.0);
  // Planned 60 s ago from (4500, 0): first waypoint behind the ship, then 30 deg to starboard.
  const std::vector<gc::PathPoint> avoid{{4500, 0}, {5000, 0}, {9000, 2309.4}, {15000, 2309.4}};
  f.set_path(avoid, 5000, 0);
  const auto o = f.update(5000, 0, 7.0, 1.0);
  EXPECT_EQ(o.active_waypoint, 2u);
  EXPECT_NEAR(o.desired_heading, deg2rad(30.0), 1e-3);
}
