// Synthetic trajectories for the evaluation tests: ships that sail straight and obey scripted
// course/speed orders with a finite turn rate (kinematics only, exact enough for verdicts).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/scenario_runner/evaluation.hpp"

namespace mpgc::scenario_runner::synthetic {

struct Order {
  double t;       // [s] when the order is given
  double course;  // [rad] new course
  double speed;   // [m/s] new speed (reached at once)
};

inline std::vector<double> times(double t_end, double dt) {
  std::vector<double> t;
  for (int i = 0; i * dt <= t_end + 1e-9; ++i) t.push_back(i * dt);
  return t;
}

// Integrates a ship along `t`, turning towards the ordered course at `rate` [rad/s].
inline ShipTrack sail(std::uint32_t id, double length, double x, double y, double course, double speed,
                      const std::vector<Order>& orders, const std::vector<double>& t,
                      double rate = geo::deg2rad(3.0)) {
  ShipTrack tr;
  tr.id = id;
  tr.length = length;
  double h = course, cmd = course, u = speed;
  std::size_t k = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (i > 0) {
      const double dt = t[i] - t[i - 1];
      const double err = geo::angle_diff(cmd, h);
      h = geo::wrap_pi(h + std::clamp(err, -rate * dt, rate * dt));
      x += u * dt * std::cos(h);
      y += u * dt * std::sin(h);
    }
    for (; k < orders.size() && orders[k].t <= t[i]; ++k) cmd = orders[k].course, u = orders[k].speed;
    tr.states.push_back({x, y, h, h, u});
  }
  return tr;
}

// A run with the given own ship and targets, goal far away, no plans.
inline RunRecord run_of(const std::vector<double>& t, ShipTrack own, std::vector<ShipTrack> targets,
                        double d_safety = 100.0) {
  RunRecord r;
  r.t = t;
  r.own = std::move(own);
  r.targets = std::move(targets);
  r.safety_distance = d_safety;
  r.goal = {1e6, 0.0, 100.0};
  return r;
}

}  // namespace mpgc::scenario_runner::synthetic
