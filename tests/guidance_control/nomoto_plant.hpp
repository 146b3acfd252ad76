// A tiny test plant: first-order Nomoto yaw (T r' + r = K delta) with a rate-limited rudder servo,
// first-order surge towards the speed the rpm gives in calm water, and a constant current.
// K, T come from ../shared/data/ship_models/nomoto_kt.csv (Mariner class cargo ship).
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "mpgc/guidance_control/autopilot.hpp"
#include "mpgc/testing.hpp"

namespace mpgc::guidance_control::test {

struct NomotoRow {
  double L = 0.0, U = 0.0, K = 0.0, T = 0.0;
};

// The first row of nomoto_kt.csv whose ship name starts with `ship`.
inline NomotoRow read_nomoto(const std::string& ship) {
  const std::string path = mpgc::testing::shared_data("ship_models/nomoto_kt.csv");
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::getline(in, line);  // header: ship,L_m,speed_mps,K_1_per_s,T_s,...
  while (std::getline(in, line)) {
    if (line.rfind(ship, 0) != 0) continue;
    std::stringstream ss(line);
    std::string f[5];
    for (auto& s : f) std::getline(ss, s, ',');
    return {std::stod(f[1]), std::stod(f[2]), std::stod(f[3]), std::stod(f[4])};
  }
  throw std::runtime_error("no row for " + ship + " in " + path);
}

struct NomotoPlant {
  // Model.
  double K = 0.185, T = 107.3;           // [1/s], [s]
  double max_rudder = 0.6109;            // [rad]
  double rudder_rate = 0.0401;           // [rad/s]
  double rpm_per_mps = 13.175;            // [1/min per m/s] calm-water speed map (matches the default)
  double surge_t = 200.0;                // [s] surge time constant
  double current_n = 0.0, current_e = 0.0;  // [m/s]
  // State.
  double x = 0.0, y = 0.0, psi = 0.0, u = 7.0, r = 0.0, rudder = 0.0, rpm = 92.225;

  void step(double dt, double rudder_cmd, double rpm_cmd) {
    const double target = std::clamp(rudder_cmd, -max_rudder, max_rudder);
    rudder += std::clamp(target - rudder, -rudder_rate * dt, rudder_rate * dt);
    rpm = rpm_cmd;  // propeller speed follows at once; the hull is the slow part
    r += dt * (K * rudder - r) / T;
    u += dt * (rpm / rpm_per_mps - u) / surge_t;
    psi += dt * r;
    x += dt * (u * std::cos(psi) + current_n);
    y += dt * (u * std::sin(psi) + current_e);
  }
};

}  // namespace mpgc::guidance_control::test
