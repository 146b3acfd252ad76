// Test support for AIS: an armoured payload read back bit by bit, independently of mpgc::ais (the
// encoder under test), and the fields of message types 1-3 and 5 at their ITU-R M.1371 offsets.
// Header-only, no gtest: callers check sizes and values in their own assertions.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mpgc::testing {

// The bits of one or more armoured payload fragments, MSB first.
class AisBits {
 public:
  AisBits() = default;
  AisBits(const std::string& payload, int fill) { append(payload, fill); }

  // De-armours one fragment (6 bits a character: c - 48, less 8 above 40) and drops its `fill`
  // trailing bits.
  void append(const std::string& payload, int fill) {
    for (char ch : payload) {
      int v = ch - 48;
      if (v > 40) v -= 8;
      for (int k = 5; k >= 0; --k) bits_.push_back(static_cast<uint8_t>((v >> k) & 1));
    }
    for (int k = 0; k < fill && !bits_.empty(); ++k) bits_.pop_back();
  }

  size_t size() const { return bits_.size(); }

  // Unsigned field of `len` bits at `start` (std::out_of_range past the end).
  uint32_t u(int start, int len) const {
    uint32_t v = 0;
    for (int i = start; i < start + len; ++i) v = (v << 1) | static_cast<uint32_t>(bits_.at(static_cast<size_t>(i)));
    return v;
  }
  // Two's complement field.
  int32_t s(int start, int len) const {
    const uint32_t v = u(start, len);
    return (v >> (len - 1)) & 1U ? static_cast<int32_t>(v) - (1 << len) : static_cast<int32_t>(v);
  }
  // `chars` characters of 6-bit ASCII as sent: '@' padding kept (see ais_trimmed).
  std::string text(int start, int chars) const {
    std::string out;
    for (int i = 0; i < chars; ++i) {
      const uint32_t c = u(start + 6 * i, 6);
      out += static_cast<char>(c < 32 ? c + 64 : c);
    }
    return out;
  }

 private:
  std::vector<uint8_t> bits_;
};

// AIS text without its trailing '@' and space padding.
inline std::string ais_trimmed(std::string s) {
  while (!s.empty() && (s.back() == '@' || s.back() == ' ')) s.pop_back();
  return s;
}

// Message types 1, 2, 3 (168 bits): every field, raw.
struct AisType1 {
  uint32_t type, repeat, mmsi, status;
  int32_t rot;
  uint32_t sog, acc;
  int32_t lon, lat;
  uint32_t cog, hdg, second, maneuver, spare, raim, radio;
};
inline AisType1 ais_type1(const AisBits& b) {
  return {b.u(0, 6),    b.u(6, 2),    b.u(8, 30),   b.u(38, 4),   b.s(42, 8),   b.u(50, 10),
          b.u(60, 1),   b.s(61, 28),  b.s(89, 27),  b.u(116, 12), b.u(128, 9),  b.u(137, 6),
          b.u(143, 2),  b.u(145, 3),  b.u(148, 1),  b.u(149, 19)};
}

// Message type 5 (424 bits): every field, raw; text '@'-padded as sent.
struct AisType5 {
  uint32_t type, mmsi, version, imo;
  std::string callsign, name;
  uint32_t ship_type, bow, stern, port, stbd, epfd, month, day, hour, minute, draught;
  std::string destination;
  uint32_t dte, spare;
};
inline AisType5 ais_type5(const AisBits& b) {
  return {b.u(0, 6),    b.u(8, 30),   b.u(38, 2),   b.u(40, 30),  b.text(70, 7),   b.text(112, 20),
          b.u(232, 8),  b.u(240, 9),  b.u(249, 9),  b.u(258, 6),  b.u(264, 6),   b.u(270, 4),
          b.u(274, 4),  b.u(278, 5),  b.u(283, 5),  b.u(288, 6),  b.u(294, 8),   b.text(302, 20),
          b.u(422, 1),  b.u(423, 1)};
}

// ROT_AIS for a rate of turn [deg/min], computed here independently of the encoder:
// round(4.733 sqrt|rot|), signed, saturating at +-126; -128 when not available (NaN).
inline double expected_rot_ais(double rot_deg_min) {
  if (std::isnan(rot_deg_min)) return -128;
  return std::copysign(std::min(126.0, std::round(4.733 * std::sqrt(std::fabs(rot_deg_min)))), rot_deg_min);
}

}  // namespace mpgc::testing
