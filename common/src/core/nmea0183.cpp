#include "mpgc/nmea/nmea0183.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mpgc::nmea {

namespace {

// ---- formatting: integers only, so no locale can turn '.' into ',' ----

// A value a sentence field can carry: finite, and small enough for the integer formatting below
// (nothing on a ship comes near 1e12 in the sentences' units).
bool usable(double v) { return std::isfinite(v) && std::fabs(v) < 1e12; }

// `v` rounded to `decimals` places, '-' for negatives, "" when not usable.
std::string fixed(double v, int decimals) {
  if (!usable(v)) return "";
  double scale = 1.0;
  for (int i = 0; i < decimals; ++i) scale *= 10.0;
  const long long q = std::llround(std::fabs(v) * scale);
  const long long p = static_cast<long long>(scale);
  char buf[48];
  if (decimals == 0)
    std::snprintf(buf, sizeof buf, "%s%lld", v < 0 && q != 0 ? "-" : "", q);
  else
    std::snprintf(buf, sizeof buf, "%s%lld.%0*lld", v < 0 && q != 0 ? "-" : "", q / p, decimals, q % p);
  return buf;
}

// Angle wrapped to [0, 360) after rounding to `decimals`, so 359.999 never prints as 360.00.
std::string angle360(double deg, int decimals) {
  if (!std::isfinite(deg)) return "";
  double scale = 1.0;
  for (int i = 0; i < decimals; ++i) scale *= 10.0;
  const long long full = std::llround(360.0 * scale);
  long long q = std::llround(std::fmod(deg, 360.0) * scale) % full;
  if (q < 0) q += full;
  return fixed(static_cast<double>(q) / scale, decimals);
}

bool position_ok(const FixData& f) {
  return std::isfinite(f.lat_deg) && std::isfinite(f.lon_deg) && std::fabs(f.lat_deg) <= 90.0 &&
         std::fabs(f.lon_deg) <= 180.0;
}

// "ddmm.mmmmmm,N" / "dddmm.mmmmmm,E": rounded in units of 1e-6 min, so 59.9999999' carries into
// the degrees instead of printing "60.000000".
std::string coord(double deg, int deg_digits, char pos, char neg) {
  const long long units_per_deg = 60LL * 1000000LL;
  const long long q = std::llround(std::fabs(deg) * static_cast<double>(units_per_deg));
  const long long d = q / units_per_deg, m = q % units_per_deg;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%0*lld%02lld.%06lld,%c", deg_digits, d, m / 1000000LL, m % 1000000LL,
                deg < 0 && q != 0 ? neg : pos);
  return buf;
}

// UTC time of day and date, both from one value rounded to 0.01 s (so they never disagree).
struct Utc {
  std::string hhmmss;  // hhmmss.ss
  std::string ddmmyy;
};
Utc utc(int64_t ns) {
  const int64_t cs_per_day = 8640000;
  int64_t cs = ns / 10000000;  // [0.01 s]
  const int64_t rem = ns % 10000000;
  if (rem >= 5000000) ++cs;
  else if (rem < -5000000) --cs;
  int64_t days = cs / cs_per_day, tod = cs % cs_per_day;
  if (tod < 0) { tod += cs_per_day; --days; }
  // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
  const int64_t z = days + 719468;
  const int64_t era = (z >= 0 ? z : z - 146096) / 146097;
  const int64_t doe = z - era * 146097;
  const int64_t yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const int64_t doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const int64_t mp = (5 * doy + 2) / 153;
  const int64_t day = doy - (153 * mp + 2) / 5 + 1;
  const int64_t month = mp < 10 ? mp + 3 : mp - 9;
  const int64_t year = yoe + era * 400 + (month <= 2 ? 1 : 0);
  char t[16], d[16];
  std::snprintf(t, sizeof t, "%02d%02d%02d.%02d", static_cast<int>(tod / 360000), static_cast<int>(tod / 6000 % 60),
                static_cast<int>(tod / 100 % 60), static_cast<int>(tod % 100));
  std::snprintf(d, sizeof d, "%02d%02d%02d", static_cast<int>(day), static_cast<int>(month),
                static_cast<int>(((year % 100) + 100) % 100));
  return {t, d};
}

std::string join(std::string_view talker, const char* type, const std::string& rest) {
  std::string body(talker);
  body += type;
  body += ',';
  body += rest;
  return frame('$', body);
}

// ---- decoding helpers ----

bool fail(std::string* why, std::string msg) {
  if (why != nullptr) *why = std::move(msg);
  return false;
}

