// FixedObstacleMap against brute force on random sets (many seeds), and exact geometry cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace om = mpgc::obstacle_manager;
using mpgc::geom::Vec2;

namespace {

std::vector<mpgc::geom::Vec2> random_points(std::mt19937_64& rng, size_t n, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  std::vector<mpgc::geom::Vec2> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng)};
  return pts;
}

// A star-shaped (simple) polygon around c with n vertices of random radius in [r/2, r].
om::Polygon random_star(std::mt19937_64& rng, mpgc::geom::Vec2 c, double r, int n, uint32_t id) {
  std::uniform_real_distribution<double> u(0.5 * r, r);
  om::Polygon g;
  g.feature_id = id;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const double rr = u(rng);
    g.ring.push_back({c.x + rr * std::cos(a), c.y + rr * std::sin(a)});
  }
  return g;
}

bool brute_inside(const std::vector<om::Polygon>& polys, mpgc::geom::Vec2 p) {
  // Even-odd per feature id, union over features (independent of the library's tree).
  std::map<uint32_t, int> parity;
  for (const auto& g : polys) {
    const auto& r = g.ring;
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      if ((r[i].x > p.x) != (r[j].x > p.x)) {
        const double y = r[i].y + (p.x - r[i].x) * (r[j].y - r[i].y) / (r[j].x - r[i].x);
        if (y > p.y) parity[g.feature_id] ^= 1;
      }
    }
  }
  for (const auto& kv : parity)
    if (kv.second) return true;
  return false;
}

double brute_segment_clearance(const std::vector<mpgc::geom::Vec2>& pts, const std::vector<om::Polygon>& polys, mpgc::geom::Vec2 a,
                               mpgc::geom::Vec2 b) {
  if (brute_inside(polys, a)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pts) best = std::min(best, mpgc::geom::segment_distance(a, b, p, p));
  for (const auto& g : polys)
    for (size_t i = 0; i < g.ring.size(); ++i)
      best = std::min(best, mpgc::geom::segment_distance(a, b, g.ring[i], g.ring[(i + 1) % g.ring.size()]));
  return best;
}

}  // namespace

TEST(FixedObstacleMap, NearestAndRadiusEqualBruteForceOnRandomSets) {
  for (uint64_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    const size_t n = 1 + rng() % 2000;
    const auto pts = random_points(rng, n, 1000.0);
    om::FixedObstacleMap map(pts, {});
    std::uniform_real_distribution<double> q(-1200.0, 1200.0), rr(0.0, 150.0);
    for (int k = 0; k < 200; ++k) {
      const mpgc::geom::Vec2 p{q(rng), q(rng)};
      double best = std::numeric_limits<double>::infinity();
      for (const auto& o : pts) best = std::min(best, std::hypot(o.x - p.x, o.y - p.y));
      const double got = map.nearest_distance(p);
      ASSERT_NEAR(got, best, 1e-9 * std::max(1.0, best)) << "seed " << seed << " query " << k;
      const size_t i = map.nearest_index(p);
      ASSERT_NEAR(std::hypot(pts[i].x - p.x, pts[i].y - p.y), best, 1e-9 * std::max(1.0, best));

      const double r = rr(rng);
      std::vector<size_t> expect;
      for (size_t j = 0; j < pts.size(); ++j) {
        const double dx = pts[j].x - p.x, dy = pts[j].y - p.y;
        if (dx * dx + dy * dy <= r * r) expect.push_back(j);
      }
      auto got_r = map.radius(p, r);
      // sorted by distance, so compare as sets
      std::sort(got_r.begin(), got_r.end());
      ASSERT_EQ(got_r, expect) << "seed " << seed << " query " << k << " r " << r;
    }
  }
}

// The nearest-point search starts from a grid of candidates over the points' box: two long
// densified shores (seed 000's canal), queries inside, far outside (the grid's edge cells) and at
// coordinates no int cell index could hold (squared distances overflow past 1e154).
TEST(FixedObstacleMap, NearestFromTheStartingGridEqualsBruteForceOffLongShores) {
  std::vector<mpgc::geom::Vec2> pts;
  for (int i = 0; i <= 2700; ++i) {
    pts.push_back({2458.0 + 20.0 * i / std::sqrt(2.0), -8858.0 + 20.0 * i / std::sqrt(2.0)});
    pts.push_back({-8858.0 + 20.0 * i / std::sqrt(2.0), 2458.0 + 20.0 * i / std::sqrt(2.0)});
  }
  om::FixedObstacleMap map(pts, {});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> q(-60000.0, 90000.0);
  std::vector<mpgc::geom::Vec2> queries{{1e12, -1e12}, {-1e150, 1e150}, {0, 0}};
  for (int k = 0; k < 3000; ++k) queries.push_back({q(rng), q(rng)});
  for (const auto& p : queries) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& o : pts) best = std::min(best, std::hypot(o.x - p.x, o.y - p.y));
    ASSERT_NEAR(map.nearest_distance(p), best, 1e-9 * std::max(1.0, best)) << p.x << ", " << p.y;
    const size_t i = map.nearest_index(p);
    ASSERT_NEAR(std::hypot(pts[i].x - p.x, pts[i].y - p.y), best, 1e-9 * std::max(1.0, best));
  }
}

