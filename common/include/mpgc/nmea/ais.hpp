// AIS (ITU-R M.1371-5) encoder: the messages a class A transponder sends, as !AIVDM sentences
// (IEC 61162-1: 6-bit armoured payload, fill bits, fragments of at most 60 payload characters,
// checksum). Decoding is gpsd's job on the bridge side; the encoder is tested against gpsd.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mpgc::ais {

// Message 1/2/3: class A position report. NaN = not available (encoded as the standard's n/a value).
struct PositionReport {
  int type = 1;               // 1, 2 or 3
  uint32_t mmsi = 0;
  int nav_status = 15;        // 0..15
  double rot_deg_min = 0.0 / 0.0;  // [deg/min] ROT_AIS = 4.733 sqrt|rot|, signed, saturating at +-126
                                   // (+-infinity: +-127, turning fast without a turn indicator)
  double sog_kn = 0.0 / 0.0;  // [kn] 0.1 kn, 102.2 for >= 102.2
  bool accuracy = false;
  double lon_deg = 181.0, lat_deg = 91.0;  // [deg] 1/10000 min
  double cog_deg = 0.0 / 0.0; // [deg] 0.1 deg
  double heading_deg = 0.0 / 0.0;  // [deg] whole degrees (511 n/a)
  int second = 60;            // UTC second
  int maneuver = 0;
  bool raim = false;
  uint32_t radio = 0;         // 19 bits of communication state
};

// Message 5: class A static and voyage data.
struct StaticVoyage {
  uint32_t mmsi = 0;
  uint32_t imo = 0;
  std::string callsign;       // up to 7 characters of the 6-bit alphabet
  std::string name;           // up to 20 characters
  int ship_type = 0;
  int to_bow = 0, to_stern = 0, to_port = 0, to_starboard = 0;  // [m] antenna position
  double draught_m = 0.0;     // [m] 0.1 m
  std::string destination;    // up to 20 characters
};

// Bit-level payload: append unsigned/signed fields MSB first, 6-bit text, then armour.
class Payload {
 public:
  void put_uint(uint32_t value, int bits);
  void put_int(int32_t value, int bits);
  void put_text(const std::string& s, int chars);  // ITU 6-bit ASCII, '@'-padded
  int bits() const { return static_cast<int>(bits_.size()); }
  // Armoured characters and the number of fill bits (0..5).
  std::string armoured(int* fill_bits) const;

 private:
  std::vector<bool> bits_;
};

Payload encode(const PositionReport& m);   // 168 bits
Payload encode(const StaticVoyage& m);     // 424 bits

// Framed sentences ("\r\n" included): one, or several fragments sharing sequential id `seq_id`
// (0..9) when the payload exceeds 60 characters. `own` gives !AIVDO (own ship) instead of !AIVDM.
std::vector<std::string> sentences(const Payload& p, char channel = 'A', int seq_id = 0, bool own = false);

}  // namespace mpgc::ais
