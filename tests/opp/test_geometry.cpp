// Index and obstacle queries against brute force.
#include <gtest/gtest.h>

#include <random>

#include "mpgc/opp/node_grid.hpp"
#include "mpgc/opp/chart_obstacles.hpp"
#include "mpgc/opp/obstacles.hpp"

namespace opp = mpgc::opp;

namespace {
double u(std::mt19937_64& g) { return static_cast<double>(g() >> 11) * (1.0 / 9007199254740992.0); }
}  // namespace

TEST(NodeGrid, NearestAndKNearestMatchBruteForce) {
  std::mt19937_64 g(3);
  opp::detail::NodeGrid grid;
  grid.reset(0, 0, 100, 50);
  std::vector<opp::Vec2> pts;
  std::vector<std::pair<double, int>> out;
  for (int n = 0; n < 3000; ++n) {
    const opp::Vec2 p{u(g) * 100, u(g) * 50};
    pts.push_back(p);
    grid.add(p);
    if (n % 97 != 0) continue;
    for (int q = 0; q < 20; ++q) {
      const opp::Vec2 x{u(g) * 100, u(g) * 50};
      std::vector<double> d;
      for (const auto& pp : pts) d.push_back(opp::norm2(pp - x));
      const int nn = grid.nearest(x);
      ASSERT_DOUBLE_EQ(d[nn], *std::min_element(d.begin(), d.end()));
      const int k = 1 + q;
      grid.k_nearest(x, k, out);
      ASSERT_EQ(static_cast<int>(out.size()), std::min<int>(k, static_cast<int>(pts.size())));
      std::vector<double> ds = d;
      std::sort(ds.begin(), ds.end());
      double worst = 0;
      for (const auto& e : out) worst = std::max(worst, e.first);
      ASSERT_DOUBLE_EQ(worst, ds[out.size() - 1]);
      grid.within(x, 7.0, out);
      ASSERT_EQ(out.size(), static_cast<size_t>(std::count_if(d.begin(), d.end(), [](double v) { return v <= 49.0; })));
    }
  }
}

// A tree in a canal fills a diagonal strip of a large sampling box (seed 000 scenario 3): most
// cells stay empty, the answers stay exact, the k nearest tie-broken by index.
TEST(NodeGrid, ThinStripMatchesBruteForce) {
  std::mt19937_64 g(11);
  opp::detail::NodeGrid grid;
  grid.reset(-10000, -10000, 42000, 42000);
  std::vector<opp::Vec2> pts;
  std::vector<std::pair<double, int>> out;
  auto strip = [&] {
    const double s = u(g) * 40000, w = (u(g) - 0.5) * 300;
    return opp::Vec2{s + w, s - w};
  };
  for (int n = 0; n < 20000; ++n) {
    const opp::Vec2 p = strip();
    pts.push_back(p);
    grid.add(p);
    if (n % 1999 != 0) continue;
    for (int q = 0; q < 10; ++q) {
      const opp::Vec2 x = strip();
      std::vector<std::pair<double, int>> d;
      for (size_t i = 0; i < pts.size(); ++i) d.emplace_back(opp::norm2(pts[i] - x), static_cast<int>(i));
      std::sort(d.begin(), d.end());
      ASSERT_EQ(grid.nearest(x), d[0].second);
      const int k = 45;
      grid.k_nearest(x, k, out);
      std::sort(out.begin(), out.end());
      d.resize(std::min(d.size(), static_cast<size_t>(k)));
      ASSERT_EQ(out, d);
    }
  }
}

// The point set F through the obstacle manager's index (point_obstacles), against brute force.
TEST(PointObstacles, SegmentClearMatchesBruteForce) {
  std::mt19937_64 g(5);
  std::vector<opp::Vec2> pts;
  for (int i = 0; i < 2000; ++i) pts.push_back({u(g) * 1000, u(g) * 1000});
  const auto obs_ptr = opp::point_obstacles(pts);
  const opp::FixedObstacles& obs = *obs_ptr;
  for (int q = 0; q < 2000; ++q) {
    const opp::Vec2 a{u(g) * 1000, u(g) * 1000};
    const opp::Vec2 b = a + opp::Vec2{(u(g) - 0.5) * 200, (u(g) - 0.5) * 200};
    const double d = u(g) * 30;
    double best = 1e300, bn = 1e300;
    for (const auto& p : pts) {
      best = std::min(best, opp::point_segment_dist2(p, a, b));
      bn = std::min(bn, opp::norm2(p - a));
    }
    ASSERT_EQ(obs.segment_clear(a, b, d), best >= d * d) << q;
    ASSERT_DOUBLE_EQ(obs.nearest(a), std::sqrt(bn));
  }
}

