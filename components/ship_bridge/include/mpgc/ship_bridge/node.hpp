// The bridge component's logic without DDS, sockets or a clock (mpgc_ship_bridge's main.cpp is
// wiring around it): its named parameters, which of gpsd's raw NMEA it uses, the through-water
// velocity it reports without a speed log, when orders go out on the actuator wire, and the health
// it says (times in ns come from the caller).
//
//   sb::NodeParams p;  p.declare(ps);  ps.validate_and_apply();  p.validate();
//   sb::OrderPacer pacer(p);  auto step = pacer.at(now, have_cmd, cmd_ns);  if (step.send) ...
//   std::string health = sb::health_text(p, nav_output, orders_stale, gpsd_connected);
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/ship_bridge/bridge.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::ship_bridge {

struct NodeParams {
  std::string gpsd_host;
  int gpsd_port = 2947;
  bool gpsd_nmea = true;
  double gpsd_reconnect = 2.0;  // [s]
  std::string listen_host;
  int gyro_port = 0;            // 0: no direct gyro input
  std::string origin_source;    // param | first_fix
  double origin_lat = 0, origin_lon = 0;  // [deg]
  int own_mmsi = 0;
  double period = 0.1;          // [s] nav/own_state period and input polling
  NavParams nav;
  std::string orders_host;
  int orders_port = 0;          // 0: no actuator wire (monitoring only)
  int feedback_port = 0;
  double order_period = 0.2;    // [s] orders are repeated: the steering gear's watchdog wants them
  double command_timeout = 1.0; // [s] no control/actuators this long: stop sending orders
  double max_rudder_deg = 35.0, min_rpm = 0.0, max_rpm = 150.0;

  void declare(rt::ParamSet& ps);
  void validate() const;  // what the ranges cannot: throws std::invalid_argument
  std::optional<geo::LatLon> origin() const;  // origin.source = param: origin.lat/lon; else the first fix
  ActuatorLimits limits() const;
};

// gpsd's raw sentences the bridge takes itself: what gpsd does not decode ($TIROT, THS) and the
// receiver's own verdict on its fix (GGA quality, RMC status).
bool gpsd_nmea_used(const std::string& line);

// Through-water velocity [m/s] from SOG/COG and heading (exact without current); NaN unless
// velocity and heading are valid.
struct WaterVelocity {
  double u, v;
};
WaterVelocity water_velocity(const NavOutput& o);

// Orders on the actuator wire: repeated every actuators.period while the last command is fresh
// (actuators.command_timeout); when commands stop, so do the orders (once said).
class OrderPacer {
 public:
  explicit OrderPacer(const NodeParams& p);
  struct Step {
    bool fresh = false;    // the last command is fresh
    bool send = false;     // send the orders now
    bool stopped = false;  // commands have just stopped: orders stop
  };
  Step at(int64_t now_ns, bool have_cmd, int64_t cmd_ns);

 private:
  int64_t timeout_ns_, period_ns_;
  int64_t next_order_ns_ = 0;
  bool ordering_ = false;
};

// The bridge's health: "" when all is well, else what is wrong, gpsd first ("gpsd H:P not
// connected; navigation invalid: <why>; no fresh control/actuators: no orders sent").
std::string health_text(const NodeParams& p, const NavOutput& o, bool orders_stale, bool gpsd_connected);

}  // namespace mpgc::ship_bridge
