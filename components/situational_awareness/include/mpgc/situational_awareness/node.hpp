// The situational awareness component's configuration and own-ship picture without DDS or a clock
// (mpgc_situational_awareness's main.cpp is wiring around it): its named parameters, the COLREG
// parameters they make (sector angles given in degrees), and the own ship at the publication time
// from its last report (or why there is none).
//
//   sa::NodeParams p;  sa::declare(ps, p);  ps.validate_and_apply();
//   const colreg::ColregParams cp = sa::colreg_params(p);
//   std::string why = sa::own_problem(p, have_own, age);  // "" when fresh
//   colreg::ShipKinematics k = sa::own_at(report, age);
#pragma once

#include <string>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/situational_awareness/tracker.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::sa {

struct NodeParams {
  double period = 0.5;          // [s] sa/tracks and sa/encounters period
  std::string origin_source;    // "nav": from the first valid NavState fix; "param": origin.lat/lon
  double origin_lat = 0.0;      // [deg]
  double origin_lon = 0.0;      // [deg]
  double own_timeout = 5.0;     // [s] no encounters from an own state older than this
  double ais_timeout = 30.0;    // [s] sensors/ais heard, then silent this long: health DEGRADED
  double radar_timeout = 10.0;  // [s] sensors/radar likewise
  nav::JumpGateParams jumps;    // own position jumps (timeout: own_timeout)
  TrackerParams tracker;
  colreg::ColregParams colreg;  // the distances; the angles come from the *_deg below
  double abaft_beam_deg = 22.5, head_on_sector_deg = 22.5, overtake_deg = 67.5, crossing_deg = 5.0;  // [deg]

  nav::JumpGateParams jump_gate() const { return {jumps.max_speed, jumps.margin, own_timeout}; }
};

// Declares every parameter of the component.
void declare(rt::ParamSet& ps, NodeParams& p);

// The encounters' COLREG parameters: the distances as given, the sectors from degrees; validated
// (throws std::invalid_argument).
colreg::ColregParams colreg_params(const NodeParams& p);

// The own ship as last reported.
struct OwnReport {
  double x = 0, y = 0;      // [m]
  double sog = 0, cog = 0;  // [m/s], [rad]
  double heading = 0;       // [rad]
  bool velocity_valid = false, heading_valid = false;
};
// Why no encounters are assessed now ("no own state yet", "own state stale"); "" when the own
// state, `age` [s] old, is fresh enough.
std::string own_problem(const NodeParams& p, bool have_own, double age);
// The own ship `age` [s] after its report, predicted at its velocity over ground (none when the
// velocity is not valid; heading NaN when not valid).
colreg::ShipKinematics own_at(const OwnReport& r, double age);

}  // namespace mpgc::sa
