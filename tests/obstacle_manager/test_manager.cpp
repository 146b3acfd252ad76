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
  const auto box = r.publish({0, 0});
  EXPECT_EQ(box.min_x, -1000.0);
  EXPECT_EQ(box.max_y, 1000.0);
  EXPECT_FALSE(r.needs_update({150, 100}));  // 180 m
  EXPECT_TRUE(r.needs_update({150, 150}));   // 212 m
  r.publish({150, 150});
  EXPECT_FALSE(r.needs_update({150, 150}));
  r.chart_changed();
  EXPECT_TRUE(r.needs_update({150, 150}));
  r.publish({150, 150});
  // A goal: the box covers it too, half_size beyond (the planner counts water beyond as unknown).
  r.set_goal(mpgc::geom::Vec2{5000, -3000});
  EXPECT_TRUE(r.needs_update({150, 150}));
  const auto both = r.publish({150, 150});
  EXPECT_EQ(both.min_x, -850.0);
  EXPECT_EQ(both.max_x, 6000.0);
  EXPECT_EQ(both.min_y, -4000.0);
  EXPECT_EQ(both.max_y, 1150.0);
  r.set_goal(mpgc::geom::Vec2{5000, -3000});  // the same goal again: nothing to do
  EXPECT_FALSE(r.needs_update({150, 150}));
  EXPECT_THROW(om::RegionPolicy({1000.0, 1000.0}), std::invalid_argument);
  EXPECT_THROW(om::RegionPolicy({-1.0, 10.0}), std::invalid_argument);
  om::RegionPolicy whole({0.0, 10.0});
  EXPECT_TRUE(whole.needs_update({0, 0}));
  // The whole chart is taken as complete: an infinite region, whatever the goal.
  EXPECT_EQ(whole.publish({5, 5}).min_y, -std::numeric_limits<double>::infinity());
  EXPECT_FALSE(whole.needs_update({1e5, 1e5}));
  whole.set_goal(mpgc::geom::Vec2{1e5, 0});
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

// A ship at rest: its track's velocity is noise, and eq. 3 would carry it over the plan's horizon.
TEST(Moving, AShipAtRestWhoseSpeedIsWithinItsNoiseIsPublishedStopped) {
  om::DomainParams p;
  om::TargetState t;
  t.id = 7;
  t.vx = -0.057;  // Annapolis's stopped motor vessel, 141 m from the goal
  t.vy = 0.051;
  t.var_vx = t.var_vy = 0.05 * 0.05;
  EXPECT_EQ(om::check_target(t, p), "");
  auto o = om::to_moving_obstacle(t, p);
  EXPECT_EQ(o.vx, 0.0);
  EXPECT_EQ(o.vy, 0.0);
  t.var_vx = t.var_vy = 0.01 * 0.01;  // the same speed, but 5 sigmas from 0: it moves
  o = om::to_moving_obstacle(t, p);
  EXPECT_EQ(o.vx, -0.057);
  EXPECT_EQ(o.vy, 0.051);
  t.vx = 0.6;  // a fresh track's large sigma never stops a ship faster than stopped_speed
  t.vy = 0.0;
  t.var_vx = t.var_vy = 25.0;
  EXPECT_EQ(om::to_moving_obstacle(t, p).vx, 0.6);
  t.vx = 0.3;
  EXPECT_EQ(om::to_moving_obstacle(t, p).vx, 0.0);
  p.stopped_speed = 0.0;  // off
  EXPECT_EQ(om::to_moving_obstacle(t, p).vx, 0.3);
  t.var_vy = -1;
  EXPECT_NE(om::check_target(t, p).find("negative velocity variance"), std::string::npos);
  t.var_vy = INFINITY;
  EXPECT_NE(om::check_target(t, p).find("not finite"), std::string::npos);
  p.stopped_sigmas = NAN;
  EXPECT_THROW(p.validate(), std::invalid_argument);
}