TEST(FixedObstacleMap, RadiusIsInclusiveAndSortedByDistance) {
  om::FixedObstacleMap map({{0, 0}, {3, 4}, {1, 0}, {0, 10}}, {});
  EXPECT_EQ(map.radius({0, 0}, 5.0), (std::vector<size_t>{0, 2, 1}));
  EXPECT_EQ(map.radius({0, 0}, 0.0), (std::vector<size_t>{0}));
  EXPECT_THROW(map.radius({0, 0}, -1.0), std::invalid_argument);
  EXPECT_THROW(map.radius({0, 0}, std::nan("")), std::invalid_argument);
}

TEST(FixedObstacleMap, SegmentClearanceAndLandEqualBruteForce) {
  for (uint64_t seed = 100; seed < 130; ++seed) {
    std::mt19937_64 rng(seed);
    const auto pts = random_points(rng, rng() % 300, 2000.0);
    std::vector<om::Polygon> polys;
    std::uniform_real_distribution<double> c(-2000.0, 2000.0), r(20.0, 400.0);
    const int np = static_cast<int>(rng() % 12);
    for (int k = 0; k < np; ++k) polys.push_back(random_star(rng, {c(rng), c(rng)}, r(rng), 3 + rng() % 40, k));
    // A hole: same feature id as polygon 0, inside it (even-odd).
    if (np > 0) {
      om::Polygon hole = polys[0];
      mpgc::geom::Vec2 ctr{0, 0};
      for (auto& v : hole.ring) ctr = {ctr.x + v.x / hole.ring.size(), ctr.y + v.y / hole.ring.size()};
      for (auto& v : hole.ring) v = {ctr.x + 0.2 * (v.x - ctr.x), ctr.y + 0.2 * (v.y - ctr.y)};
      polys.push_back(hole);
    }
    om::FixedObstacleMap map(pts, polys);
    std::uniform_real_distribution<double> q(-2500.0, 2500.0), len(0.0, 800.0), ang(-M_PI, M_PI);
    for (int k = 0; k < 300; ++k) {
      const mpgc::geom::Vec2 a{q(rng), q(rng)};
      const double l = (k % 10 == 0) ? 0.0 : len(rng), th = ang(rng);
      const mpgc::geom::Vec2 b{a.x + l * std::cos(th), a.y + l * std::sin(th)};
      ASSERT_EQ(map.inside_land(a), brute_inside(polys, a)) << "seed " << seed << " query " << k;
      // Same per-primitive function and the min of it: equal bit for bit.
      const double bf = brute_segment_clearance(pts, polys, a, b);
      ASSERT_EQ(map.segment_clearance(a, b), bf) << "seed " << seed << " query " << k;
      if (k % 10 == 1) {
        ASSERT_EQ(map.clearance(a), brute_segment_clearance(pts, polys, a, a));
      }
      for (double d : {0.0, 10.0, 100.0, 300.0, bf, std::nextafter(bf, 1e300)})
        ASSERT_EQ(map.segment_clear(a, b, d), bf >= d) << "seed " << seed << " query " << k << " d " << d;
      ASSERT_EQ(map.segment_touches(a, b), bf == 0.0) << "seed " << seed << " query " << k;
      // Legs that end on an obstacle point or a ring vertex: touching, unless rounding says otherwise
      // (the same per-primitive function decides both).
      if (!pts.empty() && k % 3 == 0) {
        const mpgc::geom::Vec2 p = pts[rng() % pts.size()];
        ASSERT_EQ(map.segment_touches(b, p), brute_segment_clearance(pts, polys, b, p) == 0.0) << "seed " << seed << " query " << k;
      }
      if (np > 0 && k % 3 == 1) {
        const auto& ring = polys[rng() % polys.size()].ring;
        const mpgc::geom::Vec2 v = ring[rng() % ring.size()];
        ASSERT_EQ(map.segment_touches(b, v), brute_segment_clearance(pts, polys, b, v) == 0.0) << "seed " << seed << " query " << k;
      }
    }
  }
}

