// The simulator as the ship's devices (hardware-in-the-loop mode): what a GNSS receiver, a gyro
// compass, an AIS transponder, the steering gear and the engine control would put on their wires,
// and what the steering gear and engine control take as orders. Pure text in and out: the main
// sends it over UDP. No DDS, no clock (times are arguments).
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/ship_simulator/sensors.hpp"
#include "mpgc/ship_simulator/ship_model.hpp"
#include "mpgc/ship_simulator/targets.hpp"

namespace mpgc::ship_simulator {

struct DeviceOrders {
  double rudder = 0.0;  // [rad] latest rudder order, positive to starboard
  double rpm = 0.0;     // [1/min] latest shaft speed order
  bool rudder_seen = false, rpm_seen = false;
  int64_t rudder_ns = 0;  // [ns] when the latest rudder order came
};

// The actuator watchdog of the steering gear and the engine control, as real ones have: what they
// do when the orders stop (the autopilot link is cut, guidance_control died or hangs).
struct WatchdogParams {
  double timeout_s = 2.0;  // [s] simulated time without a rudder order before it trips
  // [1/min] engine order while tripped, never above the last order (reduce, not speed up); NaN:
  // hold the last order. Default for the simulator: the rpm of steerage speed (README "Actuator
  // watchdog": nobody steers, so run slower, but keep the rudder effective for when orders return).
  double safe_rpm = std::numeric_limits<double>::quiet_NaN();
  void validate() const;  // throws std::invalid_argument naming the bad field
};

// The command the actuators follow at t_ns. Before any rudder order `cmd` is left as it is apart
// from an rpm order (nothing to watch yet: the ship's initial setting); without a rudder order
// for w.timeout_s the rudder goes amidships and the engine to min(order, w.safe_rpm) (or holds).
// Returns true while the watchdog has tripped; the next order ends it.
bool follow_orders(const DeviceOrders& o, int64_t t_ns, const WatchdogParams& w, ShipCommand* cmd);
// The same with the engine order held (a telegraph keeps its setting).
bool follow_orders(const DeviceOrders& o, int64_t t_ns, double timeout_s, ShipCommand* cmd);

class Devices {
 public:
  // utc_start_ns: UTC (Unix epoch) of simulated time 0, so sentences carry current dates.
  Devices(const geo::LocalNed& frame, int64_t utc_start_ns) : frame_(frame), utc0_(utc_start_ns) {}

  // GNSS receiver: RMC + GGA + VTG of one fix (talker GP), one datagram.
  std::string gnss(const NavMeasurement& m, int64_t t_ns) const;
  // Gyro compass: HDT + ROT (talker HE, as real gyros send and gpsd 3.22 drops).
  std::string gyro(const NavMeasurement& m) const;
  // Steering gear and engine feedback: RSA + RPM (talker ER).
  std::string feedback(double rudder_rad, double rpm) const;
  // AIS transponder of a target: message 1 (and message 5 every 6 min, at its first report too).
  std::vector<std::string> ais_target(const AisMeasurement& m, const TargetConfig& t, int64_t t_ns);
  // The own ship's transponder: message 1 as !AIVDO (own_mmsi != 0).
  std::vector<std::string> ais_own(uint32_t own_mmsi, const NavMeasurement& m, int64_t t_ns);

  // Orders from the autopilot wire (ROR rudder, PRC rpm). Orders beyond the limits are
  // saturated (counted in "orders.saturated"), bad lines counted by reason and not used.
  void on_order_lines(const std::vector<std::string>& lines, int64_t t_ns, double max_rudder, double max_rpm,
                      DeviceOrders* o);
  const std::map<std::string, uint64_t>& counters() const { return counters_; }

 private:
  geo::LocalNed frame_;
  int64_t utc0_;
  std::map<uint32_t, int64_t> next_static_ns_;
  int seq_ = 0;
  bool channel_b_ = false;
  std::map<std::string, uint64_t> counters_;
};

}  // namespace mpgc::ship_simulator
