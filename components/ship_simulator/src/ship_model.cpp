#include "mpgc/ship_simulator/ship_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mpgc::ship_simulator {

bool ShipState::finite() const {
  for (double a : to_array())
    if (!std::isfinite(a)) return false;
  return true;
}

void Environment::validate() const {
  if (!std::isfinite(current_north) || std::abs(current_north) > 10.0)
    throw std::invalid_argument("current_north must be finite and within +-10 m/s");
  if (!std::isfinite(current_east) || std::abs(current_east) > 10.0)
    throw std::invalid_argument("current_east must be finite and within +-10 m/s");
  if (!std::isfinite(wind_speed) || wind_speed < 0.0 || wind_speed > 70.0)
    throw std::invalid_argument("wind_speed must be within 0..70 m/s");
  if (!std::isfinite(wind_from)) throw std::invalid_argument("wind_from must be finite");
}

void RK4ShipModel::set_state(const ShipState& s) {
  if (!s.finite()) throw std::invalid_argument("ship state has a NaN or infinite component");
  state_ = s;
}

void RK4ShipModel::step(double dt, const ShipCommand& cmd) {
  if (!(dt > 0.0) || !std::isfinite(dt)) throw std::invalid_argument("step dt must be finite and > 0");
  using A = std::array<double, ShipState::kSize>;
  const A y0 = state_.to_array();
  auto add = [](const A& a, const A& k, double h) {
    A o;
    for (int i = 0; i < ShipState::kSize; ++i) o[i] = a[i] + h * k[i];
    return o;
  };
  // Classical RK4, command held constant over the step.
  const A k1 = derivative(state_, cmd);
  const A k2 = derivative(ShipState::from_array(add(y0, k1, dt / 2)), cmd);
  const A k3 = derivative(ShipState::from_array(add(y0, k2, dt / 2)), cmd);
  const A k4 = derivative(ShipState::from_array(add(y0, k3, dt)), cmd);
  A y;
  for (int i = 0; i < ShipState::kSize; ++i) y[i] = y0[i] + dt / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  ShipState next = ShipState::from_array(y);
  if (!next.finite()) throw std::runtime_error(name() + " model diverged (non-finite state)");
  state_ = next;
}

double rudder_rate(double rudder, double command, double max_angle, double max_rate, double t_servo) {
  const double target = std::clamp(command, -max_angle, max_angle);
  return std::clamp((target - rudder) / t_servo, -max_rate, max_rate);
}

}  // namespace mpgc::ship_simulator
