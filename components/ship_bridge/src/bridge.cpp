#include "mpgc/ship_bridge/bridge.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/nmea/nmea0183.hpp"

namespace mpgc::ship_bridge {

namespace {

bool fresh(int64_t t, int64_t now, double timeout) { return t >= 0 && nav::age_of(t, now) <= timeout; }
// The parameters, checked before any member is built from them.
const NavParams& validated(const NavParams& p) {
  p.validate();
  return p;
}

}  // namespace

void NavParams::validate() const {
  const auto pos = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0)) throw std::invalid_argument(std::string(name) + " must be a positive number");
  };
  pos(fix_timeout, "nav.fix_timeout");
  pos(heading_timeout, "nav.heading_timeout");
  pos(feedback_timeout, "nav.feedback_timeout");
  pos(max_speed, "nav.max_speed");
  pos(max_sog, "nav.max_sog");
  if (!(std::isfinite(jump_margin) && jump_margin >= 0)) throw std::invalid_argument("nav.jump_margin must be >= 0");
}

NavFusion::NavFusion(const NavParams& p, std::optional<geo::LatLon> origin)
    : p_(validated(p)), jumps_(nav::JumpGateParams{p.max_speed, p.jump_margin, p.fix_timeout}) {
  if (origin) {
    geo::check_latlon(origin->lat, origin->lon);
    frame_.emplace(*origin);
  }
}

std::string NavFusion::reject(const std::string& key, const std::string& why) {
  ++rejected_[key];
  return why;
}

std::string NavFusion::on_fix(const GnssFix& f, int64_t now) {
  fix_mode_ = f.mode;
  last_any_fix_t_ = now;
  // No fix is news, not a value: the position becomes invalid now, not after the timeout.
  if (f.mode < 2) {
    fix_t_ = -1;
    jumps_.forget();
    return reject("fix.no_fix", "no fix (mode " + std::to_string(f.mode) + ")");
  }
  if (f.mode == 2 && p_.require_3d) {
    fix_t_ = -1;
    jumps_.forget();
    return reject("fix.2d", "2-D fix where 3-D is required");
  }
  if (receiver_invalid_) {
    fix_t_ = -1;
    jumps_.forget();
    return reject("fix.no_fix", "the receiver flags its fix invalid (RMC status V / GGA quality 0)");
  }
  if (!std::isfinite(f.lat_deg) || !std::isfinite(f.lon_deg))
    return reject("fix.not_finite", "fix without a finite latitude/longitude");
  if (std::abs(f.lat_deg) > 90.0 || std::abs(f.lon_deg) > 180.0)
    return reject("fix.out_of_range", "latitude " + std::to_string(f.lat_deg) + " / longitude " +
                                          std::to_string(f.lon_deg) + " out of range");
  const geo::LatLon ll{geo::deg2rad(f.lat_deg), geo::deg2rad(f.lon_deg)};
  if (!frame_) frame_.emplace(ll);  // the first good fix is the origin
  const geo::NorthEast ne = frame_->to_ned(ll);
  std::string jump;
  switch (jumps_.check(ne.x, ne.y, now, &jump)) {
    case nav::JumpGate::Verdict::kJump: return reject("fix.jump", jump);
    case nav::JumpGate::Verdict::kUnconfirmed: return reject("fix.unconfirmed", jump);
    case nav::JumpGate::Verdict::kTaken: break;
  }
  lat_ = ll.lat, lon_ = ll.lon, x_ = ne.x, y_ = ne.y, fix_t_ = now;
  std::string why;
  if (std::isfinite(f.speed) && f.speed >= 0 && f.speed <= p_.max_sog) sog_ = {f.speed, now};
  else if (!std::isnan(f.speed)) why = reject("fix.sog", "SOG " + std::to_string(f.speed) + " m/s out of range");
  if (std::isfinite(f.track_deg) && f.track_deg >= -360 && f.track_deg <= 360) cog_ = {geo::wrap_pi(geo::deg2rad(f.track_deg)), now};
  else if (!std::isnan(f.track_deg)) why = reject("fix.cog", "COG " + std::to_string(f.track_deg) + " deg out of range");
  return why;
}

void NavFusion::on_receiver_status(bool valid, int64_t /*now*/) {
  if (!valid && !receiver_invalid_) ++rejected_["fix.receiver_invalid"];
  receiver_invalid_ = !valid;
  if (!valid) fix_t_ = -1, jumps_.forget();
}