// Issue 15: stale tracks age out, uncertainty grows with age, silence is reported.
namespace {
constexpr int64_t kS = 1'000'000'000;  // [ns] per second

om::TargetState target(uint32_t id, double since_update) {
  om::TargetState t;
  t.id = id;
  t.x = 1000;
  t.y = 2000;
  t.vx = 5;
  t.vy = 0;
  t.var_x = 25;  // sigma 5 m
  t.var_y = 9;
  t.length = 100;  // radius 200 m
  t.since_update = since_update;
  return t;
}
}  // namespace

TEST(Aging, UncertaintyGrowsWithTimeAndIsUnchangedAtZero) {
  om::AgingParams a;
  a.speed_std = 2.0;
  a.radius_sigmas = 3.0;
  const auto o = om::to_moving_obstacle(target(1, 0), {});
  const auto same = om::grow_uncertainty(o, 0.0, a);
  EXPECT_EQ(same.position_std, o.position_std);  // bit for bit: fresh lists give today's values
  EXPECT_EQ(same.radius, o.radius);
  const auto later = om::grow_uncertainty(o, 10.0, a);
  EXPECT_DOUBLE_EQ(later.position_std, std::sqrt(25.0 + 400.0));  // sigma^2 = sigma0^2 + (sigma_v t)^2
  EXPECT_DOUBLE_EQ(later.radius, 200.0 + 3.0 * (std::sqrt(425.0) - 5.0));
  EXPECT_EQ(later.x, o.x);  // positions stay at the time of validity: the planner extrapolates
  double prev = o.position_std;
  for (double t = 1; t < 100; t += 7) {
    const auto g = om::grow_uncertainty(o, t, a);
    EXPECT_GT(g.position_std, prev);
    EXPECT_GE(g.radius, o.radius);
    prev = g.position_std;
  }
  a.radius_sigmas = 0;
  EXPECT_EQ(om::grow_uncertainty(o, 50.0, a).radius, o.radius);
  for (double bad : {-1.0, static_cast<double>(NAN), static_cast<double>(INFINITY)}) {
    om::AgingParams b;
    b.max_age = bad;
    EXPECT_THROW(b.validate(), std::invalid_argument);
    b = {};
    b.speed_std = bad;
    EXPECT_THROW(b.validate(), std::invalid_argument);
  }
}

TEST(Aging, FreshListIsPublishedAsToday) {
  om::MovingObstacleFeed feed({}, {});
  feed.receive(100 * kS, {target(1, 3.0)}, 100 * kS);
  const auto out = feed.at(100 * kS);
  EXPECT_EQ(out.feed, om::MovingObstacleFeed::Feed::kFresh);
  EXPECT_EQ(out.t_valid_ns, 100 * kS);
  ASSERT_EQ(out.obstacles.size(), 1u);
  const auto today = om::to_moving_obstacle(target(1, 3.0), {});
  EXPECT_EQ(out.obstacles[0].position_std, today.position_std);
  EXPECT_EQ(out.obstacles[0].radius, today.radius);
  EXPECT_EQ(out.obstacles[0].x, today.x);
}

// situational_awareness decides a track's life while it speaks: a track it still lists after a long
// sensor outage (coasting, position_std grown) is passed on, however old its last measurement;
// only the list's own age (situational_awareness silent) drops obstacles.
TEST(Aging, ATrackSituationalAwarenessStillListsIsKeptHoweverOld) {
  om::AgingParams a;
  a.max_age = 60;
  om::MovingObstacleFeed feed({}, a);
  feed.receive(0, {target(1, 1.0), target(2, 300.0)}, 0);
  auto out = feed.at(0);
  ASSERT_EQ(out.obstacles.size(), 2u);
  EXPECT_TRUE(out.aged_out.empty());
  EXPECT_EQ(out.obstacles[1].position_std, om::to_moving_obstacle(target(2, 300.0), {}).position_std);
  // The list ages out as a whole, each track reported once; listed again: published, and the next
  // ageing reported again.
  out = feed.at(61 * kS);
  EXPECT_TRUE(out.obstacles.empty());
  EXPECT_EQ(out.aged_out, (std::vector<uint32_t>{1, 2}));
  EXPECT_TRUE(feed.at(62 * kS).aged_out.empty());
  feed.receive(63 * kS, {target(2, 0.0)}, 63 * kS);
  EXPECT_EQ(feed.at(63 * kS).obstacles.size(), 1u);
  EXPECT_EQ(feed.at(124 * kS).aged_out, std::vector<uint32_t>{2});
}

