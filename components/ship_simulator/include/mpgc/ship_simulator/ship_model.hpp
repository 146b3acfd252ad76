// The own-ship dynamics interface: one state, one command, one step. The MMG model, the Nomoto
// model, another hull or a hardware bridge all sit behind ShipModel, so the simulator does not
// care which one moves the ship.
#pragma once

#include <array>
#include <string>

#include "mpgc/ship/actuator_limits.hpp"

namespace mpgc::ship_simulator {

// State of a 3DOF ship (design.md conventions: NED, heading clockwise from north).
struct ShipState {
  double x = 0.0;       // [m] north position of midship
  double y = 0.0;       // [m] east position of midship
  double psi = 0.0;     // [rad] heading, clockwise from north (not wrapped while integrating)
  double u = 0.0;       // [m/s] surge speed through the water
  double v = 0.0;       // [m/s] sway speed through the water at midship, positive to starboard
  double r = 0.0;       // [rad/s] yaw rate, positive turning to starboard
  double rudder = 0.0;  // [rad] actual rudder angle, positive turns the ship to starboard
  double rpm = 0.0;     // [1/min] actual propeller speed

  static constexpr int kSize = 8;
  std::array<double, kSize> to_array() const { return {x, y, psi, u, v, r, rudder, rpm}; }
  static ShipState from_array(const std::array<double, kSize>& a) {
    return {a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]};
  }
  bool finite() const;
};

// What the actuators are told (topic control/actuators, after validation).
struct ShipCommand {
  double rudder = 0.0;  // [rad] commanded rudder angle, positive to starboard
  double rpm = 0.0;     // [1/min] commanded propeller speed
};

// Constant environment, both optional (zero by default).
struct Environment {
  double current_north = 0.0;   // [m/s] current velocity (setting towards), north component
  double current_east = 0.0;    // [m/s] current velocity, east component
  double wind_speed = 0.0;      // [m/s] true wind speed
  double wind_from = 0.0;       // [rad] direction the wind comes FROM, clockwise from north
  void validate() const;
};

class ShipModel {
 public:
  virtual ~ShipModel() = default;
  virtual std::string name() const = 0;
  virtual const ShipState& state() const = 0;
  virtual void set_state(const ShipState& s) = 0;
  // Advances the model by dt [s] with the command held constant over the step. The command is
  // saturated to the actuator limits here (the caller refuses non-finite orders before).
  virtual void step(double dt, const ShipCommand& cmd) = 0;
  virtual void set_environment(const Environment& env) = 0;
  virtual double length() const = 0;       // [m] length between perpendiculars
  virtual double beam() const = 0;         // [m]
  // The steering gear and engine limits of this hull (mpgc/ship/actuator_limits.hpp): what the
  // actuators obey, and what guidance_control's defaults must equal for the default ship.
  virtual ship::ActuatorLimits actuator_limits() const = 0;
  double max_rudder() const { return actuator_limits().max_rudder; }  // [rad] rudder angle limit
  double max_rpm() const { return actuator_limits().max_rpm; }        // [1/min] largest propeller speed
};

// A model given by a state derivative f(state, command), integrated by classical RK4 with the
// command held over the step (zero-order hold).
class RK4ShipModel : public ShipModel {
 public:
  const ShipState& state() const override { return state_; }
  void set_state(const ShipState& s) override;
  void step(double dt, const ShipCommand& cmd) override;
  void set_environment(const Environment& env) override {
    env.validate();
    env_ = env;
  }
  const Environment& environment() const { return env_; }
  virtual std::array<double, ShipState::kSize> derivative(const ShipState& s, const ShipCommand& cmd) const = 0;

 protected:
  ShipState state_;
  Environment env_;
};

// Actuator dynamics shared by the models: a rudder servo that follows the command with a first-
// order lag of time constant t_servo but never faster than max_rate, and a first-order propeller.
double rudder_rate(double rudder, double command, double max_angle, double max_rate, double t_servo);

}  // namespace mpgc::ship_simulator
