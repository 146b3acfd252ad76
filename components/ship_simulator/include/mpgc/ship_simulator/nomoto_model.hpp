// First-order Nomoto model (T r_dot + r = K delta) with a first-order speed response to the
// propeller: the fast, simple alternative to MMG. No sway (v = 0): the ship turns on its track.
#pragma once

#include <string>

#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::ship_simulator {

struct NomotoParams {
  double K_ref = 0.0;          // [1/s] Nomoto gain at the reference ship and speed
  double T_ref = 0.0;          // [s] Nomoto time constant at the reference ship and speed
  double L_ref = 0.0;          // [m] length of the ship K, T were identified for
  double U_ref = 0.0;          // [m/s] speed K, T were identified at
  double L = 0.0;              // [m] length of the simulated ship (K' = K L/U, T' = T U/L kept)
  double B = 0.0;              // [m] beam of the simulated ship
  double service_speed = 0.0;  // [m/s] speed reached at service_rpm
  double service_rpm = 0.0;    // [1/min] propeller speed for service_speed (speed ~ rpm)
  double speed_time_constant = 0.0;  // [s] surge response to a propeller change
  double max_rudder = 0.0;     // [rad]
  double rudder_rate = 0.0;    // [rad/s]
  double rudder_servo_t = 0.5; // [s]
  double rpm_time_constant = 15.0;  // [s]
  double max_rpm = 0.0;        // [1/min]
  void validate() const;
};

// Reads nomoto_kt.csv and takes the row whose `ship` contains `ship` (case-sensitive) with the
// speed nearest `speed` [m/s]. Fills K_ref, T_ref, L_ref, U_ref; the caller sets the rest.
// Throws std::runtime_error naming the file and what is missing.
NomotoParams load_nomoto_csv(const std::string& path, const std::string& ship, double speed);

class NomotoModel final : public RK4ShipModel {
 public:
  explicit NomotoModel(NomotoParams p);
  std::string name() const override { return "nomoto"; }
  std::array<double, ShipState::kSize> derivative(const ShipState& s, const ShipCommand& cmd) const override;
  double length() const override { return p_.L; }
  double beam() const override { return p_.B; }
  ship::ActuatorLimits actuator_limits() const override { return {p_.max_rudder, p_.rudder_rate, 0.0, p_.max_rpm}; }
  const NomotoParams& params() const { return p_; }

 private:
  NomotoParams p_;
};

}  // namespace mpgc::ship_simulator