TEST(Aging, SilenceIsReportedObstaclesArePredictedUntilMaxAgeThenEmpty) {
  om::AgingParams a;
  a.max_age = 60;
  a.timeout = 5;
  a.speed_std = 1;
  om::MovingObstacleFeed feed({}, a);
  EXPECT_EQ(feed.at(0).feed, om::MovingObstacleFeed::Feed::kWaiting);
  EXPECT_EQ(feed.at(4 * kS).feed, om::MovingObstacleFeed::Feed::kWaiting);
  const auto none = feed.at(6 * kS);  // nothing since start for more than the timeout
  EXPECT_EQ(none.feed, om::MovingObstacleFeed::Feed::kSilent);
  EXPECT_EQ(none.t_valid_ns, 6 * kS);
  EXPECT_TRUE(none.obstacles.empty());

  const int64_t t0 = 10 * kS;
  feed.receive(t0, {target(1, 0.0), target(2, 30.0)}, t0);
  EXPECT_EQ(feed.at(t0 + 5 * kS).feed, om::MovingObstacleFeed::Feed::kFresh);
  auto out = feed.at(t0 + 6 * kS);
  EXPECT_EQ(out.feed, om::MovingObstacleFeed::Feed::kSilent);
  EXPECT_DOUBLE_EQ(out.silence, 6.0);
  ASSERT_EQ(out.obstacles.size(), 2u);  // still predicted forward (from the list's stamp)
  EXPECT_EQ(out.t_valid_ns, t0);
  EXPECT_DOUBLE_EQ(out.obstacles[0].position_std, std::sqrt(25.0 + 36.0));
  // Both are predicted until the list is max_age old, however old track 2 was at the stamp.
  out = feed.at(t0 + 31 * kS);
  ASSERT_EQ(out.obstacles.size(), 2u);
  EXPECT_TRUE(out.aged_out.empty());
  EXPECT_EQ(feed.at(t0 + 60 * kS).obstacles.size(), 2u);  // exactly max_age: kept
  out = feed.at(t0 + 61 * kS);
  EXPECT_TRUE(out.obstacles.empty());
  EXPECT_EQ(out.aged_out, (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(out.t_valid_ns, t0 + 61 * kS);  // an empty list valid now, not the old stamp
  EXPECT_EQ(out.feed, om::MovingObstacleFeed::Feed::kSilent);
  // Tracks again: fresh.
  feed.receive(t0 + 62 * kS, {target(3, 0.0)}, t0 + 62 * kS);
  out = feed.at(t0 + 62 * kS);
  EXPECT_EQ(out.feed, om::MovingObstacleFeed::Feed::kFresh);
  EXPECT_EQ(out.obstacles.size(), 1u);
}

TEST(Aging, BadTracksAreRefusedOnArrivalWithAReason) {
  om::MovingObstacleFeed feed({}, {});
  auto nan_age = target(1, NAN);
  auto neg_age = target(2, -1.0);
  auto gone = target(3, 0.0);
  gone.deleted = true;
  auto tent = target(4, 0.0);
  tent.tentative = true;
  const auto r = feed.receive(0, {nan_age, neg_age, gone, tent, target(5, 0.0)}, 0);
  ASSERT_EQ(r.rejected.size(), 2u);
  EXPECT_NE(r.rejected[0].find("not finite"), std::string::npos);
  EXPECT_NE(r.rejected[1].find("negative since_update"), std::string::npos);
  EXPECT_EQ(r.deleted, 1u);
  EXPECT_EQ(r.tentative, 1u);
  EXPECT_EQ(feed.at(0).obstacles.size(), 1u);
  // A stamp ahead of our clock is age 0, not negative.
  feed.receive(10 * kS, {target(5, 0.0)}, 9 * kS);
  EXPECT_EQ(feed.at(9 * kS).obstacles[0].position_std, 5.0);
}
