// The ship bridge's algorithms (no DDS, no clock: every call takes the time it happens at).
// NavFusion turns GNSS fixes, gyro heading and rate of turn, and actuator feedback into the own
// ship's navigation state with explicit validity; AisAssembler turns decoded AIS messages into
// target reports (static data joined by MMSI, the own ship's messages kept out); ActuatorWire
// turns actuator commands into saturated rudder/engine orders and parses the feedback.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <string>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/ship_bridge/gpsd_client.hpp"

namespace mpgc::ship_bridge {

struct NavParams {
  double fix_timeout = 3.0;     // [s] a position older than this is stale
  double heading_timeout = 1.0; // [s] a heading or rate of turn older than this is stale
  double feedback_timeout = 2.0; // [s] rudder/rpm feedback older than this is stale
  bool require_3d = false;      // a 2-D fix is invalid when true
  double max_speed = 25.0;      // [m/s] fastest the ship can go: a position jump beyond it (plus
  double jump_margin = 30.0;    // [m] GNSS noise allowance) is rejected as impossible
  double max_sog = 40.0;        // [m/s] a reported SOG above this is rejected
  void validate() const;        // throws std::invalid_argument naming the parameter
};

// The navigation state with its validity (NavState's NAV_*_VALID bits).
struct NavOutput {
  double x = 0, y = 0;          // [m] NED about the origin
  double lat = 0, lon = 0;      // [rad]
  double heading = 0, cog = 0, sog = 0;  // [rad] [rad] [m/s]
  double r = 0;                 // [rad/s]
  double rudder = 0, rpm = 0;   // [rad] [1/min]
  bool position_valid = false, velocity_valid = false, heading_valid = false, rate_valid = false,
       actuators_valid = false;
  std::string why_invalid;      // e.g. "no fix", "2-D fix", "position stale (4.2 s)", "" when all valid
};

class NavFusion {
 public:
  // origin: the local frame's origin; nullopt = the first good fix becomes the origin.
  NavFusion(const NavParams& p, std::optional<geo::LatLon> origin);

  // Each returns "" when the input was used, else why it was rejected (and counts it).
  std::string on_fix(const GnssFix& f, int64_t now_ns);
  // The receiver's own verdict on its fix (GGA quality, RMC status, from gpsd's raw NMEA): gpsd
  // 3.22 reports an RMC "V" / GGA quality 0 cycle that still carries a position as a 3-D fix, so
  // an invalid verdict makes the position invalid at once and until a valid verdict comes.
  void on_receiver_status(bool valid, int64_t now_ns);
  std::string on_heading(double heading_deg, int64_t now_ns);
  std::string on_rate_of_turn(double rot_deg_min, int64_t now_ns);
  std::string on_rudder(double rudder_deg, int64_t now_ns);
  std::string on_rpm(double rpm, int64_t now_ns);

  bool has_origin() const { return frame_.has_value(); }
  const geo::LocalNed* frame() const { return frame_ ? &*frame_ : nullptr; }
  // The state at now_ns: values of the last good inputs, validity from their age and kind.
  NavOutput state(int64_t now_ns) const;
  // Rejections per reason ("fix.not_finite", "fix.jump", ...).
  const std::map<std::string, uint64_t>& rejected() const { return rejected_; }

 private:
  std::string reject(const std::string& key, const std::string& why);
  NavParams p_;
  std::optional<geo::LocalNed> frame_;
  struct Stamped { double v = 0; int64_t t = -1; };
  int fix_mode_ = 0;
  int64_t fix_t_ = -1, last_any_fix_t_ = -1;
  bool receiver_invalid_ = false;
  // After a rejected jump the position is invalid until the gate takes the new place.
  nav::JumpGate jumps_;
  double lat_ = 0, lon_ = 0, x_ = 0, y_ = 0;
  Stamped sog_, cog_, heading_, rot_, rudder_, rpm_;
  std::map<std::string, uint64_t> rejected_;
};

// A target report in SI units (AisReport's fields); unavailable values NaN.
struct TargetReport {
  uint32_t mmsi = 0;
  bool class_b = false;
  double lat = 0, lon = 0;      // [rad]
  double cog = 0, sog = 0;      // [rad] [m/s]
  double heading = 0, rot = 0;  // [rad] [rad/s]
  int nav_status = 15;
  double length = 0, beam = 0;  // [m]
  std::string name;
  int ship_type = -1;
};

class AisAssembler {
 public:
  explicit AisAssembler(uint32_t own_mmsi) : own_mmsi_(own_mmsi) {}
  // A target report for a position message of another ship; nullopt for static data (stored and
  // joined into later reports), the own ship's messages and bad ones (*why says which).
  std::optional<TargetReport> on_message(const AisMessage& m, std::string* why);
  const std::map<std::string, uint64_t>& rejected() const { return rejected_; }
  uint64_t own_ship_messages() const { return own_; }

 private:
  struct Static { std::string name; int ship_type = -1; double length = 0.0 / 0.0, beam = 0.0 / 0.0; };
  uint32_t own_mmsi_;
  std::map<uint32_t, Static> static_;
  std::map<std::string, uint64_t> rejected_;
  uint64_t own_ = 0;
};

struct ActuatorLimits {
  double max_rudder = 0.6108652;  // [rad] 35 deg
  double min_rpm = 0.0, max_rpm = 150.0;  // [1/min]
};

// One datagram of orders (README "Putting mpgc on a boat"): IEC 61162-1 ROR (rudder order, degrees,
// '-' = bow to port) and PRC (rpm demand) from talker AG (autopilot), clipped to the limits;
// *saturated says whether an order was clipped. Non-finite inputs give "" (never sent).
std::string encode_orders(double rudder_rad, double rpm, const ActuatorLimits& lim, bool* saturated);

// What a line from the gyro compass, the actuator feedback wire or gpsd's raw NMEA (HDT, THS, ROT,
// RSA, RPM, and the receiver's GGA quality / RMC status; any talker) means for NavFusion: applies it and returns "" or why it was not used; *kind names the
// sentence type ("HDT", ...) or "" when the line did not parse.
std::string apply_nmea_line(const std::string& line, NavFusion& nav, int64_t now_ns, std::string* kind);

}  // namespace mpgc::ship_bridge
