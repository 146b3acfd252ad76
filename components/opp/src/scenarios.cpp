#include "mpgc/opp/scenarios.hpp"

#include "mpgc/opp/chart_obstacles.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

namespace mpgc::opp {

namespace {
constexpr double kPi = 3.14159265358979323846;
Vec2 course(double deg, double speed) { return {speed * std::cos(deg * kPi / 180.0), speed * std::sin(deg * kPi / 180.0)}; }
}  // namespace

Scenario paper_scenario(int n, double L, double speed) {
  if (n < 1 || n > 3) throw std::invalid_argument("paper_scenario: n must be 1, 2 or 3");
  Scenario s;
  s.name = "seed000-scenario" + std::to_string(n);
  Problem& pb = s.problem;
  pb.start = {0, 0};
  pb.heading = kPi / 4;
  pb.speed = speed;
  pb.goal.p = {100 * L, 100 * L};
  pb.bounds = {0, 0, 100 * L, 100 * L};
  pb.colreg = true;
  // Table 1 (positions [N, E] in Lpp, routes in degrees).
  if (n == 1) {
    pb.targets = {{1, {0, 100 * L}, course(315, speed)}, {2, {100 * L, 25 * L}, course(135, speed)}};
  } else if (n == 2) {
    pb.targets = {{1, {90 * L, 100 * L}, course(240, speed)}, {2, {40 * L, 100 * L}, course(270, speed)}};
  } else {
    pb.targets = {{1, {100 * L, 100 * L}, course(225, speed)}};
    std::vector<Vec2> walls;
    const double half = 25 * L;
    const Vec2 u{std::sqrt(0.5), std::sqrt(0.5)}, nrm{-std::sqrt(0.5), std::sqrt(0.5)};
    for (double t = -40 * L; t <= 180 * L; t += L)
      for (double side : {-1.0, 1.0}) walls.push_back(t * u + (side * half) * nrm);
    s.fixed = point_obstacles(std::move(walls));
    pb.fixed = s.fixed.get();
  }
  Params& p = s.params;
  p.safety_distance = 10 * L;
  p.colreg_distance = 30 * L;
  p.step = 5 * L;
  p.max_turn = kPi / 3;
  p.gamma_l = 1.0;
  p.gamma_s = 5 * L;          // 1 rad^2 of steering weighs like 5 Lpp of extra length
  p.gamma_m = 10 * L * L;     // 1/d margin terms: 1 Lpp per waypoint at d = 10 Lpp
  p.gamma_f = 10 * L * L;
  p.goal_bias = 0.05;
  p.max_iterations = 20000;
  p.time_budget = 0.5;
  p.restart_after = 1000;     // fresh trees when stuck (measured: lower median and worst cost)
  return s;
}

Scenario paper_scenario1_frozen(double L, double speed) {
  Scenario s = paper_scenario(1, L, speed);
  s.name = "seed000-scenario1-frozen";
  std::vector<Disc> discs;
  const Vec2 dir = (1.0 / norm(s.problem.goal.p - s.problem.start)) * (s.problem.goal.p - s.problem.start);
  for (const Target& t : s.problem.targets) {
    // Time of closest approach with the own ship on the straight route at `speed`.
    const Vec2 r = t.p - s.problem.start, dv = t.v - speed * dir;
    const double tc = std::max(0.0, -dot(r, dv) / norm2(dv));
    discs.push_back({t.p + tc * t.v, s.params.safety_distance});
  }
  s.problem.targets.clear();
  s.fixed = std::make_shared<DiscObstacles>(discs);
  s.problem.fixed = s.fixed.get();
  s.problem.colreg = false;
  s.params.safety_distance = 0.0;  // the discs already are the safety zones
  s.params.colreg_distance = 0.0;
  s.params.max_turn = kPi;
  s.params.gamma_s = s.params.gamma_f = s.params.gamma_m = 0.0;
  s.params.gamma_l = 1.0;
  s.params.restart_after = 0;  // plain RRT*, as OMPL's
  return s;
}

Scenario disc_world() {
  Scenario s;
  s.name = "disc-world-100";
  Problem& pb = s.problem;
  pb.start = {5, 5};
  pb.heading = kPi / 4;
  pb.speed = 1.0;
  pb.goal.p = {95, 95};
  pb.bounds = {0, 0, 100, 100};
  pb.colreg = false;
  s.fixed = std::make_shared<DiscObstacles>(std::vector<Disc>{
      {{50, 50}, 12}, {{25, 30}, 8}, {{72, 65}, 9}, {{30, 75}, 10}, {{75, 25}, 10}});
  pb.fixed = s.fixed.get();
  Params& p = s.params;
  p.safety_distance = 0.0;
  p.colreg_distance = 0.0;
  p.max_turn = kPi;
  p.gamma_l = 1.0;
  p.step = 5.0;
  p.goal_bias = 0.05;
  p.rewire_factor = 1.1;
  p.max_iterations = 5000;
  return s;
}

std::vector<Target> random_targets(const Problem& pb, int n, double speed, uint64_t seed) {
  std::mt19937_64 g(seed);
  auto u = [&] { return static_cast<double>(g() >> 11) * (1.0 / 9007199254740992.0); };
  std::vector<Target> out;
  const Bounds& b = pb.bounds;
  for (int i = 0; i < n; ++i) {
    // Start on the boundary box, heading roughly across the map.
    const Vec2 p{b.min_x + u() * (b.max_x - b.min_x), b.min_y + u() * (b.max_y - b.min_y)};
    const Vec2 c{0.5 * (b.min_x + b.max_x), 0.5 * (b.min_y + b.max_y)};
    const double ang = std::atan2(c.y - p.y, c.x - p.x) + (u() - 0.5) * kPi / 2;
    Target t;
    t.id = static_cast<uint32_t>(100 + i);
    t.p = p;
    t.v = {speed * std::cos(ang), speed * std::sin(ang)};
    out.push_back(t);
  }
  return out;
}

std::vector<Vec2> random_points(const Problem& pb, int n, double keep_out, uint64_t seed) {
  std::mt19937_64 g(seed);
  auto u = [&] { return static_cast<double>(g() >> 11) * (1.0 / 9007199254740992.0); };
  const Bounds& b = pb.bounds;
  // 40 round islands (radius 2 % of the map) whose shores stay `keep_out` from the straight
  // route; the points fill them uniformly, like densified shore lines and point features.
  const double rad = 0.02 * std::max(b.max_x - b.min_x, b.max_y - b.min_y);
  std::vector<Vec2> centres;
  for (int guard = 0; centres.size() < 40 && guard < 100000; ++guard) {
    const Vec2 c{b.min_x + u() * (b.max_x - b.min_x), b.min_y + u() * (b.max_y - b.min_y)};
    if (point_segment_dist2(c, pb.start, pb.goal.p) < (keep_out + rad) * (keep_out + rad)) continue;
    if (norm2(c - pb.start) < 4 * keep_out * keep_out || norm2(c - pb.goal.p) < 4 * keep_out * keep_out) continue;
    centres.push_back(c);
  }
  std::vector<Vec2> out;
  if (centres.empty()) return out;
  out.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Vec2 c = centres[static_cast<size_t>(i) % centres.size()];
    const double r = rad * std::sqrt(u()), a = 2 * kPi * u();
    out.push_back(c + Vec2{r * std::cos(a), r * std::sin(a)});
  }
  return out;
}

}  // namespace mpgc::opp