std::string NavFusion::on_heading(double deg, int64_t now) {
  if (!std::isfinite(deg) || deg < 0.0 || deg > 360.0)
    return reject("heading.bad", "heading " + std::to_string(deg) + " deg outside 0..360");
  heading_ = {geo::wrap_pi(geo::deg2rad(deg)), now};
  return "";
}

std::string NavFusion::on_rate_of_turn(double deg_min, int64_t now) {
  // 720 deg/min (12 deg/s) is far beyond any ship's rate of turn.
  if (!std::isfinite(deg_min) || std::abs(deg_min) > 720.0)
    return reject("rot.bad", "rate of turn " + std::to_string(deg_min) + " deg/min outside +-720");
  rot_ = {geo::deg2rad(deg_min) / 60.0, now};
  return "";
}

std::string NavFusion::on_rudder(double deg, int64_t now) {
  if (!std::isfinite(deg) || std::abs(deg) > 90.0)
    return reject("rudder.bad", "rudder angle " + std::to_string(deg) + " deg outside +-90");
  rudder_ = {geo::deg2rad(deg), now};
  return "";
}

std::string NavFusion::on_rpm(double rpm, int64_t now) {
  if (!std::isfinite(rpm) || std::abs(rpm) > 10000.0)
    return reject("rpm.bad", "shaft speed " + std::to_string(rpm) + " rpm outside +-10000");
  rpm_ = {rpm, now};
  return "";
}

NavOutput NavFusion::state(int64_t now) const {
  NavOutput o;
  std::string why;
  const auto add = [&why](const std::string& s) { why += (why.empty() ? "" : "; ") + s; };
  o.position_valid = fresh(fix_t_, now, p_.fix_timeout) && frame_;
  if (!o.position_valid) {
    if (receiver_invalid_) add("no fix");
    else if (last_any_fix_t_ < 0) add("no fix yet");
    else if (fix_mode_ < 2) add("no fix");
    else if (jumps_.jumped()) add("position jumped");
    else if (fix_mode_ == 2 && p_.require_3d) add("2-D fix");
    else add("position stale");  // no ages here: health repeats this text only when it changes
  }
  o.velocity_valid = o.position_valid && fresh(sog_.t, now, p_.fix_timeout) && fresh(cog_.t, now, p_.fix_timeout);
  if (o.position_valid && !o.velocity_valid) add("no SOG/COG");
  o.heading_valid = fresh(heading_.t, now, p_.heading_timeout);
  if (!o.heading_valid) add(heading_.t < 0 ? "no heading yet" : "heading stale");
  o.rate_valid = fresh(rot_.t, now, p_.heading_timeout);
  if (!o.rate_valid) add(rot_.t < 0 ? "no rate of turn yet" : "rate of turn stale");
  o.actuators_valid = fresh(rudder_.t, now, p_.feedback_timeout) && fresh(rpm_.t, now, p_.feedback_timeout);
  if (!o.actuators_valid) add("no actuator feedback");
  // Invalid values are NaN, never the last value as if fresh.
  const double nan = std::nan("");
  o.x = o.position_valid ? x_ : nan;
  o.y = o.position_valid ? y_ : nan;
  o.lat = o.position_valid ? lat_ : nan;
  o.lon = o.position_valid ? lon_ : nan;
  o.sog = o.velocity_valid ? sog_.v : nan;
  o.cog = o.velocity_valid ? cog_.v : nan;
  o.heading = o.heading_valid ? heading_.v : nan;
  o.r = o.rate_valid ? rot_.v : nan;
  o.rudder = o.actuators_valid ? rudder_.v : nan;
  o.rpm = o.actuators_valid ? rpm_.v : nan;
  o.why_invalid = why;
  return o;
}

