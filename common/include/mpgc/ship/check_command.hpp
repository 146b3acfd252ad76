// What every ship side refuses on control/actuators: the simulator and the ship bridge (for the
// DDS side only: a main that links mpgc_msgs, and the fuzz targets in tests/fuzz/). Only a
// non-finite order is refused; one beyond a limit is saturated and counted where it is taken
// (actuator_limits.hpp), as real steering gear and engine controls do.
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/control.hpp"

namespace mpgc::ship {

// Why an actuator command is unusable, or "" (design.md: reject, count, keep the last valid one).
inline std::string check_command(const msg::ActuatorCommand& c) {
  if (!std::isfinite(c.rudder)) return "rudder is not finite";
  if (!std::isfinite(c.propeller_rpm)) return "propeller_rpm is not finite";
  return "";
}

}  // namespace mpgc::ship
