// Seed 002 §2: turning-circle tables (written by ship_simulator, read by opp), Fig. 3 and eq. 4
// interpolation, and the paper's accuracy check against the model itself.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "mpgc/geo/angles.hpp"
#include "mpgc/opp/turning_tables.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/trials.hpp"
#include "mpgc/testing.hpp"

namespace opp = mpgc::opp;
namespace sim = mpgc::ship_simulator;
namespace geo = mpgc::geo;
using mpgc::geom::Vec2;

namespace {

std::vector<double> range_deg(double from, double to, double step) {
  std::vector<double> out;
  for (double d = from; d <= to + 1e-9; d += step) out.push_back(geo::deg2rad(d));
  return out;
}

struct Ship {
  std::unique_ptr<sim::ShipModel> model;
  sim::TrialConditions c;
};

Ship make_ship(const std::string& kind) {
  Ship s{sim::make_model({kind, mpgc::testing::shared_data("ship_models"), "Mariner"}), {}};
  s.c = {7.97, sim::straight_rpm(*s.model, 7.97), 0.1};
  return s;
}

// The CSV of `./mpgc trial table` for this grid.
std::string tables_csv(Ship& s, const std::vector<double>& rudders, const std::vector<double>& r0s, double duration,
                       double dt_out) {
  std::ostringstream out;
  sim::write_tables_csv(out, sim::turning_tables(*s.model, rudders, r0s, s.c, duration, dt_out), {"test"});
  return out.str();
}

opp::TurningTables load(const std::string& csv) {
  std::istringstream in(csv);
  return opp::load_turning_tables(in, "t.csv");
}

// The message of the loader's error on `csv` ("" when it loads).
std::string load_error(const std::string& csv) {
  try {
    load(csv);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> v;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}
std::size_t first_data_line(const std::vector<std::string>& v) {
  std::size_t i = 0;
  while (v[i].empty() || v[i][0] == '#') ++i;
  return i + 1;  // after the header
}

opp::TrialFn truth_of(Ship& s) {
  return [&s](double r0, double rudder, double step, int n) {
    std::vector<opp::StateVector> out;
    for (const auto& q : sim::turning_trial(*s.model, rudder, r0, s.c, step, n))
      out.push_back({q.x, q.y, q.psi, q.r, q.u, q.v});
    return out;
  };
}

}  // namespace

// ---- Fig. 3 and eq. 4 on known functions ------------------------------------------------------

TEST(TurningTables, LinearInterpolationIsExactOnLines) {
  EXPECT_DOUBLE_EQ(opp::interpolate_linear(1.0, 5.0, 3.0, 11.0, 2.5), 9.5);  // f = 3x + 2
  EXPECT_DOUBLE_EQ(opp::interpolate_linear(1.0, 5.0, 3.0, 11.0, 1.0), 5.0);
  const opp::StateVector a{0, 10, 0.1, 0.01, 8, 0}, b{100, 30, 0.3, 0.03, 6, 0.4};
  const auto m = opp::interpolate_linear(0.0, a, 10.0, b, 2.5);  // Fig. 3, each column alike
  EXPECT_DOUBLE_EQ(m.x, 25.0);
  EXPECT_DOUBLE_EQ(m.y, 15.0);
  EXPECT_DOUBLE_EQ(m.psi, 0.15);
  EXPECT_DOUBLE_EQ(m.r, 0.015);
  EXPECT_DOUBLE_EQ(m.u, 7.5);
  EXPECT_DOUBLE_EQ(m.v, 0.1);
  EXPECT_THROW(opp::interpolate_linear(1.0, 0.0, 1.0, 1.0, 1.0), std::invalid_argument);
}

TEST(TurningTables, BilinearInterpolationIsExactOnBilinearFunctions) {
  auto f = [](double a, double b) { return 1.0 + 2.0 * a - 3.0 * b + 4.0 * a * b; };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double a1 = -2, a2 = 3, b1 = 0.5, b2 = 1.5;
  for (int i = 0; i < 50; ++i) {
    const double a = a1 + (a2 - a1) * u(rng), b = b1 + (b2 - b1) * u(rng);
    EXPECT_NEAR(opp::interpolate_bilinear(a1, a2, b1, b2, f(a1, b1), f(a2, b1), f(a1, b2), f(a2, b2), a, b), f(a, b),
                1e-12);
  }
  // A quadratic is not reproduced: the check below can see a coarse grid.
  auto g = [](double a, double) { return a * a; };
  EXPECT_GT(std::abs(opp::interpolate_bilinear(0, 2, 0, 1, g(0, 0), g(2, 0), g(0, 1), g(2, 1), 1.0, 0.5) - 1.0), 0.5);
}

TEST(TurningTables, Eq4WeightsAreTheDistanceComplements) {
  const std::array<Vec2, 4> sq{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  const auto wc = opp::quad_weights(sq, {0.5, 0.5});
  for (double w : wc) EXPECT_NEAR(w, 0.25, 1e-15);  // the centre: the mean
  // At node 0: d = (0, 1, sqrt 2, 1), D = 2 + sqrt 2; w_i = (D - d_i) / D, normalised by their sum 3.
  const double D = 2.0 + std::sqrt(2.0);
  const auto w0 = opp::quad_weights(sq, {0.0, 0.0});
  EXPECT_NEAR(w0[0], 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(w0[1], (D - 1.0) / (3.0 * D), 1e-15);
  EXPECT_NEAR(w0[2], (D - std::sqrt(2.0)) / (3.0 * D), 1e-15);
  EXPECT_NEAR(w0[0] + w0[1] + w0[2] + w0[3], 1.0, 1e-15);
  // A constant is kept anywhere; f = x at node 0 is not 0: eq. 4 is a weighted mean, not an
  // interpolant (what makes its error a sizeable fraction of the node spread near a node or edge).
  EXPECT_NEAR(opp::quad_interpolate(sq, {4, 4, 4, 4}, {0.2, 0.7}), 4.0, 1e-14);
  EXPECT_NEAR(opp::quad_interpolate(sq, {0, 1, 1, 0}, {0.0, 0.0}), (2 * D - 1 - std::sqrt(2.0)) / (3 * D), 1e-14);
  EXPECT_NEAR(opp::quad_interpolate(sq, {0, 1, 1, 0}, {0.5, 0.5}), 0.5, 1e-15);
  // Symmetry: a mirrored point gets the mirrored weights.
  const auto wa = opp::quad_weights(sq, {0.2, 0.3}), wb = opp::quad_weights(sq, {0.8, 0.3});
  EXPECT_NEAR(wa[0], wb[1], 1e-15);
  EXPECT_NEAR(wa[3], wb[2], 1e-15);
  EXPECT_GT(wa[0], wa[2]);  // nearer node, larger weight
  EXPECT_THROW(opp::quad_weights(sq, {std::nan(""), 0.0}), std::invalid_argument);
}

TEST(TurningTables, ConvexQuadContainment) {
  const std::array<Vec2, 4> q{{{0, 0}, {2, 0}, {3, 2}, {0, 1}}};
  EXPECT_TRUE(opp::convex_quad_contains(q, {1, 0.5}));
  EXPECT_TRUE(opp::convex_quad_contains(q, {1, 0}));  // on an edge
  EXPECT_FALSE(opp::convex_quad_contains(q, {-0.1, 0.5}));
  EXPECT_FALSE(opp::convex_quad_contains(q, {2.9, 0.5}));
  std::array<Vec2, 4> cw = q;  // the other sense
  std::swap(cw[1], cw[3]);
  EXPECT_TRUE(opp::convex_quad_contains(cw, {1, 0.5}));
  const std::array<Vec2, 4> bow{{{0, 0}, {1, 1}, {1, 0}, {0, 1}}};  // crossed
  EXPECT_FALSE(opp::convex_quad_contains(bow, {0.5, 0.5}));
  const std::array<Vec2, 4> concave{{{0, 0}, {2, 0}, {0.5, 0.5}, {0, 2}}};
  EXPECT_FALSE(opp::convex_quad_contains(concave, {0.2, 0.2}));
  const std::array<Vec2, 4> tri{{{0, 0}, {0, 0}, {2, 1}, {1, 2}}};  // the first quad of a fan
  EXPECT_TRUE(opp::convex_quad_contains(tri, {1, 1}));
  EXPECT_FALSE(opp::convex_quad_contains(tri, {1, 0}));
  const std::array<Vec2, 4> line{{{0, 0}, {1, 0}, {2, 0}, {3, 0}}};
  EXPECT_FALSE(opp::convex_quad_contains(line, {1, 0}));
}

TEST(TurningTables, InverseBilinearReproducesBilinearFields) {
  const std::array<Vec2, 4> q{{{0, 0}, {4, 1}, {5, 4}, {-1, 3}}};  // convex, no two sides parallel
  auto map = [&](double s, double t) {
    return (1 - s) * (1 - t) * q[0] + s * (1 - t) * q[1] + s * t * q[2] + (1 - s) * t * q[3];
  };
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const double s = u(rng), t = u(rng);
    const auto st = opp::quad_inverse_bilinear(q, map(s, t));
    ASSERT_TRUE(st.has_value()) << s << " " << t;
    EXPECT_NEAR((*st)[0], s, 1e-9);
    EXPECT_NEAR((*st)[1], t, 1e-9);
  }
  const auto n2 = opp::quad_inverse_bilinear(q, q[2]);  // a node is itself (eq. 4 is not)
  ASSERT_TRUE(n2.has_value());
  EXPECT_NEAR((*n2)[0], 1.0, 1e-12);
  EXPECT_NEAR((*n2)[1], 1.0, 1e-12);
  EXPECT_FALSE(opp::quad_inverse_bilinear(q, {6, 0}).has_value());
  EXPECT_FALSE(opp::quad_inverse_bilinear(q, {2, -0.5}).has_value());
  const std::array<Vec2, 4> sq{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};  // parallel sides: linear case
  const auto c = opp::quad_inverse_bilinear(sq, {0.25, 0.75});
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR((*c)[0], 0.25, 1e-12);
  EXPECT_NEAR((*c)[1], 0.75, 1e-12);
  const std::array<Vec2, 4> tri{{{0, 0}, {0, 0}, {2, 1}, {1, 2}}};  // the first quad of a fan
  const auto a = opp::quad_inverse_bilinear(tri, {1.5, 1.5});
  ASSERT_TRUE(a.has_value());
  EXPECT_NEAR((*a)[0], 0.5, 1e-12);
  EXPECT_NEAR((*a)[1], 1.0, 1e-12);
}

// ---- tables: round trip, Fig. 3 on the grid, the start transform -------------------------------

TEST(TurningTables, WrittenTablesLoadBackOnTheirGrid) {
  Ship s = make_ship("nomoto");
  const auto rud = range_deg(-20, 20, 10), r0 = range_deg(-0.2, 0.2, 0.2);
  const auto rows = sim::turning_tables(*s.model, rud, r0, s.c, 100.0, 10.0);
  const auto tt = load(tables_csv(s, rud, r0, 100.0, 10.0));
  ASSERT_EQ(tt.rudders().size(), 5u);
  ASSERT_EQ(tt.r0s().size(), 3u);
  EXPECT_EQ(tt.n_times(), 11);
  EXPECT_NEAR(tt.dt(), 10.0, 1e-12);
  EXPECT_NEAR(tt.rudders()[1], geo::deg2rad(-10.0), 1e-12);
  EXPECT_NEAR(tt.approach_speed(), 7.97, 1e-9);
  // Every node as written (10 significant digits), and Fig. 3 on a node returns the node.
  for (std::size_t i = 0; i < 5; ++i)
    for (std::size_t j = 0; j < 3; ++j)
      for (int k = 0; k < 11; ++k) {
        const auto& w = rows[(i * 3 + j) * 11 + static_cast<std::size_t>(k)];
        const auto& n = tt.node(i, j, k);
        EXPECT_NEAR(n.x, w.x, 1e-8 * (1 + std::abs(w.x)));
        EXPECT_NEAR(n.psi, w.psi, 1e-10);
        const auto rw = tt.row(tt.rudders()[i], tt.r0s()[j], k);
        EXPECT_EQ(rw.y, n.y);
        EXPECT_EQ(rw.v, n.v);
        EXPECT_NEAR(tt.at(tt.rudders()[i], tt.r0s()[j], k * 10.0).x, n.x, 1e-9 * (1 + std::abs(n.x)));
      }
  // Between nodes: the mean of the neighbours at the midpoint (Fig. 3 with (r - r1)/(r2 - r1) = 1/2).
  const auto mid = tt.row(geo::deg2rad(5.0), tt.r0s()[0], 7);
  EXPECT_NEAR(mid.psi, 0.5 * (tt.node(2, 0, 7).psi + tt.node(3, 0, 7).psi), 1e-14);
  const auto half = tt.at(geo::deg2rad(10.0), 0.0, 75.0);
  EXPECT_NEAR(half.y, 0.5 * (tt.node(3, 1, 7).y + tt.node(3, 1, 8).y), 1e-9);
  EXPECT_THROW(tt.row(geo::deg2rad(25.0), 0.0, 3), std::out_of_range);
  EXPECT_THROW(tt.row(0.0, geo::deg2rad(0.3), 3), std::out_of_range);
  EXPECT_THROW(tt.at(0.0, 0.0, 100.5), std::out_of_range);
  EXPECT_THROW(tt.row(0.0, 0.0, 11), std::out_of_range);
}

TEST(TurningTables, PredictionIsTheTableTurnedToTheStart) {
  Ship s = make_ship("nomoto");
  const auto rud = range_deg(-20, 20, 10), r0 = range_deg(-0.2, 0.2, 0.2);
  const auto tt = load(tables_csv(s, rud, r0, 100.0, 10.0));
  const opp::StateVector rel = tt.at(geo::deg2rad(10.0), 0.0, 60.0);
  // Heading east (90 deg) from (1000, 2000): the table's forward x becomes +east.
  const opp::StateVector start{1000.0, 2000.0, geo::deg2rad(90.0), 0.0, 7.97, 0.0};
  const auto w = opp::predict(tt, start, geo::deg2rad(10.0), 60.0);
  EXPECT_NEAR(w.x, 1000.0 - rel.y, 1e-9);
  EXPECT_NEAR(w.y, 2000.0 + rel.x, 1e-9);
  EXPECT_NEAR(w.psi, geo::deg2rad(90.0) + rel.psi, 1e-12);
  EXPECT_EQ(w.r, rel.r);
  EXPECT_EQ(w.u, rel.u);
  // Distance travelled does not depend on the start.
  EXPECT_NEAR(std::hypot(w.x - 1000.0, w.y - 2000.0), std::hypot(rel.x, rel.y), 1e-9);
}

TEST(TurningTables, Eq4FindsTheTimeAndRudderOfAPointOnATrial) {
  Ship s = make_ship("mmg");
  const auto tt = load(tables_csv(s, range_deg(-35, 35, 5), range_deg(-0.2, 0.2, 0.1), 300.0, 10.0));
  // A point on the table's own +10 deg trial, half-way between two rows.
  const auto a = tt.row(geo::deg2rad(10.0), 0.0, 12), b = tt.row(geo::deg2rad(10.0), 0.0, 13);
  const Vec2 p{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
  const auto ps = opp::state_at_point(tt, 0.0, p);
  ASSERT_TRUE(ps.has_value());
  EXPECT_EQ(ps->state.x, p.x);
  EXPECT_NEAR(ps->t, 125.0, 0.2 * 10.0);                     // within a fifth of a table step
  EXPECT_NEAR(geo::rad2deg(ps->rudder), 10.0, 0.5 * 5.0);    // within half a rudder step
  EXPECT_LE(ps->node_t[0], 125.0);
  EXPECT_GE(ps->node_t[2], 125.0);
  EXPECT_FALSE(opp::state_at_point(tt, 0.0, {-500.0, 0.0}).has_value());  // behind the start
}

// ---- the loader refuses what is not a table, saying what is wrong -----------------------------

TEST(TurningTables, LoaderNamesWhatIsWrong) {
  Ship s = make_ship("nomoto");
  const std::string good = tables_csv(s, range_deg(-10, 10, 10), range_deg(-0.2, 0.2, 0.2), 30.0, 10.0);
  ASSERT_EQ(load_error(good), "");
  const auto L = lines_of(good);
  const std::size_t d = first_data_line(L);  // rows d.. : 3 rudders x 3 r0 x 4 times
  auto edited = [&](auto edit) {
    auto v = L;
    edit(v);
    return load_error(join(v));
  };
  auto expect_error = [](const std::string& msg, const std::string& part) {
    EXPECT_NE(msg.find(part), std::string::npos) << "message: '" << msg << "' lacks '" << part << "'";
  };
  expect_error(load_error(""), "no header");
  expect_error(load_error("# only a comment\n"), "no header");
  expect_error(edited([&](auto& v) { v.resize(d); }), "no data rows");
  expect_error(edited([&](auto& v) { v[d - 1] = "rudder,r0,t,x,y,psi,r,u,v"; }), "header must be");
  expect_error(edited([&](auto& v) { v[d + 2] = "-10,-0.2,20,nan,1,0,0,7.9,0"; }), "x_m is not finite");
  expect_error(edited([&](auto& v) { v[d + 2] = "-10,-0.2,20,abc,1,0,0,7.9,0"; }), "x_m 'abc' is not a number");
  expect_error(edited([&](auto& v) { v[d + 2] = "-10,-0.2,20,1,1,0,0,7.9"; }), "8 cells, expected 9");
  expect_error(edited([&](auto& v) { v[d + 2] = "-10,-0.2,20,1,1,0,0,7.9,0,5"; }), "more than 9 cells");
  expect_error(edited([&](auto& v) { v.erase(v.begin() + static_cast<long>(d + 2)); }), "missing or extra rows");
  // a whole trial missing: rudder 0, r0 0 (rows 4 .. 7 of that rudder's block)
  expect_error(edited([&](auto& v) { v.erase(v.begin() + static_cast<long>(d + 16), v.begin() + static_cast<long>(d + 20)); }),
               "missing trial (rudder 0 deg, r0 0 deg/s)");
  // two trials swapped: the r0 grid goes down
  expect_error(edited([&](auto& v) {
                 std::rotate(v.begin() + static_cast<long>(d), v.begin() + static_cast<long>(d + 4),
                             v.begin() + static_cast<long>(d + 8));
               }),
               "out of order");
  // a time out of step
  expect_error(edited([&](auto& v) {
                 auto& l = v[d + 2];
                 l.replace(l.find(",20,"), 4, ",25,");
               }),
               "time grid");
  // a t = 0 row that is not eq. 3
  expect_error(edited([&](auto& v) {
                 auto& l = v[d];
                 l.replace(l.find(",0,0,0,"), 7, ",0,5,0,");
               }),
               "is not eq. 3");
  expect_error(edited([&](auto& v) { v[d] = "-10,-0.2,0,0,0,0,0.1,7.97,0"; }), "is not eq. 3");  // r != r0
  try {
    opp::load_turning_tables_file("/nonexistent/tables.csv");
    FAIL() << "loaded a missing file";
  } catch (const std::runtime_error& e) {
    expect_error(e.what(), "cannot open");
  }
}

TEST(TurningTables, LoaderSurvivesMangledFiles) {
  Ship s = make_ship("nomoto");
  const std::string good = tables_csv(s, range_deg(-10, 10, 10), range_deg(-0.2, 0.2, 0.2), 30.0, 10.0);
  std::mt19937_64 rng(11);
  const std::string alphabet = "0123456789.,-+eE#\n nainf";
  int loaded = 0, refused = 0;
  for (int i = 0; i < 500; ++i) {
    std::string m = good;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = rng() % m.size();
      switch (rng() % 3) {
        case 0: m[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: m.erase(at, 1 + rng() % 40); break;
        default: m.insert(at, 1, alphabet[rng() % alphabet.size()]);
      }
    }
    try {
      load(m);
      ++loaded;  // an edit inside a number's digits can still be a valid table
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("t.csv:"), std::string::npos) << e.what();
      ++refused;
    }  // anything else escapes and fails the test
  }
  EXPECT_GT(refused, 250);
  EXPECT_EQ(loaded + refused, 500);
}

// ---- §2's accuracy check: 200 random starting conditions and rudder settings ------------------

// The paper (after eq. 4): in 200 experiments "the interpolation error did not exceed 10 % of the
// difference between the maximum and the minimum value of the measurements in the interpolation
// nodes (|max{f1..f4} - min{f1..f4}|)". check_accuracy measures that, per state parameter, against
// the MMG model itself (definitions in turning_tables.hpp). Measured here (MMG KVLCC2, 7.97 m/s,
// rudder -35..35 deg by 2.5, r0 -0.4..0.4 deg/s by 0.1, 300 s every 10 s; seed 1):
//  - Fig. 3 (bilinear table row): median of the cases' worst error 6 %; the claim "all <= 10 %" does
//    not hold (worst case u where the rudder nearly cancels r0: no turn, no speed loss, a peak of u
//    between two nodes that both slow down);
//  - eq. 4 (state at a point): median about 28 %, per parameter 14-19 %, the same with a finer
//    grid: eq. 4 is a weighted mean whose normalised weights (D - d_i)/3D never exceed 1/3, even
//    on a node, so near an edge of a long quad it is about a third of the spread off even for a
//    linear function.
//  - the quad's inverse bilinear map instead of eq. 4 (same quads): median 3.8 %, 153/193 <= 10 %.
// The test asserts what holds, and that the check does see a coarse table.
TEST(TurningTables, AccuracyCheckOf200RandomCases) {
  Ship s = make_ship("mmg");
  const auto r0 = range_deg(-0.4, 0.4, 0.1);
  const auto fine = load(tables_csv(s, range_deg(-35, 35, 2.5), r0, 300.0, 10.0));
  const auto coarse = load(tables_csv(s, range_deg(-35, 35, 17.5), range_deg(-0.4, 0.4, 0.4), 300.0, 10.0));
  opp::AccuracyParams prm;  // 200 cases, seed 1
  const auto f = opp::check_accuracy(fine, truth_of(s), prm);
  const auto c = opp::check_accuracy(coarse, truth_of(s), prm);
  ASSERT_EQ(f.fig3_pct.size(), 200u);
  auto within10 = [](const std::vector<double>& v) {
    return std::count_if(v.begin(), v.end(), [](double e) { return e <= 10.0; });
  };
  std::cout << "fine:   Fig. 3 max " << opp::max_of(f.fig3_pct) << " % median " << opp::median_of(f.fig3_pct)
            << " % (<= 10 %: " << within10(f.fig3_pct) << "/200; worst " << f.fig3_worst << ")\n"
            << "        eq. 4 max " << opp::max_of(f.eq4_pct) << " % median " << opp::median_of(f.eq4_pct)
            << " % (<= 10 %: " << within10(f.eq4_pct) << "/" << f.eq4_pct.size() << " located, " << f.eq4_other_rudder << " in another rudder's quad; worst " << f.eq4_worst
            << ")\n"
            << "coarse: Fig. 3 median " << opp::median_of(c.fig3_pct) << " %, eq. 4 median " << opp::median_of(c.eq4_pct)
            << " %\n";
  for (const auto& [name, v] : f.eq4_by_param) std::cout << "  eq. 4 " << name << " median " << opp::median_of(v) << " %\n";
  // Fig. 3 on the fine grid: the paper's 10 % for the typical case, every parameter's median too.
  EXPECT_LE(opp::median_of(f.fig3_pct), 10.0);
  for (const auto& [name, v] : f.fig3_by_param) EXPECT_LE(opp::median_of(v), 10.0) << name;
  EXPECT_GE(within10(f.fig3_pct), 120);
  // Eq. 4: nearly every point is located in the fan, its error is the weighted mean's (above).
  EXPECT_GE(f.eq4_pct.size(), 190u);
  EXPECT_LE(opp::median_of(f.eq4_pct), 40.0);
  for (const auto& [name, v] : f.eq4_by_param) EXPECT_LE(opp::median_of(v), 25.0) << name;
  // The quad's inverse bilinear map (not the paper's) on the same quads: within 10 % in the median.
  std::cout << "        inverse bilinear median " << opp::median_of(f.inv_pct) << " % (<= 10 %: "
            << within10(f.inv_pct) << "/" << f.inv_pct.size() << ")\n";
  EXPECT_GE(f.inv_pct.size(), 190u);
  EXPECT_LE(opp::median_of(f.inv_pct), 10.0);
  EXPECT_LT(3.0 * opp::median_of(f.inv_pct), opp::median_of(f.eq4_pct));
  // The check can fail: a table four times coarser in rudder and r0 is seen as clearly worse.
  EXPECT_GT(opp::median_of(c.fig3_pct), 3.0 * opp::median_of(f.fig3_pct));
  EXPECT_GT(opp::median_of(c.fig3_pct), 10.0);
  EXPECT_LT(within10(c.fig3_pct), within10(f.fig3_pct) / 2);
  // Same seed, same figures (the RNG is injected).
  EXPECT_EQ(opp::check_accuracy(fine, truth_of(s), prm).fig3_pct, f.fig3_pct);
}
