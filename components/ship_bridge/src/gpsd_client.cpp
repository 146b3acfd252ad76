// GpsdClient: libgps (gpsd 3.22, API 11) in JSON watch mode. Facts this relies on, checked on this
// machine (shared/notes/gpsd.md §3) and in libgps's source (tag release-3.22):
//  * gps_unpack() resets `set` only for TPV; DEVICE/AIS/ATT add bits to what was there, so `set`
//    is cleared before every line. A TPV's absent fields are NaN (or mode 0 / time 0) in gd.fix,
//    and LATLON_SET is set from the longitude alone: both coordinates are checked.
//  * gd.ais and gd.attitude share a union: each is read only under its own bit.
//  * gps_unpack() never fails, so a line libgps could not parse shows no report bit. The line is
//    kept, which is how DEVICE "activated":0 (no DEVICE_SET in 3.22), raw NMEA and type 24 parts
//    are recognised.
//  * gps_unpack() loops for ever on some lines (gpsd_json_problem below), so the client reads the
//    socket itself and hands libgps only lines that cannot make it loop; gps_read() is not used.
//    libgps still opens the connection and sends the WATCH.
#include "mpgc/ship_bridge/gpsd_client.hpp"

#include <fcntl.h>
#include <gps.h>
#include <poll.h>
#include <sys/socket.h>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_bridge {
namespace {

const double kNaN = std::nan("");
constexpr size_t kLineMax = 16384;  // > GPS_JSON_RESPONSE_MAX (10240): longer lines are dropped
constexpr int kReadsPerPoll = 64;   // [-] recv() calls of one poll (8 KiB each): a flood cannot hold poll

// RFC 8259 syntax of one line: exactly one object and nothing after it, nesting at most 32 deep.
class JsonSyntax {
 public:
  explicit JsonSyntax(std::string_view s) : s_(s) {}
  bool one_object() {
    ws();
    if (!object(0)) return false;
    ws();
    return i_ == s_.size();
  }

 private:
  bool object(int d) {
    if (d > 32 || !eat('{')) return false;
    ws();
    if (eat('}')) return true;
    for (;;) {
      ws();
      if (!string()) return false;
      ws();
      if (!eat(':') || !value(d)) return false;
      ws();
      if (eat('}')) return true;
      if (!eat(',')) return false;
    }
  }
  bool array(int d) {
    if (d > 32 || !eat('[')) return false;
    ws();
    if (eat(']')) return true;
    for (;;) {
      if (!value(d)) return false;
      ws();
      if (eat(']')) return true;
      if (!eat(',')) return false;
    }
  }
  bool value(int d) {
    ws();
    if (i_ >= s_.size()) return false;
    const char c = s_[i_];
    if (c == '{') return object(d + 1);
    if (c == '[') return array(d + 1);
    if (c == '"') return string();
    for (std::string_view w : {"true", "false", "null"})
      if (s_.substr(i_, w.size()) == w) return (i_ += w.size()), true;
    return number();
  }
  bool string() {
    if (!eat('"')) return false;
    while (i_ < s_.size()) {
      const unsigned char c = static_cast<unsigned char>(s_[i_++]);
      if (c == '"') return true;
      if (c < 0x20) return false;
      if (c == '\\') {
        if (i_ >= s_.size() || std::strchr("\"\\/bfnrtu", s_[i_]) == nullptr) return false;
        ++i_;
      }
    }
    return false;
  }
  bool digits() {
    const size_t start = i_;
    while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
    return i_ > start;
  }
  bool number() {
    eat('-');
    if (!digits()) return false;
    if (eat('.') && !digits()) return false;
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (!eat('+')) eat('-');
      if (!digits()) return false;
    }
    return true;
  }
  bool eat(char c) {
    if (i_ < s_.size() && s_[i_] == c) return ++i_, true;
    return false;
  }
  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\r' || s_[i_] == '\n')) ++i_;
  }
  std::string_view s_;
  size_t i_ = 0;
};

