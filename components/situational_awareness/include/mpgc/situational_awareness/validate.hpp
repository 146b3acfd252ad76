// What situational_awareness refuses on nav/own_state, and how its sensor messages become the
// tracker's inputs (for the DDS side only: a component main that links mpgc_msgs, and the fuzz
// targets in tests/fuzz/). The tracker itself refuses bad AIS and radar values (Rejections).
// Moved verbatim from components/situational_awareness/main.cpp (check_nav, both to_input).
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/situational_awareness/tracker.hpp"

namespace mpgc::sa {

// nav/own_state: a valid, finite position; velocity and heading finite where flagged valid.
inline std::string check_nav(const msg::NavState& s) {
  if (!(s.valid_mask & msg::NAV_POSITION_VALID)) return "position not valid";
  if (!std::isfinite(s.x) || !std::isfinite(s.y)) return "x/y not finite";
  if ((s.valid_mask & msg::NAV_VELOCITY_VALID) && (!std::isfinite(s.sog) || !std::isfinite(s.cog) || s.sog < 0))
    return "sog/cog not finite";
  if ((s.valid_mask & msg::NAV_HEADING_VALID) && !std::isfinite(s.heading)) return "heading not finite";
  return {};
}

inline AisInput to_input(const msg::AisReport& r) {
  // The transmitter's fix time when given, else the reception stamp.
  const int64_t t = r.report_time_ns > 0 ? r.report_time_ns : r.header.stamp_ns;
  return {r.mmsi, t, r.lat, r.lon, r.cog, r.sog, r.length};
}

inline RadarScanInput to_input(const msg::RadarScan& s) {
  RadarScanInput in{s.header.stamp_ns, s.antenna_x, s.antenna_y, s.max_range, {}};
  in.contacts.reserve(s.contacts.size());
  for (const auto& c : s.contacts) in.contacts.push_back({c.range, c.bearing, c.range_std, c.bearing_std});
  return in;
}

}  // namespace mpgc::sa