std::optional<TargetReport> AisAssembler::on_message(const AisMessage& m, std::string* why) {
  const auto bad = [&](const std::string& key, const std::string& w) -> std::optional<TargetReport> {
    ++rejected_[key];
    if (why != nullptr) *why = w;
    return std::nullopt;
  };
  if (why != nullptr) why->clear();
  if (m.mmsi == 0 || m.mmsi > 999999999u) return bad("ais.mmsi", "MMSI " + std::to_string(m.mmsi) + " is not 1..999999999");
  if (own_mmsi_ != 0 && m.mmsi == own_mmsi_) {  // the own ship's AIVDO looks like any AIVDM in gpsd
    ++own_;
    if (why != nullptr) *why = "own ship";
    return std::nullopt;
  }
  if (m.has_static) {
    Static& s = static_[m.mmsi];
    if (!m.name.empty()) s.name = m.name;
    if (m.ship_type >= 0) s.ship_type = m.ship_type;
    // AIS dimensions are antenna offsets; 0 means "not available", 511/63 "that or more".
    if (m.to_bow + m.to_stern > 0) s.length = m.to_bow + m.to_stern;
    if (m.to_port + m.to_starboard > 0) s.beam = m.to_port + m.to_starboard;
  }
  if (!m.has_position) {
    if (why != nullptr) *why = m.has_static ? "static data stored" : "no position in message type " + std::to_string(m.type);
    return std::nullopt;
  }
  if (!std::isfinite(m.lat_deg) || !std::isfinite(m.lon_deg) || std::abs(m.lat_deg) > 90.0 || std::abs(m.lon_deg) > 180.0)
    return bad("ais.position", "MMSI " + std::to_string(m.mmsi) + ": position not available");
  TargetReport r;
  r.mmsi = m.mmsi;
  r.class_b = m.type == 18 || m.type == 19;
  r.lat = geo::deg2rad(m.lat_deg);
  r.lon = geo::deg2rad(m.lon_deg);
  r.sog = m.sog;  // NaN when not available
  r.cog = std::isfinite(m.cog_deg) ? geo::wrap_pi(geo::deg2rad(m.cog_deg)) : std::nan("");
  r.heading = std::isfinite(m.heading_deg) ? geo::wrap_pi(geo::deg2rad(m.heading_deg)) : std::nan("");
  // ROT_AIS = 4.733 sqrt(ROT [deg/min]); -128 n/a, +-127 "turning faster than 5 deg/30 s" has no rate.
  if (m.turn_raw > -127 && m.turn_raw < 127) {
    const double q = m.turn_raw / 4.733;
    r.rot = std::copysign(q * q, q) * geo::kPi / 180.0 / 60.0;
  } else {
    r.rot = std::nan("");
  }
  r.nav_status = m.nav_status >= 0 && m.nav_status <= 15 ? m.nav_status : 15;
  const auto it = static_.find(m.mmsi);
  r.length = it != static_.end() ? it->second.length : std::nan("");
  r.beam = it != static_.end() ? it->second.beam : std::nan("");
  if (it != static_.end()) r.name = it->second.name, r.ship_type = it->second.ship_type;
  return r;
}

std::string encode_orders(double rudder_rad, double rpm, const ActuatorLimits& lim, bool* saturated) {
  if (saturated != nullptr) *saturated = false;
  if (!std::isfinite(rudder_rad) || !std::isfinite(rpm)) return "";
  const double r = std::clamp(rudder_rad, -lim.max_rudder, lim.max_rudder);
  const double n = std::clamp(rpm, lim.min_rpm, lim.max_rpm);
  if (saturated != nullptr) *saturated = r != rudder_rad || n != rpm;
  return nmea::ror("AG", geo::rad2deg(r)) + nmea::prc("AG", n);
}

std::string apply_nmea_line(const std::string& line, NavFusion& nav, int64_t now, std::string* kind) {
  if (kind != nullptr) kind->clear();
  std::string why;
  const auto s = nmea::parse(line, &why);
  if (!s) return why;
  if (kind != nullptr) *kind = s->type;
  if (s->type == "HDT" || s->type == "THS") {
    const auto h = s->type == "HDT" ? nmea::parse_hdt(*s, &why) : nmea::parse_ths(*s, &why);
    return h ? nav.on_heading(h->heading_deg, now) : why;
  }
  if (s->type == "ROT") {
    const auto r = nmea::parse_rot(*s, &why);
    return r ? nav.on_rate_of_turn(r->rot_deg_min, now) : why;
  }
  // The receiver's verdict: GGA field 6 (quality, 0 = invalid), RMC field 2 (status A/V).
  if (s->type == "GGA" && s->fields.size() > 5) {
    nav.on_receiver_status(!s->fields[5].empty() && s->fields[5] != "0", now);
    return "";
  }
  if (s->type == "RMC" && s->fields.size() > 1) {
    nav.on_receiver_status(s->fields[1] == "A", now);
    return "";
  }
  if (s->type == "RSA") {
    const auto r = nmea::parse_rsa(*s, &why);
    return r ? nav.on_rudder(r->rudder_deg, now) : why;
  }
  if (s->type == "RPM") {
    const auto r = nmea::parse_rpm(*s, &why);
    return r ? nav.on_rpm(r->rpm, now) : why;
  }
  return "sentence " + s->type + " is not used by the bridge";
}

}  // namespace mpgc::ship_bridge
