// The ship's actuator limits: one description for the side that orders (guidance_control) and the
// side that obeys (the simulator's models, the steering gear and engine control). When the two
// disagree, an order the controller thinks legal is refused by the ship (hard-over orders at
// 0.6109 rad against a 35 deg = 0.610865 rad gear), so both take their defaults from here and
// both saturate rather than refuse an order beyond a limit.
//
//   const mpgc::ship::ActuatorLimits lim = mpgc::ship::kvlcc2_actuator_limits();
//   lim.validate();                                  // throws std::invalid_argument naming the field
//   const auto o = mpgc::ship::saturate(lim, rudder, rpm);   // finite inputs only
//   if (o.rudder_saturated) count("saturated.rudder");
//
// Header only, no DDS, no clock.
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mpgc::ship {

struct ActuatorLimits {
  double max_rudder = 0.0;       // [rad] rudder angle limit, both sides (|rudder| <= max_rudder)
  double max_rudder_rate = 0.0;  // [rad/s] steering gear's rudder rate
  double min_rpm = 0.0;          // [1/min] lowest shaft speed order (0: ahead only)
  double max_rpm = 0.0;          // [1/min] highest shaft speed order

  // Throws std::invalid_argument naming the first bad field; `who` prefixes the message.
  void validate(const std::string& who = "ActuatorLimits") const {
    const double kRightAngle = 1.5707963267948966;
    if (!std::isfinite(max_rudder) || max_rudder <= 0.0 || max_rudder > kRightAngle)
      throw std::invalid_argument(who + ".max_rudder must be in (0, pi/2] rad, got " + std::to_string(max_rudder));
    if (!std::isfinite(max_rudder_rate) || max_rudder_rate <= 0.0 || max_rudder_rate > 1.0)
      throw std::invalid_argument(who + ".max_rudder_rate must be in (0, 1] rad/s, got " +
                                  std::to_string(max_rudder_rate));
    if (!std::isfinite(min_rpm) || !std::isfinite(max_rpm) || !(max_rpm > min_rpm))
      throw std::invalid_argument(who + ".min_rpm/max_rpm must be finite with max_rpm > min_rpm, got [" +
                                  std::to_string(min_rpm) + ", " + std::to_string(max_rpm) + "]");
  }
};

// The default ship of this project: KVLCC2 at full scale (the simulator's MMG and Nomoto models).
// 35 deg and 2.32 deg/s are SIMMAN 2008's steering gear (kvlcc2_mmg_parameters.csv, delta_rate);
// 0..150 rpm: ahead only (the MMG propeller model is for n > 0), above the ~105 rpm the model needs
// for 15.5 kn.
inline ActuatorLimits kvlcc2_actuator_limits() {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  return {35.0 * kDeg, 2.32 * kDeg, 0.0, 150.0};
}

struct SaturatedOrder {
  double rudder = 0.0;  // [rad] within +-max_rudder
  double rpm = 0.0;     // [1/min] within [min_rpm, max_rpm]
  bool rudder_saturated = false;
  bool rpm_saturated = false;
};

// Clips an order to the limits and says which part was clipped. Non-finite orders are not
// saturated but refused by the caller (a NaN says the sender is broken, not that it asked much).
inline SaturatedOrder saturate(const ActuatorLimits& lim, double rudder, double rpm) {
  SaturatedOrder o;
  o.rudder = std::clamp(rudder, -lim.max_rudder, lim.max_rudder);
  o.rpm = std::clamp(rpm, lim.min_rpm, lim.max_rpm);
  o.rudder_saturated = o.rudder != rudder;
  o.rpm_saturated = o.rpm != rpm;
  return o;
}

}  // namespace mpgc::ship
