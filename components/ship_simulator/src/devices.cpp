#include "mpgc/ship_simulator/devices.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/nmea/ais.hpp"
#include "mpgc/nmea/nmea0183.hpp"

namespace mpgc::ship_simulator {

namespace {

constexpr int64_t kStaticInterval_ns = 360'000'000'000;  // ITU-R M.1371: message 5 every 6 min

double deg360(double rad) {
  const double d = std::fmod(geo::rad2deg(rad), 360.0);
  return d < 0 ? d + 360.0 : d;
}

nmea::FixData fix_of(const geo::LocalNed& f, const NavMeasurement& m, int64_t utc_ns) {
  const geo::LatLon ll = f.to_latlon({m.x, m.y});
  nmea::FixData d;
  d.utc_ns = utc_ns;
  d.lat_deg = geo::rad2deg(ll.lat);
  d.lon_deg = geo::rad2deg(ll.lon);
  d.sog_kn = m.sog / geo::kKnot;
  d.cog_deg = deg360(m.cog);
  return d;
}

int utc_second(int64_t utc_ns) { return static_cast<int>((utc_ns / 1'000'000'000) % 60); }

}  // namespace

std::string Devices::gnss(const NavMeasurement& m, int64_t t_ns) const {
  const nmea::FixData d = fix_of(frame_, m, utc0_ + t_ns);
  return nmea::rmc("GP", d) + nmea::gga("GP", d) + nmea::vtg("GP", d);
}

std::string Devices::gyro(const NavMeasurement& m) const {
  return nmea::hdt("HE", deg360(m.heading)) + nmea::rot("HE", geo::rad2deg(m.rot) * 60.0);
}

std::string Devices::feedback(double rudder_rad, double rpm) const {
  return nmea::rsa("ER", geo::rad2deg(rudder_rad)) + nmea::rpm("ER", rpm);
}

std::vector<std::string> Devices::ais_target(const AisMeasurement& m, const TargetConfig& t, int64_t t_ns) {
  const geo::LatLon ll = frame_.to_latlon({m.x, m.y});
  ais::PositionReport r;
  r.mmsi = m.mmsi;
  r.nav_status = m.nav_status;
  r.rot_deg_min = std::isfinite(m.rot) ? geo::rad2deg(m.rot) * 60.0 : std::nan("");
  r.sog_kn = m.sog / geo::kKnot;
  r.accuracy = true;
  r.lat_deg = geo::rad2deg(ll.lat);
  r.lon_deg = geo::rad2deg(ll.lon);
  r.cog_deg = deg360(m.cog);
  r.heading_deg = std::isfinite(m.heading) ? std::fmod(std::round(deg360(m.heading)), 360.0) : std::nan("");
  r.second = utc_second(utc0_ + t_ns);
  const char ch = (channel_b_ = !channel_b_) ? 'B' : 'A';
  std::vector<std::string> out = ais::sentences(ais::encode(r), ch);
  auto& next = next_static_ns_.try_emplace(m.mmsi, t_ns).first->second;
  if (t_ns >= next) {
    ais::StaticVoyage s;
    s.mmsi = m.mmsi;
    s.name = t.name;
    std::transform(s.name.begin(), s.name.end(), s.name.begin(), [](unsigned char c) { return std::toupper(c); });
    s.ship_type = 70;  // cargo
    s.to_bow = static_cast<int>(std::lround(t.length / 2)), s.to_stern = static_cast<int>(std::lround(t.length)) - s.to_bow;
    s.to_port = static_cast<int>(std::lround(t.beam / 2)), s.to_starboard = static_cast<int>(std::lround(t.beam)) - s.to_port;
    for (auto& l : ais::sentences(ais::encode(s), ch, seq_)) out.push_back(std::move(l));
    seq_ = (seq_ + 1) % 10;
    next = t_ns + kStaticInterval_ns;
  }
  return out;
}

std::vector<std::string> Devices::ais_own(uint32_t own_mmsi, const NavMeasurement& m, int64_t t_ns) {
  if (own_mmsi == 0) return {};
  const nmea::FixData d = fix_of(frame_, m, utc0_ + t_ns);
  ais::PositionReport r;
  r.mmsi = own_mmsi;
  r.nav_status = 0;
  r.rot_deg_min = geo::rad2deg(m.rot) * 60.0;
  r.sog_kn = d.sog_kn;
  r.accuracy = true;
  r.lat_deg = d.lat_deg;
  r.lon_deg = d.lon_deg;
  r.cog_deg = d.cog_deg;
  r.heading_deg = std::fmod(std::round(deg360(m.heading)), 360.0);
  r.second = utc_second(d.utc_ns);
  return ais::sentences(ais::encode(r), 'A', 0, true);
}

void WatchdogParams::validate() const {
  if (!std::isfinite(timeout_s) || timeout_s <= 0.0)
    throw std::invalid_argument("WatchdogParams.timeout_s must be finite and > 0 s");
  if (std::isinf(safe_rpm) || safe_rpm < 0.0)
    throw std::invalid_argument("WatchdogParams.safe_rpm must be NaN (hold) or finite and >= 0 rpm");
}

bool follow_orders(const DeviceOrders& o, int64_t t_ns, const WatchdogParams& w, ShipCommand* cmd) {
  if (o.rpm_seen) cmd->rpm = o.rpm;
  if (!o.rudder_seen) return false;
  const bool tripped = static_cast<double>(t_ns - o.rudder_ns) * 1e-9 > w.timeout_s;
  cmd->rudder = tripped ? 0.0 : o.rudder;
  if (tripped && !std::isnan(w.safe_rpm)) cmd->rpm = std::min(cmd->rpm, w.safe_rpm);
  return tripped;
}

bool follow_orders(const DeviceOrders& o, int64_t t_ns, double timeout_s, ShipCommand* cmd) {
  WatchdogParams w;
  w.timeout_s = timeout_s;
  return follow_orders(o, t_ns, w, cmd);
}

void Devices::on_order_lines(const std::vector<std::string>& lines, int64_t t_ns, double max_rudder, double max_rpm,
                             DeviceOrders* o) {
  for (const auto& l : lines) {
    std::string why;
    const auto s = nmea::parse(l, &why);
    if (!s) {
      ++counters_["orders.bad_sentence"];
      continue;
    }
    if (s->type == "ROR") {
      const auto r = nmea::parse_ror(*s, &why);
      if (!r) {
        ++counters_["orders.bad_ror"];
        continue;
      }
      const double want = geo::deg2rad(r->rudder_deg);
      o->rudder = std::clamp(want, -max_rudder, max_rudder);
      if (o->rudder != want) ++counters_["orders.saturated"];
      o->rudder_seen = true;
      o->rudder_ns = t_ns;
      ++counters_["orders.ror"];
    } else if (s->type == "PRC") {
      const auto n = nmea::parse_prc(*s, &why);
      if (!n) {
        ++counters_["orders.bad_prc"];
        continue;
      }
      o->rpm = std::clamp(n->rpm, 0.0, max_rpm);
      if (o->rpm != n->rpm) ++counters_["orders.saturated"];
      o->rpm_seen = true;
      ++counters_["orders.prc"];
    } else {
      ++counters_["orders.ignored"];
    }
  }
}

}  // namespace mpgc::ship_simulator