TEST(PointObstacles, SegmentClearExactNearDenseClustersAndLargeMargins) {
  // Dense islands and a safety distance comparable to the legs: the bisection must stay exact,
  // including for clearances just above and just below d.
  std::mt19937_64 g(8);
  std::vector<opp::Vec2> pts;
  for (int c = 0; c < 5; ++c) {
    const opp::Vec2 ctr{u(g) * 5000, u(g) * 5000};
    for (int i = 0; i < 2000; ++i) pts.push_back(ctr + opp::Vec2{(u(g) - 0.5) * 200, (u(g) - 0.5) * 200});
  }
  const auto obs_ptr = opp::point_obstacles(pts);
  const opp::FixedObstacles& obs = *obs_ptr;
  int clear = 0, blocked = 0;
  for (int q = 0; q < 1500; ++q) {
    const opp::Vec2 a{u(g) * 5000, u(g) * 5000};
    const opp::Vec2 b = a + opp::Vec2{(u(g) - 0.5) * 3000, (u(g) - 0.5) * 3000};
    double best = 1e300;
    for (const auto& p : pts) best = std::min(best, opp::point_segment_dist2(p, a, b));
    // Half the queries put d within 0.1 % of the true clearance, on either side.
    const double d = q % 2 ? u(g) * 1000 : std::sqrt(best) * (q % 4 == 0 ? 0.999 : 1.001);
    const bool expect = best >= d * d;
    ASSERT_EQ(obs.segment_clear(a, b, d), expect) << q;
    (expect ? clear : blocked)++;
  }
  EXPECT_GT(clear, 300);
  EXPECT_GT(blocked, 300);
}

TEST(Obstacles, RejectNonFiniteInput) {
  EXPECT_THROW(opp::point_obstacles({{0, 0}, {std::nan(""), 1}}), std::invalid_argument);
  EXPECT_THROW(opp::DiscObstacles({{{0, 0}, -1}}), std::invalid_argument);
  const auto empty = opp::point_obstacles({});
  EXPECT_TRUE(std::isinf(empty->nearest({1, 2})));
  EXPECT_TRUE(empty->segment_clear({0, 0}, {1, 1}, 5));
}

TEST(Geometry, MinDistanceOfLinearMotion) {
  // Relative start (10, 0), closing at 1 m/s along x: closest 0 at tau = 10, but clipped at T.
  EXPECT_DOUBLE_EQ(mpgc::geom::closest_approach({10, 3}, {-1, 0}, 20).dist2, 9.0);
  EXPECT_DOUBLE_EQ(mpgc::geom::closest_approach({10, 3}, {-1, 0}, 4).dist2, 36.0 + 9.0);
  EXPECT_DOUBLE_EQ(mpgc::geom::closest_approach({10, 3}, {1, 0}, 4).dist2, 109.0);
}

TEST(ChartObstacles, AgreesWithPointSetAndBlocksLand) {
  std::mt19937_64 g(9);
  std::vector<opp::Vec2> pts;
  std::vector<mpgc::geom::Vec2> opts;
  for (int i = 0; i < 500; ++i) {
    pts.push_back({u(g) * 1000, u(g) * 1000});
    opts.push_back({pts.back().x, pts.back().y});
  }
  // A square island with no points inside it: only the polygon makes it an obstacle.
  std::vector<mpgc::geom::Polygon> polys{{1, {{2000, 2000}, {2000, 2100}, {2100, 2100}, {2100, 2000}}}};
  opp::ChartObstacles chart(std::make_shared<const mpgc::geom::FixedObstacleMap>(opts, polys));
  const auto plain = opp::point_obstacles(pts);  // the same points without the island
  for (int q = 0; q < 500; ++q) {
    const opp::Vec2 a{u(g) * 1000, u(g) * 1000}, b{u(g) * 1000, u(g) * 1000};
    const double d = u(g) * 20;
    ASSERT_EQ(chart.segment_clear(a, b, d), plain->segment_clear(a, b, d));
    ASSERT_NEAR(chart.nearest(a), plain->nearest(a), 1e-9);
  }
  EXPECT_FALSE(chart.segment_clear({2050, 1900}, {2050, 2200}, 0.0));  // crosses the island
  EXPECT_EQ(chart.nearest({2050, 2050}), 0.0);                         // inside land
  EXPECT_TRUE(chart.segment_clear({1900, 1900}, {1900, 2200}, 50.0));
}
