#include "mpgc/ship_bridge/node.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::ship_bridge {

void NodeParams::declare(rt::ParamSet& ps) {
  ps.add("gpsd.host", &gpsd_host, "127.0.0.1", "gpsd host");
  ps.add("gpsd.port", &gpsd_port, 2947, "-", 1, 65535, "gpsd TCP port");
  ps.add("gpsd.nmea", &gpsd_nmea, true, "also watch gpsd's raw NMEA (HDT/THS/ROT from talkers gpsd passes through)");
  ps.add("gpsd.reconnect", &gpsd_reconnect, 2.0, "s", 0.1, 600.0, "retry period while gpsd cannot be reached");
  ps.add("listen.host", &listen_host, "127.0.0.1", "IPv4 address the UDP inputs bind to");
  ps.add("gyro.port", &gyro_port, 0, "-", 0, 65535, "UDP port of the gyro compass NMEA (HDT/THS/ROT); 0 = none");
  ps.add("origin.source", &origin_source, "first_fix", "local NED origin: origin.lat/lon, or the first good fix",
         {"param", "first_fix"});
  ps.add("origin.lat", &origin_lat, 0.0, "deg", -90.0, 90.0, "NED origin latitude (origin.source = param)");
  ps.add("origin.lon", &origin_lon, 0.0, "deg", -180.0, 180.0, "NED origin longitude (origin.source = param)");
  ps.add("own.mmsi", &own_mmsi, 0, "-", 0, 999999999, "own ship's MMSI: its AIS messages are never a target");
  ps.add("period", &period, 0.1, "s", 0.01, 10.0, "nav/own_state period (inputs are polled at the same rate)");
  ps.add("nav.fix_timeout", &nav.fix_timeout, 3.0, "s", 0.1, 600.0, "a position older than this is invalid");
  ps.add("nav.heading_timeout", &nav.heading_timeout, 1.0, "s", 0.05, 600.0, "a heading / rate of turn older than this is invalid");
  ps.add("nav.feedback_timeout", &nav.feedback_timeout, 2.0, "s", 0.05, 600.0, "rudder/rpm feedback older than this is invalid");
  ps.add("nav.require_3d", &nav.require_3d, false, "a 2-D fix is invalid");
  ps.add("nav.max_speed", &nav.max_speed, 25.0, "m/s", 0.1, 200.0, "a position jump faster than this is rejected");
  ps.add("nav.jump_margin", &nav.jump_margin, 30.0, "m", 0.0, 10000.0, "GNSS noise allowance of the jump check");
  ps.add("nav.max_sog", &nav.max_sog, 40.0, "m/s", 0.1, 200.0, "a reported SOG above this is rejected");
  ps.add("actuators.host", &orders_host, "127.0.0.1", "IPv4 address of the steering gear / engine control (orders)");
  ps.add("actuators.port", &orders_port, 0, "-", 0, 65535, "UDP port orders (ROR, PRC) are sent to; 0 = no orders");
  ps.add("actuators.feedback_port", &feedback_port, 0, "-", 0, 65535, "UDP port for RSA/RPM feedback; 0 = none");
  ps.add("actuators.period", &order_period, 0.2, "s", 0.01, 10.0, "orders are repeated at this period");
  ps.add("actuators.command_timeout", &command_timeout, 1.0, "s", 0.05, 60.0,
         "no control/actuators this long: stop sending orders, the steering gear's own watchdog takes over");
  ps.add("actuators.max_rudder", &max_rudder_deg, 35.0, "deg", 1.0, 90.0, "rudder limit (orders beyond are saturated)");
  ps.add("actuators.min_rpm", &min_rpm, 0.0, "1/min", -10000.0, 10000.0, "lowest shaft speed order");
  ps.add("actuators.max_rpm", &max_rpm, 150.0, "1/min", 0.0, 10000.0, "highest shaft speed order");
}

void NodeParams::validate() const {
  if (min_rpm > max_rpm) throw std::invalid_argument("actuators.min_rpm is above actuators.max_rpm");
}

std::optional<geo::LatLon> NodeParams::origin() const {
  if (origin_source != "param") return std::nullopt;
  return geo::LatLon{geo::deg2rad(origin_lat), geo::deg2rad(origin_lon)};
}

ActuatorLimits NodeParams::limits() const { return {geo::deg2rad(max_rudder_deg), min_rpm, max_rpm}; }

bool gpsd_nmea_used(const std::string& line) {
  // gpsd sends a cycle's raw sentences before its TPV, so the verdict applies to that TPV (gpsd
  // reports an RMC "V" cycle with a position as a 3-D fix).
  static const char* kUsed[] = {"ROT", "THS", "GGA", "RMC"};
  return line.size() > 6 &&
         std::any_of(std::begin(kUsed), std::end(kUsed), [&](const char* t) { return line.compare(3, 3, t) == 0; });
}

WaterVelocity water_velocity(const NavOutput& o) {
  if (!o.velocity_valid || !o.heading_valid) return {std::nan(""), std::nan("")};
  const double beta = geo::angle_diff(o.cog, o.heading);
  return {o.sog * std::cos(beta), o.sog * std::sin(beta)};
}

OrderPacer::OrderPacer(const NodeParams& p)
    : timeout_ns_(static_cast<int64_t>(p.command_timeout * 1e9)), period_ns_(static_cast<int64_t>(p.order_period * 1e9)) {}

OrderPacer::Step OrderPacer::at(int64_t now_ns, bool have_cmd, int64_t cmd_ns) {
  Step s;
  s.fresh = have_cmd && now_ns - cmd_ns <= timeout_ns_;
  if (s.fresh && now_ns >= next_order_ns_) {
    s.send = true;
    next_order_ns_ = now_ns + period_ns_;
  }
  s.stopped = ordering_ && !s.fresh;
  ordering_ = s.fresh;
  return s;
}

std::string health_text(const NodeParams& p, const NavOutput& o, bool orders_stale, bool gpsd_connected) {
  std::string health = orders_stale ? "no fresh control/actuators: no orders sent" : "";
  if (!o.position_valid || !o.heading_valid || !o.velocity_valid)
    health = "navigation invalid: " + o.why_invalid + (health.empty() ? "" : "; " + health);
  if (!gpsd_connected)
    health = "gpsd " + p.gpsd_host + ":" + std::to_string(p.gpsd_port) + " not connected" + (health.empty() ? "" : "; " + health);
  return health;
}

}  // namespace mpgc::ship_bridge
