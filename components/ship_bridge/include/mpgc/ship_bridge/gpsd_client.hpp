// A gpsd client (libgps, JSON watch) that turns gpsd's reports into plain values: position fixes
// (TPV), headings gpsd decoded (ATT, from HDT), AIS messages, raw NMEA lines when watched with
// nmea pass-through, and the end of a device. No DDS and no clock: the caller stamps what it gets.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace mpgc::ship_bridge {

// One TPV report. Unavailable values are NaN.
struct GnssFix {
  int mode = 0;               // [-] 0 unknown, 1 no fix, 2 2-D, 3 3-D (gpsd TPV mode)
  double lat_deg = 0.0 / 0.0; // [deg] WGS84
  double lon_deg = 0.0 / 0.0; // [deg] WGS84
  double speed = 0.0 / 0.0;   // [m/s] speed over ground
  double track_deg = 0.0 / 0.0; // [deg] course over ground, true
  int64_t time_ns = 0;        // [ns] UTC of the fix (Unix epoch), 0 if gpsd gave none
  std::string device;
};

// One ATT report with a heading (gpsd decodes HDT into it).
struct AttitudeHeading {
  double heading_deg = 0.0 / 0.0;  // [deg] true heading
  std::string device;
};

// One decoded AIS message, values in the units of ITU-R M.1371 converted to SI/degrees;
// unavailable values are NaN (or -1 for integers).
struct AisMessage {
  int type = 0;               // [-] message type 1..27
  uint32_t mmsi = 0;
  // position reports (types 1/2/3, 18, 19)
  bool has_position = false;
  double lat_deg = 0.0 / 0.0, lon_deg = 0.0 / 0.0;  // [deg]
  double sog = 0.0 / 0.0;     // [m/s]
  double cog_deg = 0.0 / 0.0; // [deg]
  double heading_deg = 0.0 / 0.0; // [deg]
  int turn_raw = -128;        // [-] ROT_AIS as sent (-128 n/a, +-127 turning fast without rate)
  int nav_status = 15;        // [-] 0..15 (15 = not defined; class B: 15)
  int second = 60;            // [-] UTC second of the report (60 = n/a)
  // static data (types 5, 19, 24)
  bool has_static = false;
  std::string name;           // trailing '@' and spaces stripped
  std::string callsign;
  int ship_type = -1;
  double to_bow = 0.0 / 0.0, to_stern = 0.0 / 0.0, to_port = 0.0 / 0.0, to_starboard = 0.0 / 0.0;  // [m]
  std::string device;
};

// A raw NMEA sentence gpsd passed through (watch with nmea = true).
struct RawNmea {
  std::string line;  // without CR/LF
};

// The device stopped (gpsd "DEVICE ... activated 0"), or gpsd closed the connection.
struct DeviceEnd {
  std::string device;
};

using GpsdEvent = std::variant<GnssFix, AttitudeHeading, AisMessage, RawNmea, DeviceEnd>;

// Why libgps 3.22 must not unpack this JSON line ("" = it may). When json_read_object fails
// (a key it does not know, a value of the wrong type, a string longer than its field), gps_unpack
// retries from where the error was; if another "class": follows there, it retries the same failing
// parse for ever, and malformed JSON can do the same (checked on this machine; found by
// fuzz_gpsd_json: a TPV with "mode":"x" before a second "class", an unknown key before the only
// "class", an AIS callsign longer than libgps's field, a DEVICES list whose first device has a
// path longer than GPS_PATH_MAX, two objects on one line). So a line reaches libgps only as one
// well-formed object whose first key is its only "class": then no "class": follows any error. gpsd
// writes every report so, except DEVICES (nested DEVICE classes), which the client does not unpack.
std::string gpsd_json_problem(std::string_view line);

class GpsdClient {
 public:
  // Connects to gpsd at host:port and watches in JSON (and raw NMEA when nmea is true).
  // Throws std::runtime_error naming host and port when gpsd cannot be reached.
  GpsdClient(const std::string& host, int port, bool nmea = false);
  ~GpsdClient();
  GpsdClient(const GpsdClient&) = delete;
  GpsdClient& operator=(const GpsdClient&) = delete;

  // Waits up to timeout_us for data, then reads every report that has arrived (never blocks longer).
  // Appends one event per report. Returns false once the connection is closed (a DeviceEnd is appended).
  bool poll(int64_t timeout_us, std::vector<GpsdEvent>* out);
  bool connected() const;
  uint64_t unparsed() const;  // [-] lines gpsd sent that gave no usable report

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpgc::ship_bridge