bool is_type(const Sentence& s, const char* type, std::string* why) {
  if (s.start == '$' && s.type == type) return true;
  return fail(why, std::string("not ") + type + ": " + s.start + s.talker + s.type);
}

const std::string* field(const Sentence& s, size_t i, const char* type, const char* name, std::string* why) {
  if (i >= s.fields.size()) {
    fail(why, std::string(type) + ": no " + name + " field");
    return nullptr;
  }
  if (s.fields[i].empty()) {
    fail(why, std::string(type) + ": empty " + name);
    return nullptr;
  }
  return &s.fields[i];
}

// A decimal number "[+-]digits[.digits]": the strict shape first (strtod alone would take "inf",
// "0x1p3" or leading blanks), then strtod with a full-consumption check.
std::optional<double> number(const Sentence& s, size_t i, const char* type, const char* name, std::string* why) {
  const std::string* f = field(s, i, type, name, why);
  if (f == nullptr) return std::nullopt;
  size_t k = 0, digits = 0;
  if (k < f->size() && ((*f)[k] == '-' || (*f)[k] == '+')) ++k;
  for (; k < f->size() && (*f)[k] >= '0' && (*f)[k] <= '9'; ++k) ++digits;
  if (k < f->size() && (*f)[k] == '.')
    for (++k; k < f->size() && (*f)[k] >= '0' && (*f)[k] <= '9'; ++k) ++digits;
  const std::string bad = std::string(type) + ": " + name + " '" + *f + "' is not a number";
  if (k != f->size() || digits == 0) {
    fail(why, bad);
    return std::nullopt;
  }
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(f->c_str(), &end);
  if (end != f->c_str() + f->size() || errno == ERANGE || !std::isfinite(v)) {
    fail(why, bad);
    return std::nullopt;
  }
  return v;
}

std::optional<int> integer(const Sentence& s, size_t i, const char* type, const char* name, std::string* why) {
  const std::string* f = field(s, i, type, name, why);
  if (f == nullptr) return std::nullopt;
  if (f->size() > 6 || f->find_first_not_of("0123456789") != std::string::npos) {
    fail(why, std::string(type) + ": " + name + " '" + *f + "' is not a whole number");
    return std::nullopt;
  }
  return std::atoi(f->c_str());
}

// The field must be exactly `want` (a status or unit letter).
bool letter(const Sentence& s, size_t i, const char* type, const char* name, char want, std::string* why) {
  const std::string* f = field(s, i, type, name, why);
  if (f == nullptr) return false;
  if (f->size() == 1 && (*f)[0] == want) return true;
  if (*f == "V") return fail(why, std::string(type) + ": " + name + " V (invalid)");
  return fail(why, std::string(type) + ": " + name + " '" + *f + "', expected " + want);
}

int hex(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

bool is_addr_char(char c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); }

}  // namespace

std::string checksum(std::string_view body) {
  unsigned x = 0;
  for (char c : body) x ^= static_cast<unsigned char>(c);
  static const char* digits = "0123456789ABCDEF";
  return {digits[(x >> 4) & 0xF], digits[x & 0xF]};
}

std::string frame(char start, std::string_view body) {
  std::string out;
  out.reserve(body.size() + 6);
  out += start;
  out += body;
  out += '*';
  out += checksum(body);
  out += "\r\n";
  return out;
}

