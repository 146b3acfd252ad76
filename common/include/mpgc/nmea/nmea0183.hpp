// NMEA 0183 / IEC 61162-1 sentences: framing and checksum, a tolerant parser that names what is
// wrong, encoders for what the simulator sends as the ship's devices (GGA, RMC, VTG, HDT, ROT, and
// the actuator wire's ROR/PRC orders and RSA/RPM feedback), decoders for what the bridge reads.
// Units at this edge are the sentences' own (degrees, knots, degrees per minute); SI inside.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpgc::nmea {

// Two upper-case hex digits: XOR of every character of `body` (what lies between '$'/'!' and '*').
std::string checksum(std::string_view body);
// start + body + '*' + checksum + "\r\n", e.g. frame('$', "GPHDT,47.5,T") == "$GPHDT,47.5,T*03\r\n".
std::string frame(char start, std::string_view body);

struct Sentence {
  char start = '$';                 // '$' (parametric) or '!' (encapsulated, AIS)
  std::string talker;               // e.g. "GP", "HE", "AI"; "P" for proprietary ($P...)
  std::string type;                 // e.g. "HDT", "VDM"
  std::vector<std::string> fields;  // after the address field, empty fields kept
};

// Parses one line (trailing CR/LF and whitespace ignored; an IEC 61162-450 / NMEA 4.10 tag block
// "\...\" before the sentence is skipped). A missing checksum is accepted only when
// require_checksum is false. On failure returns nullopt and sets *why (e.g. "bad checksum: got 4B,
// computed 4A", "no '$' or '!'", "sentence longer than 82 characters", "non-printable character").
std::optional<Sentence> parse(std::string_view line, std::string* why, bool require_checksum = true);

// ---- encoders (one framed sentence each, "\r\n" included) ----

struct FixData {
  int64_t utc_ns = 0;         // [ns] UTC, Unix epoch
  double lat_deg = 0.0;       // [deg] WGS84
  double lon_deg = 0.0;       // [deg]
  double sog_kn = 0.0;        // [kn]
  double cog_deg = 0.0;       // [deg] true, 0..360
  int quality = 1;            // [-] GGA fix quality (0 invalid, 1 GPS, 2 DGPS)
  int satellites = 10;        // [-]
  double hdop = 0.9;          // [-]
  double altitude_m = 20.0;   // [m] antenna above MSL (GGA: makes gpsd report a 3-D fix)
};
// Positions with 6 decimals of minutes (0.002 m), speeds to 0.01 kn, courses to 0.01 deg.
std::string gga(std::string_view talker, const FixData& f);
std::string rmc(std::string_view talker, const FixData& f);  // status A (or V when quality == 0)
std::string vtg(std::string_view talker, const FixData& f);
std::string hdt(std::string_view talker, double heading_deg);          // 0..360, 0.01 deg
std::string ths(std::string_view talker, double heading_deg, char mode = 'A');
std::string rot(std::string_view talker, double rot_deg_min, bool valid = true);  // '-' = bow to port
// Actuator wire (README "Putting mpgc on a boat"): orders from the bridge, feedback from the ship.
std::string ror(std::string_view talker, double rudder_order_deg, char source = 'C');  // '-' = port
std::string prc(std::string_view talker, double rpm_demand, int shaft = 1);
std::string rsa(std::string_view talker, double rudder_deg);  // '-' = port
std::string rpm(std::string_view talker, double rpm_value, int shaft = 1, char source = 'S');

// ---- decoders: nullopt and *why when the sentence is not of the type or its fields are bad ----

struct Heading { double heading_deg; };            // HDT, or THS with mode A/E/M/S (not V)
struct RateOfTurn { double rot_deg_min; };         // ROT with status A
struct RudderAngle { double rudder_deg; };         // RSA starboard (or single) sensor, status A; ROR order
struct ShaftRpm { double rpm; int shaft; };        // RPM with status A; PRC rpm demand

std::optional<Heading> parse_hdt(const Sentence& s, std::string* why);
std::optional<Heading> parse_ths(const Sentence& s, std::string* why);
std::optional<RateOfTurn> parse_rot(const Sentence& s, std::string* why);
std::optional<RudderAngle> parse_rsa(const Sentence& s, std::string* why);
std::optional<RudderAngle> parse_ror(const Sentence& s, std::string* why);
std::optional<ShaftRpm> parse_rpm(const Sentence& s, std::string* why);
std::optional<ShaftRpm> parse_prc(const Sentence& s, std::string* why);

}  // namespace mpgc::nmea
