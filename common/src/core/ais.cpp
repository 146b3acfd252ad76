#include "mpgc/nmea/ais.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "mpgc/nmea/nmea0183.hpp"

namespace mpgc::ais {

namespace {

int clamp_int(int v, int lo, int hi) { return std::min(std::max(v, lo), hi); }

// ROT_AIS = 4.733 sqrt(|rot|) [deg/min], signed, saturating at +-126 (708 deg/min and more).
// -128 = not available (NaN); +-127 = turning faster than 5 deg/30 s without a turn indicator,
// which a caller asks for with +-infinity.
int rot_ais(double rot_deg_min) {
  if (std::isnan(rot_deg_min)) return -128;
  if (std::isinf(rot_deg_min)) return rot_deg_min > 0 ? 127 : -127;
  const int v = static_cast<int>(std::lround(std::min(126.0, 4.733 * std::sqrt(std::fabs(rot_deg_min)))));
  return rot_deg_min < 0 ? -v : v;
}

// An angle [deg] wrapped to [0, 360) in units of 1/`per_deg` deg, or `na` when not finite.
uint32_t angle_units(double deg, int per_deg, uint32_t na) {
  if (!std::isfinite(deg)) return na;
  const long full = 360L * per_deg;
  long q = std::lround(std::fmod(deg, 360.0) * per_deg) % full;
  if (q < 0) q += full;
  return static_cast<uint32_t>(q);
}

// Latitude/longitude in 1/600000 deg (1/10000 min), or the n/a value (91 / 181 deg).
int32_t latlon_units(double deg, double limit, double na) {
  const double v = std::isfinite(deg) && std::fabs(deg) <= limit ? deg : na;
  return static_cast<int32_t>(std::lround(v * 600000.0));
}

}  // namespace

void Payload::put_uint(uint32_t value, int bits) {
  for (int i = bits - 1; i >= 0; --i) bits_.push_back(i < 32 && ((value >> i) & 1U) != 0);
}

void Payload::put_int(int32_t value, int bits) {
  put_uint(static_cast<uint32_t>(value), bits);  // two's complement, low `bits` bits
}

void Payload::put_text(const std::string& s, int chars) {
  for (int i = 0; i < chars; ++i) {
    int c = i < static_cast<int>(s.size()) ? std::toupper(static_cast<unsigned char>(s[i])) : '@';
    uint32_t v;
    if (c >= '@' && c <= '_') v = static_cast<uint32_t>(c - 64);
    else if (c >= ' ' && c <= '?') v = static_cast<uint32_t>(c);
    else v = '?';  // outside the 6-bit alphabet
    put_uint(v, 6);
  }
}

std::string Payload::armoured(int* fill_bits) const {
  const size_t n = bits_.size();
  const int fill = static_cast<int>((6 - n % 6) % 6);
  std::string out;
  out.reserve((n + 5) / 6);
  for (size_t i = 0; i < n; i += 6) {
    unsigned v = 0;
    for (size_t k = i; k < i + 6; ++k) v = (v << 1) | (k < n && bits_[k] ? 1U : 0U);
    out += static_cast<char>(v < 40 ? v + 48 : v + 56);
  }
  if (fill_bits != nullptr) *fill_bits = fill;
  return out;
}

Payload encode(const PositionReport& m) {
  Payload p;
  p.put_uint(static_cast<uint32_t>(m.type >= 1 && m.type <= 3 ? m.type : 1), 6);
  p.put_uint(0, 2);  // repeat indicator
  p.put_uint(m.mmsi, 30);
  p.put_uint(static_cast<uint32_t>(m.nav_status >= 0 && m.nav_status <= 15 ? m.nav_status : 15), 4);
  p.put_int(rot_ais(m.rot_deg_min), 8);
  uint32_t sog = 1023;  // [0.1 kn] n/a (also for negative speeds); 1022 = 102.2 kn or more
  if (std::isfinite(m.sog_kn) && m.sog_kn >= 0.0)
    sog = m.sog_kn >= 102.2 ? 1022 : static_cast<uint32_t>(std::lround(m.sog_kn * 10.0));
  p.put_uint(sog, 10);
  p.put_uint(m.accuracy ? 1 : 0, 1);
  p.put_int(latlon_units(m.lon_deg, 180.0, 181.0), 28);
  p.put_int(latlon_units(m.lat_deg, 90.0, 91.0), 27);
  p.put_uint(angle_units(m.cog_deg, 10, 3600), 12);
  p.put_uint(angle_units(m.heading_deg, 1, 511), 9);
  p.put_uint(static_cast<uint32_t>(m.second >= 0 && m.second <= 63 ? m.second : 60), 6);
  p.put_uint(static_cast<uint32_t>(clamp_int(m.maneuver, 0, 3)), 2);
  p.put_uint(0, 3);  // spare
  p.put_uint(m.raim ? 1 : 0, 1);
  p.put_uint(m.radio & 0x7FFFFU, 19);
  return p;
}

Payload encode(const StaticVoyage& m) {
  // Fields the struct does not carry take what the class A transponders in gpsd's sample.aivdm
  // send: AIS version 0, EPFD 1 (GPS), ETA not available, DTE 0 (available).
  Payload p;
  p.put_uint(5, 6);
  p.put_uint(0, 2);  // repeat indicator
  p.put_uint(m.mmsi, 30);
  p.put_uint(0, 2);  // AIS version
  p.put_uint(m.imo, 30);
  p.put_text(m.callsign, 7);
  p.put_text(m.name, 20);
  p.put_uint(static_cast<uint32_t>(clamp_int(m.ship_type, 0, 255)), 8);
  // Dimensions saturate: 511 m / 63 m mean "that or more".
  p.put_uint(static_cast<uint32_t>(clamp_int(m.to_bow, 0, 511)), 9);
  p.put_uint(static_cast<uint32_t>(clamp_int(m.to_stern, 0, 511)), 9);
  p.put_uint(static_cast<uint32_t>(clamp_int(m.to_port, 0, 63)), 6);
  p.put_uint(static_cast<uint32_t>(clamp_int(m.to_starboard, 0, 63)), 6);
  p.put_uint(1, 4);   // EPFD: GPS
  p.put_uint(0, 4);   // ETA month n/a
  p.put_uint(0, 5);   // ETA day n/a
  p.put_uint(24, 5);  // ETA hour n/a
  p.put_uint(60, 6);  // ETA minute n/a
  uint32_t draught = 0;  // [0.1 m] 0 = n/a, 255 = 25.5 m or more
  if (std::isfinite(m.draught_m) && m.draught_m > 0.0)
    draught = static_cast<uint32_t>(std::lround(std::min(255.0, m.draught_m * 10.0)));
  p.put_uint(draught, 8);
  p.put_text(m.destination, 20);
  p.put_uint(0, 1);  // DTE available
  p.put_uint(0, 1);  // spare
  return p;
}

std::vector<std::string> sentences(const Payload& p, char channel, int seq_id, bool own) {
  constexpr size_t kMaxChars = 60;  // payload characters per fragment (keeps a sentence <= 82)
  int fill = 0;
  const std::string data = p.armoured(&fill);
  const size_t n = std::max<size_t>(1, (data.size() + kMaxChars - 1) / kMaxChars);
  const std::string head = own ? "AIVDO," : "AIVDM,";
  const std::string seq = n > 1 ? std::to_string(((seq_id % 10) + 10) % 10) : "";
  std::vector<std::string> out;
  for (size_t k = 0; k < n; ++k) {
    const bool last = k + 1 == n;
    std::string body = head + std::to_string(n) + ',' + std::to_string(k + 1) + ',' + seq + ',' + channel + ',' +
                       data.substr(k * kMaxChars, kMaxChars) + ',' + std::to_string(last ? fill : 0);
    out.push_back(nmea::frame('!', body));
  }
  return out;
}

}  // namespace mpgc::ais