size_t count_of(std::string_view s, std::string_view what) {
  size_t n = 0;
  for (size_t p = s.find(what); p != std::string_view::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// The string value of "key":"..." in a JSON line, "" when absent (gpsd's keys and paths have no
// escapes worth decoding here).
std::string json_string(const char* line, const char* key) {
  std::string pat = std::string("\"") + key + "\":\"";
  const char* p = std::strstr(line, pat.c_str());
  if (p == nullptr) return {};
  p += pat.size();
  const char* e = std::strchr(p, '"');
  return e ? std::string(p, e) : std::string();
}

bool has_key(const char* line, const char* key) {
  std::string pat = std::string("\"") + key + "\":";
  return std::strstr(line, pat.c_str()) != nullptr;
}

// The first "class":"X" of the line, as libgps takes it (a DEVICES line nests DEVICE objects).
std::string first_class(const char* line) { return json_string(line, "class"); }

// Trailing '@' (6-bit padding) and spaces stripped.
std::string ais_text(const char* s, size_t max) {
  size_t n = strnlen(s, max);
  while (n > 0 && (s[n - 1] == '@' || s[n - 1] == ' ')) --n;
  return std::string(s, n);
}

// 1/10000 minute → degrees; NaN when "not available" (91° / 181°) or out of range.
void ais_latlon(int lat, int lon, AisMessage* m) {
  double la = lat / AIS_LATLON_DIV, lo = lon / AIS_LATLON_DIV;
  if (std::fabs(la) <= 90.0 && std::fabs(lo) <= 180.0) {
    m->lat_deg = la;
    m->lon_deg = lo;
    m->has_position = true;
  }
}

double ais_sog(unsigned speed) {  // 0.1 kn; 1023 n/a, 1022 = 102.2 kn or more
  return speed >= AIS_SPEED_NOT_AVAILABLE ? kNaN : speed / 10.0 * geo::kKnot;
}
double ais_cog(unsigned course) {  // 0.1 deg; 3600 n/a
  return course >= AIS_COURSE_NOT_AVAILABLE ? kNaN : course / 10.0;
}
double ais_heading(unsigned heading) {  // whole degrees; 511 n/a
  return heading >= 360 ? kNaN : static_cast<double>(heading);
}
int ais_ship_type(unsigned t) {  // 0 = not available (M.1371 table 53)
  return t == 0 ? -1 : static_cast<int>(t);
}
// Dimensions in metres; all four 0 = not available (A = C = 0 with B, D set is a valid "reference
// point unknown": B is the length and D the beam).
void ais_dims(unsigned a, unsigned b, unsigned c, unsigned d, AisMessage* m) {
  if (a == 0 && b == 0 && c == 0 && d == 0) return;
  m->to_bow = a;
  m->to_stern = b;
  m->to_port = c;
  m->to_starboard = d;
}

AisMessage convert_ais(const ais_t& a, const char* line) {
  AisMessage m;
  m.type = static_cast<int>(a.type);
  m.mmsi = a.mmsi;
  m.device = json_string(line, "device");
  switch (a.type) {
    case 1:
    case 2:
    case 3: {
      const auto& p = a.type1;
      ais_latlon(p.lat, p.lon, &m);
      m.sog = ais_sog(p.speed);
      m.cog_deg = ais_cog(p.course);
      m.heading_deg = ais_heading(p.heading);
      // gps.h says 128 is n/a; libgps delivers the signed -128. Either means n/a.
      m.turn_raw = (p.turn == AIS_TURN_NOT_AVAILABLE || p.turn < -127 || p.turn > 127) ? -128 : p.turn;
      m.nav_status = static_cast<int>(p.status);
      m.second = static_cast<int>(p.second);
      break;
    }
    case 18: {
      const auto& p = a.type18;  // same lat/lon units as type 1 (the AIS_GNS_* macros are type 17's)
      ais_latlon(p.lat, p.lon, &m);
      m.sog = ais_sog(p.speed);
      m.cog_deg = ais_cog(p.course);
      m.heading_deg = ais_heading(p.heading);
      m.second = static_cast<int>(p.second);
      break;
    }
    case 19: {
      const auto& p = a.type19;
      ais_latlon(p.lat, p.lon, &m);
      m.sog = ais_sog(p.speed);
      m.cog_deg = ais_cog(p.course);
      m.heading_deg = ais_heading(p.heading);
      m.second = static_cast<int>(p.second);
      m.has_static = true;
      m.name = ais_text(p.shipname, sizeof p.shipname);
      m.ship_type = ais_ship_type(p.shiptype);
      ais_dims(p.to_bow, p.to_stern, p.to_port, p.to_starboard, &m);
      break;
    }
    case 5: {
      const auto& s = a.type5;
      m.has_static = true;
      m.name = ais_text(s.shipname, sizeof s.shipname);
      m.callsign = ais_text(s.callsign, sizeof s.callsign);
      m.ship_type = ais_ship_type(s.shiptype);
      ais_dims(s.to_bow, s.to_stern, s.to_port, s.to_starboard, &m);
      break;
    }
    case 24: {
      // libgps 3.22 does not read the part: json_ais_read memsets the struct (part = both) and
      // gpsd prints part A's fields (shipname) and part B's (shiptype, vendorid, callsign, dims or
      // mothership_mmsi) only for the part(s) it has; gpsd merges A+B into one message unless
      // watched with split24. So the part is taken from the keys in the line.
      const auto& s = a.type24;
      m.has_static = true;
      if (has_key(line, "shipname")) m.name = ais_text(s.shipname, sizeof s.shipname);
      if (has_key(line, "shiptype")) {
        m.ship_type = ais_ship_type(s.shiptype);
        m.callsign = ais_text(s.callsign, sizeof s.callsign);
        if (!AIS_AUXILIARY_MMSI(a.mmsi) && has_key(line, "to_bow"))
          ais_dims(s.dim.to_bow, s.dim.to_stern, s.dim.to_port, s.dim.to_starboard, &m);
      }
      break;
    }
    case 27: {
      // Long-range broadcast: 1/10 minute, knots (63 n/a), whole degrees (511 n/a).
      const auto& p = a.type27;
      double la = p.lat / AIS_LONGRANGE_LATLON_DIV, lo = p.lon / AIS_LONGRANGE_LATLON_DIV;
      if (std::fabs(la) <= 90.0 && std::fabs(lo) <= 180.0) {
        m.lat_deg = la;
        m.lon_deg = lo;
        m.has_position = true;
      }
      m.sog = p.speed >= AIS_LONGRANGE_SPEED_NOT_AVAILABLE ? kNaN : p.speed * geo::kKnot;
      m.cog_deg = p.course >= 360 ? kNaN : static_cast<double>(p.course);
      m.nav_status = static_cast<int>(p.status);
      break;
    }
    default:
      break;  // other types: type and MMSI only
  }
  return m;
}

}  // namespace

std::string gpsd_json_problem(std::string_view line) {
  if (!JsonSyntax(line).one_object()) return "not one well-formed JSON object";
  if (line.substr(0, 9) != R"({"class":)") return "\"class\" is not the first key";
  if (count_of(line, "\"class\":") != 1) return "more than one \"class\": key";
  return {};
}

struct GpsdClient::Impl {
  gps_data_t gd{};
  bool open = false;       // gps_open succeeded (gps_close owed)
  bool connected = false;
  bool discarding = false; // inside a line longer than kLineMax: dropped up to its end
  uint64_t unparsed = 0;
  std::string last_device;
  std::string where;       // "host:port" for log lines
  std::string rx;          // received bytes after the last complete line
  char line[kLineMax + 1];
  char scratch[kLineMax + 1];  // gps_unpack's own copy (it may write into its argument)

  void reject(const char* why) {
    ++unparsed;
    // A log line per rejection, thinned out after the first few so a bad feed cannot flood.
    if (unparsed <= 20 || unparsed % 1000 == 0) {
      std::fprintf(stderr, "gpsd_client %s: %s (#%llu): %.200s\n", where.c_str(), why,
                   static_cast<unsigned long long>(unparsed), line);
    }
  }

  void handle(std::vector<GpsdEvent>* out);
  void take(const char* p, size_t n, std::vector<GpsdEvent>* out);
  bool read_available(std::vector<GpsdEvent>* out);
};

GpsdClient::GpsdClient(const std::string& host, int port, bool nmea) : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  I.where = host + ":" + std::to_string(port);
  std::string port_s = std::to_string(port);
  errno = 0;
  if (gps_open(host.c_str(), port_s.c_str(), &I.gd) != 0) {
    // gps_open returns -1 and leaves libgps's (netlib's) error code in errno.
    const int e = errno;
    throw std::runtime_error("gpsd_client: cannot connect to gpsd at " + I.where + ": " + gps_errstr(e));
  }
  I.open = true;
  unsigned flags = WATCH_ENABLE | WATCH_JSON | (nmea ? WATCH_NMEA : 0u);
  if (gps_stream(&I.gd, flags, nullptr) != 0) {
    int e = errno;
    gps_close(&I.gd);
    I.open = false;
    throw std::runtime_error("gpsd_client: cannot start the watch on gpsd at " + I.where + ": " +
                             std::strerror(e));
  }
  // libgps 3.22 already makes the socket non-blocking; a read must never wait for the rest of a line.
  const int fl = fcntl(I.gd.gps_fd, F_GETFL, 0);
  if (fl >= 0) (void)fcntl(I.gd.gps_fd, F_SETFL, fl | O_NONBLOCK);
  I.connected = true;
}

