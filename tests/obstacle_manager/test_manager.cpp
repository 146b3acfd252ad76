// The obstacle manager's decisions without DDS: inline shapes, region policy, tracks -> moving obstacles.
#include <gtest/gtest.h>

#include <cmath>

#include "mpgc/geo/angles.hpp"
#include "mpgc/obstacle_manager/manager.hpp"

namespace om = mpgc::obstacle_manager;

namespace {
om::ChartBuilder builder() { return om::ChartBuilder(mpgc::geo::LocalNed({0.7, -1.3}), om::ChartParams{}); }
std::string error_of(const std::string& spec) {
  auto b = builder();
  try {
    om::add_shapes(b, spec);
  } catch (const om::ChartError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Shapes, Seed003CirclesAndCanal) {
  auto b = builder();
  // Two circles of seed 003 Table 3 (Cir01, Cir14) and a canal as two walls (seed 000 scenario 3).
  om::add_shapes(b, "circle 15703 18214 208; circle 64252 10445 18;"
                    " line 0 -100 5000 -100; line 0 100 5000 100; point 1 2; polygon 0 0 10 0 10 10");
  const auto s = b.take();
  EXPECT_EQ(s.features.size(), 6u);
  om::FixedObstacleMap map(s.points, s.polygons);
  EXPECT_TRUE(map.inside_land({15703, 18214}));
  EXPECT_TRUE(map.inside_land({15703 + 207, 18214}));
  EXPECT_FALSE(map.inside_land({15703 + 240, 18214}));
  EXPECT_TRUE(map.inside_land({64252, 10445 + 17.9}));
  EXPECT_NEAR(map.clearance({2500, 0}), 100.0, 1e-9);
}

TEST(Shapes, MalformedShapesNameTheShape) {
  EXPECT_NE(error_of("circle 1 2").find("shape 0 (circle): needs 'circle N E R'"), std::string::npos);
  EXPECT_NE(error_of("circle 1 2 3; polygon 0 0 1 x 2 2").find("shape 1 (polygon): 'x' is not a number"), std::string::npos);
  EXPECT_NE(error_of("hexagon 1 2 3").find("unknown shape 'hexagon'"), std::string::npos);
  EXPECT_NE(error_of("polygon 0 0 1 1 1 0 0 1").find("shape 0 (polygon): polygon ring intersects itself"),
            std::string::npos);
  EXPECT_NE(error_of("line 0 0 1").find("needs pairs"), std::string::npos);
  EXPECT_NE(error_of("circle 0 0 -5").find("radius > 0"), std::string::npos);
  EXPECT_NE(error_of("circle 0 0 nan").find("shape 0 (circle)"), std::string::npos);
  EXPECT_EQ(error_of(" ; ;"), "(no error)");
}

TEST(Region, RepublishesAfterMovingFarEnoughOrChartChange) {
  om::RegionPolicy r({1000.0, 200.0});
  EXPECT_TRUE(r.needs_update({0, 0}));
  const auto box = r.publish({0, 0}, {});
  EXPECT_EQ(box.min_x, -1000.0);
  EXPECT_EQ(box.max_y, 1000.0);
  EXPECT_FALSE(r.needs_update({150, 100}));  // 180 m
  EXPECT_TRUE(r.needs_update({150, 150}));   // 212 m
  r.publish({150, 150}, {});
  EXPECT_FALSE(r.needs_update({150, 150}));
  r.chart_changed();
  EXPECT_TRUE(r.needs_update({150, 150}));
  EXPECT_THROW(om::RegionPolicy({1000.0, 1000.0}), std::invalid_argument);
  EXPECT_THROW(om::RegionPolicy({-1.0, 10.0}), std::invalid_argument);
  om::RegionPolicy whole({0.0, 10.0});
  EXPECT_TRUE(whole.needs_update({0, 0}));
  EXPECT_EQ(whole.publish({5, 5}, {-3, -4, 7, 8}).min_y, -4.0);
  EXPECT_FALSE(whole.needs_update({1e5, 1e5}));
}

TEST(Moving, TracksBecomeObstaclesWithDomain) {
  om::DomainParams p;
  om::TargetState t;
  t.id = 4;
  t.mmsi = 257000000;
  t.x = 100;
  t.y = -50;
  t.vx = 3;
  t.vy = 4;
  t.var_x = 9;
  t.var_y = 16;
  EXPECT_EQ(om::check_target(t, p), "");
  auto o = om::to_moving_obstacle(t, p);
  EXPECT_EQ(o.radius, p.min_radius);
  EXPECT_EQ(o.position_std, 4.0);
  EXPECT_EQ(o.vx, 3.0);
  t.length = 180;
  o = om::to_moving_obstacle(t, p);
  EXPECT_EQ(o.radius, 360.0);
  t.tentative = true;
  EXPECT_EQ(om::check_target(t, p), "tentative");
  p.tentative = true;
  EXPECT_EQ(om::check_target(t, p), "");
  t.deleted = true;
  EXPECT_EQ(om::check_target(t, p), "deleted");
  t.deleted = false;
  t.vx = NAN;
  EXPECT_NE(om::check_target(t, p).find("not finite"), std::string::npos);
  t.vx = 100;
  EXPECT_NE(om::check_target(t, p).find("speed"), std::string::npos);
  t.vx = 3;
  t.var_y = -1;
  EXPECT_NE(om::check_target(t, p).find("negative"), std::string::npos);
  t.var_y = 1;
  t.length = -4;
  EXPECT_NE(om::check_target(t, p).find("length"), std::string::npos);
}
