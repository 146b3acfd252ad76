// Heading autopilot (PID with anti-windup, derivative on the measured yaw rate, rudder angle and
// rate limits) and speed control on propeller rpm (feed-forward from a speed -> rpm map plus PI),
// with pole-placement tuning of the heading PID from first-order Nomoto K, T. No DDS, no clock.
#pragma once

#include <string>
#include <vector>

#include "mpgc/ship/actuator_limits.hpp"

namespace mpgc::guidance_control {

// Defaults: KVLCC2 (simulator's MMG model) at 7 m/s, Nomoto fit K = 0.033 1/s, T = 75 s, pole
// placement with omega_n = 0.04 rad/s, zeta = 1, integral_ratio 20 (README.md "Tuning"; test
// Kvlcc2.NomotoFitAndDefaultGainsFromIt checks the defaults still match the model). The rudder
// limits are the ship's (mpgc/ship/actuator_limits.hpp, the same the simulator's KVLCC2 obeys).
struct HeadingAutopilotParams {
  double kp = 3.7;                 // [rad/rad] rudder per heading error
  double ki = 0.0075;              // [1/s] rudder per integrated heading error
  double kd = 150.0;               // [s] rudder per yaw rate (derivative on the measurement)
  double max_rudder = ship::kvlcc2_actuator_limits().max_rudder;            // [rad] 35 deg
  double max_rudder_rate = ship::kvlcc2_actuator_limits().max_rudder_rate;  // [rad/s] 2.32 deg/s
  double integral_limit = 0.1745;  // [rad] bound of the integral's rudder contribution (10 deg)
  void validate() const;           // throws std::invalid_argument naming the bad field
};

// delta = kp e + ki int(e) - kd r, e = wrap(psi_d - psi); positive rudder turns to starboard.
// Anti-windup: the integral does not grow while the output is held by the angle or rate limit in
// the direction the error pushes (conditional integration), and it is bounded by integral_limit.
class HeadingAutopilot {
 public:
  explicit HeadingAutopilot(const HeadingAutopilotParams& p);
  // Forgets the integral and starts the rate limit from `rudder` [rad].
  void reset(double rudder = 0.0);
  // One step: desired heading, measured heading [rad], measured yaw rate [rad/s], dt [s] -> rudder [rad].
  double update(double psi_d, double psi, double r, double dt);
  double integral() const { return integral_; }  // [rad]
  // The last update asked for more rudder than max_rudder (clipped to it).
  bool saturated() const { return saturated_; }
  const HeadingAutopilotParams& params() const { return p_; }

 private:
  HeadingAutopilotParams p_;
  double integral_ = 0.0;
  double last_ = 0.0;
  bool saturated_ = false;
};

// Defaults: the simulator's KVLCC2 MMG model, whose self-propulsion rpm is 13.17 rpm per m/s
// (105.4 rpm at 8 m/s; MARIN's model tests needed ~92 rpm at 15.5 kn with a different propeller):
// rpm is proportional to speed for a fixed-pitch propeller at constant advance ratio.
struct SpeedControllerParams {
  std::vector<double> map_speed{0.0, 8.0};  // [m/s] speed -> rpm map: speeds, strictly increasing
  std::vector<double> map_rpm{0.0, 105.4};  // [1/min] rpm at those speeds in calm water
  double kp = 30.0;                         // [rpm/(m/s)] proportional gain on the speed error
  double ki = 0.04;                         // [rpm/m] integral gain (tuned on the KVLCC2 MMG model)
  double integral_limit = 20.0;             // [1/min] bound of the integral's contribution
  double integral_zone = 0.3;               // [m/s] integrate only while |speed error| < this: a tanker's
                                            // slow speed change would otherwise wind the integral up
  double min_rpm = ship::kvlcc2_actuator_limits().min_rpm;  // [1/min] lowest command (0: ahead only)
  double max_rpm = ship::kvlcc2_actuator_limits().max_rpm;  // [1/min] highest command (the engine's 150)
  double max_rpm_rate = 2.0;                // [1/min/s] slew limit of the command
  void validate() const;                    // throws std::invalid_argument naming the bad field
};

// Parses a speed -> rpm map "speed:rpm, speed:rpm, ..." ([m/s]:[1/min]) into p.map_speed/map_rpm.
// Throws std::invalid_argument naming the malformed entry.
void parse_speed_map(const std::string& text, SpeedControllerParams& p);
std::string format_speed_map(const SpeedControllerParams& p);

class SpeedController {
 public:
  explicit SpeedController(const SpeedControllerParams& p);
  void reset(double rpm = 0.0);
  // Feed-forward rpm for a speed (piecewise linear, linear extrapolation past the last point).
  double feedforward(double speed) const;
  // One step: desired speed, measured surge speed [m/s], dt [s] -> propeller rpm [1/min].
  double update(double u_d, double u, double dt);
  double integral() const { return integral_; }  // [1/min]
  // The last update asked for an rpm outside [min_rpm, max_rpm] (clipped to it).
  bool saturated() const { return saturated_; }
  const SpeedControllerParams& params() const { return p_; }

 private:
  SpeedControllerParams p_;
  double integral_ = 0.0;
  double last_ = 0.0;
  bool saturated_ = false;
};

// First-order Nomoto model T r' + r = K delta.
struct NomotoModel {
  double K = 0.0;  // [1/s] rudder-to-yaw-rate gain
  double T = 0.0;  // [s] time constant
};

// Pole placement (Fossen 2011, section 15.3): with delta = -(kp e + kd r + ki int e) the closed loop
// T psi'' + (1 + K kd) psi' + K kp psi = K kp psi_d has natural frequency omega_n and damping zeta when
//   kp = T omega_n^2 / K,  kd = (2 zeta omega_n T - 1) / K,  ki = omega_n kp / integral_ratio
// (Fossen's rule of thumb is integral_ratio = 10; 20 halves the overshoot the integral's zero adds to
// small steps). Limits are copied from `base`. Throws std::invalid_argument for K <= 0, T <= 0,
// omega_n <= 0, zeta <= 0 or integral_ratio <= 0, or when kd would be negative (omega_n too low for
// this hull: raise it).
HeadingAutopilotParams tune_heading_pid(const NomotoModel& m, double omega_n, double zeta,
                                        const HeadingAutopilotParams& base = {}, double integral_ratio = 10.0);

}  // namespace mpgc::guidance_control
