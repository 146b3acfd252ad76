#include "mpgc/ship_simulator/nomoto_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace mpgc::ship_simulator {
namespace {
void positive(double v, const char* name) {
  if (!(v > 0.0) || !std::isfinite(v)) throw std::invalid_argument(std::string("NomotoParams.") + name + " must be > 0");
}
}  // namespace

void NomotoParams::validate() const {
  positive(K_ref, "K_ref");
  positive(T_ref, "T_ref");
  positive(L_ref, "L_ref");
  positive(U_ref, "U_ref");
  positive(L, "L");
  positive(B, "B");
  positive(service_speed, "service_speed");
  positive(service_rpm, "service_rpm");
  positive(speed_time_constant, "speed_time_constant");
  positive(max_rudder, "max_rudder");
  positive(rudder_rate, "rudder_rate");
  positive(rudder_servo_t, "rudder_servo_t");
  positive(rpm_time_constant, "rpm_time_constant");
  positive(max_rpm, "max_rpm");
  ship::ActuatorLimits{max_rudder, rudder_rate, 0.0, max_rpm}.validate("NomotoParams");
}

NomotoParams load_nomoto_csv(const std::string& path, const std::string& ship, double speed) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open Nomoto file '" + path + "'");
  std::string line;
  std::getline(in, line);
  if (line.rfind("ship,L_m,speed_mps,K_1_per_s,T_s", 0) != 0)
    throw std::runtime_error(path + ": unexpected header '" + line + "'");
  NomotoParams best;
  double best_dist = std::numeric_limits<double>::infinity();
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) f.push_back(cell);
    if (f.size() < 5 || f[0].find(ship) == std::string::npos) continue;
    char* end = nullptr;
    double v[4];
    for (int i = 0; i < 4; ++i) {
      v[i] = std::strtod(f[1 + i].c_str(), &end);
      if (end == f[1 + i].c_str() || !std::isfinite(v[i])) throw std::runtime_error(path + ": bad number in '" + line + "'");
    }
    const double dist = std::abs(v[1] - speed);
    if (dist < best_dist) {
      best_dist = dist;
      best.L_ref = v[0];
      best.U_ref = v[1];
      best.K_ref = v[2];
      best.T_ref = v[3];
    }
  }
  if (!std::isfinite(best_dist)) throw std::runtime_error(path + ": no row for ship '" + ship + "'");
  return best;
}

NomotoModel::NomotoModel(NomotoParams p) : p_(std::move(p)) { p_.validate(); }

std::array<double, ShipState::kSize> NomotoModel::derivative(const ShipState& s, const ShipCommand& cmd) const {
  // Non-dimensional K' = K L/U and T' = T U/L are taken as speed- and size-independent, so the
  // reference ship's K, T scale to this ship at its current speed (floored at 0.5 m/s).
  const double U = std::max(std::abs(s.u), 0.5);
  const double Kp = p_.K_ref * p_.L_ref / p_.U_ref, Tp = p_.T_ref * p_.U_ref / p_.L_ref;
  const double K = Kp * U / p_.L, T = Tp * p_.L / U;
  const double rpm_cmd = std::clamp(cmd.rpm, 0.0, p_.max_rpm);
  const double u_ss = p_.service_speed * s.rpm / p_.service_rpm;
  const double c = std::cos(s.psi), sn = std::sin(s.psi);
  return {s.u * c + env_.current_north,
          s.u * sn + env_.current_east,
          s.r,
          (u_ss - s.u) / p_.speed_time_constant,
          -s.v,  // no sway in this model: any v decays
          (K * s.rudder - s.r) / T,
          rudder_rate(s.rudder, cmd.rudder, p_.max_rudder, p_.rudder_rate, p_.rudder_servo_t),
          (rpm_cmd - s.rpm) / p_.rpm_time_constant};
}

}  // namespace mpgc::ship_simulator