TEST(FixedObstacleMap, ExactGeometryCases) {
  // Unit square land at x,y in [0, 10] with a square hole [4, 6]^2, one point obstacle at (20, 0).
  om::Polygon land{7, {{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
  om::Polygon hole{7, {{4, 4}, {6, 4}, {6, 6}, {4, 6}}};
  om::FixedObstacleMap map({{20, 0}}, {land, hole});
  EXPECT_TRUE(map.inside_land({1, 1}));
  EXPECT_FALSE(map.inside_land({5, 5}));  // in the hole: water
  EXPECT_FALSE(map.inside_land({-1, 5}));
  EXPECT_DOUBLE_EQ(map.clearance({5, 5}), 1.0);
  EXPECT_DOUBLE_EQ(map.clearance({-3, 5}), 3.0);
  EXPECT_DOUBLE_EQ(map.clearance({2, 2}), 0.0);
  // A leg passing north of the land at x = 13, parallel to it: 3 m from the edge x = 10.
  EXPECT_DOUBLE_EQ(map.segment_clearance({13, -5}, {13, 15}), 3.0);
  // A leg crossing the land: 0 although both ends are in water.
  EXPECT_DOUBLE_EQ(map.segment_clearance({-5, 2}, {15, 2}), 0.0);
  // A leg passing 1 m from the point obstacle.
  EXPECT_DOUBLE_EQ(map.segment_clearance({21, -5}, {21, 5}), 1.0);
  EXPECT_FALSE(map.segment_touches({21, -5}, {21, 5}));
  EXPECT_TRUE(map.segment_touches({-5, 2}, {15, 2}));  // across the land
  EXPECT_TRUE(map.segment_touches({20, -5}, {20, 5}));  // through the point obstacle
  EXPECT_TRUE(map.segment_touches({2, 2}, {2, 3}));     // inside land
  EXPECT_TRUE(map.segment_touches({10, 12}, {10, 10})); // ends on a corner
  EXPECT_FALSE(map.segment_touches({5, 5}, {5.5, 5.5}));  // in the hole
  EXPECT_DOUBLE_EQ(map.nearest_distance({20, 3}), 3.0);
  // Bounds cover points and rings.
  const auto b = map.bounds();
  EXPECT_EQ(b.min_x, 0.0);
  EXPECT_EQ(b.max_x, 20.0);
  EXPECT_EQ(b.max_y, 10.0);
}

TEST(FixedObstacleMap, EmptyMapAndBadInput) {
  om::FixedObstacleMap empty;
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(empty.nearest_distance({0, 0}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(empty.segment_clearance({0, 0}, {1, 1}), std::numeric_limits<double>::infinity());
  EXPECT_FALSE(empty.inside_land({0, 0}));
  EXPECT_TRUE(empty.radius({0, 0}, 10).empty());
  EXPECT_THROW(om::FixedObstacleMap({{0, std::nan("")}}, {}), std::invalid_argument);
  EXPECT_THROW(om::FixedObstacleMap({}, {{1, {{0, 0}, {1, 1}}}}), std::invalid_argument);
  EXPECT_THROW(om::FixedObstacleMap({}, {{1, {{0, 0}, {1, 1}, {INFINITY, 0}}}}), std::invalid_argument);
  om::FixedObstacleMap map({{0, 0}}, {});
  EXPECT_THROW(map.nearest_distance({std::nan(""), 0}), std::invalid_argument);
  EXPECT_THROW(map.segment_clearance({0, 0}, {INFINITY, 0}), std::invalid_argument);
  EXPECT_THROW(map.segment_touches({std::nan(""), 0}, {0, 0}), std::invalid_argument);
  EXPECT_FALSE(empty.segment_touches({0, 0}, {1, 1}));
  try {
    om::FixedObstacleMap({}, {{42, {{0, 0}, {1, 1}}}});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("feature 42"), std::string::npos) << e.what();
  }
}

TEST(FixedObstacleMap, MovedMapStillAnswers) {
  om::FixedObstacleMap a({{1, 1}, {5, 5}}, {});
  om::FixedObstacleMap b = std::move(a);
  EXPECT_DOUBLE_EQ(b.nearest_distance({5, 6}), 1.0);
}