std::optional<Sentence> parse(std::string_view line, std::string* why, bool require_checksum) {
  auto reject = [why](std::string msg) -> std::optional<Sentence> {
    fail(why, std::move(msg));
    return std::nullopt;
  };
  while (!line.empty() && (line.back() == '\r' || line.back() == '\n' || line.back() == ' ' || line.back() == '\t'))
    line.remove_suffix(1);
  if (!line.empty() && line.front() == '\\') {  // tag block: its content is not ours to check
    const size_t end = line.find('\\', 1);
    if (end == std::string_view::npos) return reject("unterminated tag block");
    line.remove_prefix(end + 1);
  }
  if (line.empty() || (line.front() != '$' && line.front() != '!')) return reject("no '$' or '!'");
  // IEC 61162-1 allows 82 characters including CR LF; counted here without them, which also lets
  // through the 1-2 character overlong sentences some AIS receivers send.
  if (line.size() > 82) return reject("sentence longer than 82 characters (" + std::to_string(line.size()) + ")");
  for (size_t i = 0; i < line.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (c < 0x20 || c > 0x7E) return reject("non-printable character at column " + std::to_string(i + 1));
  }
  Sentence s;
  s.start = line.front();
  std::string_view body = line.substr(1);
  const size_t star = body.find('*');
  if (star == std::string_view::npos) {
    if (require_checksum) return reject("no checksum");
  } else {
    const std::string_view got = body.substr(star + 1);
    body = body.substr(0, star);
    const std::string computed = checksum(body);
    if (got.size() != 2 || hex(got[0]) < 0 || hex(got[1]) < 0)
      return reject("bad checksum: got '" + std::string(got) + "', computed " + computed);
    if (hex(got[0]) * 16 + hex(got[1]) != hex(computed[0]) * 16 + hex(computed[1]))
      return reject("bad checksum: got " + std::string(got) + ", computed " + computed);
  }
  size_t pos = 0;
  std::string_view address;
  for (;;) {
    const size_t comma = body.find(',', pos);
    const std::string_view f = body.substr(pos, comma == std::string_view::npos ? std::string_view::npos : comma - pos);
    if (pos == 0) address = f;
    else s.fields.emplace_back(f);
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  for (char c : address)
    if (!is_addr_char(c)) return reject("address field '" + std::string(address) + "' has a character other than A-Z 0-9");
  if (s.start == '$' && address.size() >= 2 && address.front() == 'P') {  // proprietary: P + maker + type
    s.talker = "P";
    s.type = std::string(address.substr(1));
  } else if (address.size() == 5) {
    s.talker = std::string(address.substr(0, 2));
    s.type = std::string(address.substr(2));
  } else {
    return reject("address field '" + std::string(address) + "' is not talker (2) + type (3)");
  }
  return s;
}

// ---- encoders ----

std::string gga(std::string_view talker, const FixData& f) {
  const bool ok = position_ok(f);
  const Utc t = utc(f.utc_ns);
  const int sats = f.satellites < 0 ? 0 : f.satellites > 99 ? 99 : f.satellites;
  char sat[8];
  std::snprintf(sat, sizeof sat, "%02d", sats);
  std::string r = t.hhmmss + ',';
  r += ok ? coord(f.lat_deg, 2, 'N', 'S') + ',' + coord(f.lon_deg, 3, 'E', 'W') : std::string(",,,");
  r += ',' + std::to_string(ok ? f.quality : 0) + ',' + sat + ',' + fixed(f.hdop, 1) + ',' + fixed(f.altitude_m, 1) +
       ",M,0.0,M,,";
  return join(talker, "GGA", r);
}

std::string rmc(std::string_view talker, const FixData& f) {
  const bool ok = position_ok(f) && f.quality != 0;
  const Utc t = utc(f.utc_ns);
  std::string r = t.hhmmss + (ok ? ",A," : ",V,");
  r += position_ok(f) ? coord(f.lat_deg, 2, 'N', 'S') + ',' + coord(f.lon_deg, 3, 'E', 'W') : std::string(",,,");
  // Mode indicator N (data not valid) goes with status V (IEC 61162-1).
  r += ',' + fixed(f.sog_kn, 2) + ',' + angle360(f.cog_deg, 2) + ',' + t.ddmmyy + ",,," + (ok ? "A" : "N");
  return join(talker, "RMC", r);
}

std::string vtg(std::string_view talker, const FixData& f) {
  const double kmh = f.sog_kn * 1.852;  // [km/h]
  return join(talker, "VTG",
              angle360(f.cog_deg, 2) + ",T,,M," + fixed(f.sog_kn, 2) + ",N," + fixed(kmh, 2) + ",K," +
                  (usable(f.sog_kn) ? "A" : "N"));
}

std::string hdt(std::string_view talker, double heading_deg) {
  return join(talker, "HDT", angle360(heading_deg, 2) + ",T");
}

std::string ths(std::string_view talker, double heading_deg, char mode) {
  if (!std::isfinite(heading_deg)) mode = 'V';
  return join(talker, "THS", angle360(heading_deg, 2) + ',' + mode);
}

std::string rot(std::string_view talker, double rot_deg_min, bool valid) {
  valid = valid && usable(rot_deg_min);
  return join(talker, "ROT", fixed(rot_deg_min, 2) + (valid ? ",A" : ",V"));
}

std::string ror(std::string_view talker, double rudder_order_deg, char source) {
  // Starboard (or single) rudder order; port rudder empty and invalid.
  const bool ok = usable(rudder_order_deg);
  return join(talker, "ROR", fixed(rudder_order_deg, 2) + (ok ? ",A" : ",V") + ",,V," + source);
}

std::string prc(std::string_view talker, double rpm_demand, int shaft) {
  // Lever demand empty/invalid, rpm demand in mode R (rpm), pitch empty/invalid, location B (bridge).
  const bool ok = usable(rpm_demand);
  return join(talker, "PRC", ",V," + fixed(rpm_demand, 2) + (ok ? ",R" : ",V") + ",,V,B," + std::to_string(shaft));
}

std::string rsa(std::string_view talker, double rudder_deg) {
  const bool ok = usable(rudder_deg);
  return join(talker, "RSA", fixed(rudder_deg, 2) + (ok ? ",A" : ",V") + ",,V");
}

std::string rpm(std::string_view talker, double rpm_value, int shaft, char source) {
  const bool ok = usable(rpm_value);
  return join(talker, "RPM",
              std::string(1, source) + ',' + std::to_string(shaft) + ',' + fixed(rpm_value, 2) + (ok ? ",,A" : ",,V"));
}

// ---- decoders ----

std::optional<Heading> parse_hdt(const Sentence& s, std::string* why) {
  if (!is_type(s, "HDT", why)) return std::nullopt;
  const auto h = number(s, 0, "HDT", "heading", why);
  if (!h || !letter(s, 1, "HDT", "reference", 'T', why)) return std::nullopt;
  if (*h < 0.0 || *h > 360.0) {
    fail(why, "HDT: heading " + s.fields[0] + " outside [0, 360]");
    return std::nullopt;
  }
  return Heading{*h == 360.0 ? 0.0 : *h};
}

std::optional<Heading> parse_ths(const Sentence& s, std::string* why) {
  if (!is_type(s, "THS", why)) return std::nullopt;
  const std::string* mode = field(s, 1, "THS", "mode", why);
  if (mode == nullptr) return std::nullopt;
  // A autonomous, E estimated, M manual, S simulator; V invalid.
  if (*mode != "A" && *mode != "E" && *mode != "M" && *mode != "S") {
    fail(why, "THS: mode '" + *mode + (*mode == "V" ? "' (invalid)" : "' unknown"));
    return std::nullopt;
  }
  const auto h = number(s, 0, "THS", "heading", why);
  if (!h) return std::nullopt;
  if (*h < 0.0 || *h > 360.0) {
    fail(why, "THS: heading " + s.fields[0] + " outside [0, 360]");
    return std::nullopt;
  }
  return Heading{*h == 360.0 ? 0.0 : *h};
}

std::optional<RateOfTurn> parse_rot(const Sentence& s, std::string* why) {
  if (!is_type(s, "ROT", why) || !letter(s, 1, "ROT", "status", 'A', why)) return std::nullopt;
  const auto r = number(s, 0, "ROT", "rate of turn", why);
  if (!r) return std::nullopt;
  return RateOfTurn{*r};
}

std::optional<RudderAngle> parse_rsa(const Sentence& s, std::string* why) {
  if (!is_type(s, "RSA", why) || !letter(s, 1, "RSA", "starboard status", 'A', why)) return std::nullopt;
  const auto a = number(s, 0, "RSA", "starboard rudder angle", why);
  if (!a) return std::nullopt;
  return RudderAngle{*a};
}

std::optional<RudderAngle> parse_ror(const Sentence& s, std::string* why) {
  if (!is_type(s, "ROR", why) || !letter(s, 1, "ROR", "starboard status", 'A', why)) return std::nullopt;
  const auto a = number(s, 0, "ROR", "starboard rudder order", why);
  if (!a) return std::nullopt;
  return RudderAngle{*a};
}

std::optional<ShaftRpm> parse_rpm(const Sentence& s, std::string* why) {
  if (!is_type(s, "RPM", why) || !letter(s, 4, "RPM", "status", 'A', why)) return std::nullopt;
  const std::string* src = field(s, 0, "RPM", "source", why);
  if (src == nullptr) return std::nullopt;
  if (*src != "S" && *src != "E") {
    fail(why, "RPM: source '" + *src + "', expected S or E");
    return std::nullopt;
  }
  const auto n = integer(s, 1, "RPM", "number", why);
  if (!n) return std::nullopt;
  const auto r = number(s, 2, "RPM", "speed", why);
  if (!r) return std::nullopt;
  return ShaftRpm{*r, *n};
}

std::optional<ShaftRpm> parse_prc(const Sentence& s, std::string* why) {
  // Only the rpm demand is used: it must be in mode R (rpm), not P (per cent) or V.
  if (!is_type(s, "PRC", why) || !letter(s, 3, "PRC", "rpm mode", 'R', why)) return std::nullopt;
  const auto r = number(s, 2, "PRC", "rpm demand", why);
  if (!r) return std::nullopt;
  const auto n = integer(s, 7, "PRC", "shaft number", why);
  if (!n) return std::nullopt;
  return ShaftRpm{*r, *n};
}

}  // namespace mpgc::nmea