GpsdClient::~GpsdClient() {
  // No WATCH_DISABLE: writing to a socket gpsd already closed would raise SIGPIPE; closing the
  // socket ends the watch just as well.
  if (impl_ && impl_->open) gps_close(&impl_->gd);
}

bool GpsdClient::connected() const { return impl_->connected; }
uint64_t GpsdClient::unparsed() const { return impl_->unparsed; }

void GpsdClient::Impl::handle(std::vector<GpsdEvent>* out) {
  // Strip CR/LF (gpsd ends lines with \r\n; libgps cut at \n).
  size_t n = strnlen(line, sizeof line);
  while (n > 0 && (line[n - 1] == '\r' || line[n - 1] == '\n')) line[--n] = '\0';
  if (n == 0) return;  // an empty line carries nothing

  if (line[0] == '$' || line[0] == '!') {
    out->push_back(RawNmea{std::string(line, n)});
    return;
  }
  if (line[0] != '{') {
    reject("not JSON or NMEA");
    return;
  }
  const std::string cls = first_class(line);
  if (cls == "DEVICES") return;  // nests DEVICE classes (see gpsd_json_problem); not used
  if (const std::string why = gpsd_json_problem(std::string_view(line, n)); !why.empty()) {
    reject(why.c_str());
    return;
  }
  gd.set = 0;
  std::memcpy(scratch, line, n + 1);
  (void)gps_unpack(scratch, &gd);
  const gps_mask_t set = gd.set;

  if (cls == "TPV") {
    // Every TPV is reported, also mode 0/1 ones without a position: they say "no fix".
    GnssFix f;
    f.mode = (set & MODE_SET) ? gd.fix.mode : 0;
    if (f.mode < 0 || f.mode > 3) f.mode = 0;
    if ((set & LATLON_SET) && std::isfinite(gd.fix.latitude) && std::isfinite(gd.fix.longitude) &&
        std::fabs(gd.fix.latitude) <= 90.0 && std::fabs(gd.fix.longitude) <= 180.0) {
      f.lat_deg = gd.fix.latitude;
      f.lon_deg = gd.fix.longitude;
    }
    if ((set & SPEED_SET) && std::isfinite(gd.fix.speed)) f.speed = gd.fix.speed;
    if ((set & TRACK_SET) && std::isfinite(gd.fix.track)) f.track_deg = gd.fix.track;
    // |tv_sec| below 9e9 s (year 2255): beyond it the nanoseconds overflow int64 (a TPV time in the
    // year 3238 did, found by fuzz_gpsd_json); such a time counts as none.
    if ((set & TIME_SET) && gd.fix.time.tv_sec != 0 && gd.fix.time.tv_sec > -9'000'000'000LL &&
        gd.fix.time.tv_sec < 9'000'000'000LL)
      f.time_ns = static_cast<int64_t>(gd.fix.time.tv_sec) * 1000000000LL + gd.fix.time.tv_nsec;
    f.device = json_string(line, "device");
    if (!f.device.empty()) last_device = f.device;
    out->push_back(std::move(f));
    return;
  }
  if (cls == "ATT") {
    if ((set & ATTITUDE_SET) && std::isfinite(gd.attitude.heading)) {
      AttitudeHeading h;
      h.heading_deg = gd.attitude.heading;
      h.device = json_string(line, "device");
      if (!h.device.empty()) last_device = h.device;
      out->push_back(std::move(h));
    } else {
      // e.g. gpsd 3.22's invalid ATT after an AIS message on the same device (notes §5).
      reject("ATT without a usable heading");
    }
    return;
  }
  if (cls == "AIS") {
    if (set & AIS_SET) {
      AisMessage m = convert_ais(gd.ais, line);
      if (!m.device.empty()) last_device = m.device;
      out->push_back(std::move(m));
    } else {
      reject("AIS that libgps could not parse");
    }
    return;
  }
  if (cls == "DEVICE") {
    // libgps 3.22 sets only PACKET_SET for {"class":"DEVICE","path":...,"activated":0}.
    const char* a = std::strstr(line, "\"activated\":0");
    if (a != nullptr && (a[13] == ',' || a[13] == '}')) {
      std::string path = json_string(line, "path");
      out->push_back(DeviceEnd{path});
    } else {
      std::string path = json_string(line, "path");
      if (!path.empty()) last_device = path;
    }
    return;
  }
  // Protocol and reports the bridge does not use.
  static const char* const known[] = {"VERSION", "WATCH", "SKY", "GST", "PPS", "TOFF",
                                      "OSC", "RAW", "SUBFRAME", "POLL", "RTCM2", "RTCM3"};
  for (const char* k : known)
    if (cls == k) return;
  if (cls == "ERROR") {
    reject("gpsd reported an error");
    return;
  }
  reject("unknown JSON");
}

// Appends p[0, n) to the line being received and handles every line it completes.
void GpsdClient::Impl::take(const char* p, size_t n, std::vector<GpsdEvent>* out) {
  while (n > 0) {
    const char* nl = static_cast<const char*>(std::memchr(p, '\n', n));
    const size_t len = nl ? static_cast<size_t>(nl - p) : n;
    if (!discarding) rx.append(p, len);
    if (rx.size() > kLineMax) {
      std::snprintf(line, sizeof line, "%.200s", rx.c_str());
      reject("line longer than 16384 bytes, dropped");
      rx.clear();
      discarding = true;
    }
    if (!nl) return;
    if (!discarding) {
      if (rx.find('\0') != std::string::npos) {
        std::snprintf(line, sizeof line, "%.200s", rx.c_str());
        reject("NUL byte in the line");
      } else {
        std::memcpy(line, rx.data(), rx.size());
        line[rx.size()] = '\0';
        handle(out);
      }
    }
    rx.clear();
    discarding = false;
    p = nl + 1;
    n -= len + 1;
  }
}

// Reads what the socket holds (at most kReadsPerPoll reads); false on end of stream or an error.
bool GpsdClient::Impl::read_available(std::vector<GpsdEvent>* out) {
  char buf[8192];
  for (int reads = 0; reads < kReadsPerPoll;) {
    const ssize_t r = ::recv(gd.gps_fd, buf, sizeof buf, MSG_DONTWAIT);
    if (r > 0) {
      ++reads;
      take(buf, static_cast<size_t>(r), out);
    } else if (r == 0) {
      return false;
    } else if (errno != EINTR) {
      return errno == EAGAIN || errno == EWOULDBLOCK;
    }
  }
  return true;
}

bool GpsdClient::poll(int64_t timeout_us, std::vector<GpsdEvent>* out) {
  Impl& I = *impl_;
  if (!I.connected) return false;
  if (timeout_us < 0) timeout_us = 0;
  if (timeout_us > INT_MAX) timeout_us = INT_MAX;
  struct pollfd p{I.gd.gps_fd, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>((timeout_us + 999) / 1000)) <= 0) return true;
  bool open = true;
  try {
    open = I.read_available(out);
  } catch (...) {
    // Never throw from poll (an allocation failure while appending): count and go on.
    ++I.unparsed;
  }
  if (!open) {
    I.connected = false;
    out->push_back(DeviceEnd{I.last_device});
  }
  return open;
}

}  // namespace mpgc::ship_bridge
