// What the ship bridge refuses on control/actuators before encode_orders saturates it (for the DDS
// side only: a component main that links mpgc_msgs, and the fuzz targets in tests/fuzz/).
// Moved verbatim from the validator lambda of components/ship_bridge/main.cpp.
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/control.hpp"

namespace mpgc::ship_bridge {

inline std::string check_command(const msg::ActuatorCommand& a) {
  return std::isfinite(a.rudder) && std::isfinite(a.propeller_rpm) ? "" : "rudder or propeller_rpm is not finite";
}

}  // namespace mpgc::ship_bridge
