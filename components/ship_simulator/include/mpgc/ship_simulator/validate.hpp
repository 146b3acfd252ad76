// What the simulator refuses on control/actuators (for the DDS side only: a component main that
// links mpgc_msgs, and the fuzz targets in tests/fuzz/). Moved verbatim from
// components/ship_simulator/main.cpp (check_command, in its saturating form: only a non-finite
// order is refused; one beyond a limit is saturated and counted where it is taken).
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/control.hpp"

namespace mpgc::ship_simulator {

// Why an actuator command is unusable, or "" (design.md: reject, count, keep the last valid one).
inline std::string check_command(const msg::ActuatorCommand& c) {
  if (!std::isfinite(c.rudder)) return "rudder is not finite";
  if (!std::isfinite(c.propeller_rpm)) return "propeller_rpm is not finite";
  return "";
}

}  // namespace mpgc::ship_simulator
