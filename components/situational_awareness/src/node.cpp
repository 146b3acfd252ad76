#include "mpgc/situational_awareness/node.hpp"

#include <cmath>

#include "mpgc/geo/angles.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::sa {

void declare(rt::ParamSet& ps, NodeParams& p) {
  const double inf = 1e12;  // ParamSet refuses infinities; a huge bound is "no limit"
  ps.add("period", &p.period, 0.5, "s", 0.01, 60.0, "publication period of sa/tracks and sa/encounters");
  ps.add("origin.source", &p.origin_source, "nav", "local NED origin: from the first NavState fix, or origin.lat/lon",
         {"nav", "param"});
  ps.add("origin.lat", &p.origin_lat, 0.0, "deg", -90.0, 90.0, "NED origin latitude (origin.source = param)");
  ps.add("origin.lon", &p.origin_lon, 0.0, "deg", -180.0, 180.0, "NED origin longitude (origin.source = param)");
  ps.add("own.timeout", &p.own_timeout, 5.0, "s", 0.1, 3600.0, "no encounters from an older own state");
  nav::declare_params(ps, &p.jumps);
  ps.add("sensors.ais_timeout", &p.ais_timeout, 30.0, "s", 1.0, 3600.0,
         "AIS reports heard, then none this long: degraded (class B reports every 30 s, class A 2-10 s)");
  ps.add("sensors.radar_timeout", &p.radar_timeout, 10.0, "s", 1.0, 3600.0,
         "radar scans heard, then none this long: degraded (a scan every 2-3 s)");
  auto& t = p.tracker;
  ps.add("tracker.process_noise", &t.process_noise, 0.01, "m^2/s^3", 1e-8, 100.0, "CV white-acceleration PSD");
  ps.add("tracker.ais_pos_std", &t.ais_pos_std, 10.0, "m", 0.1, 1000.0, "AIS position sigma per axis");
  ps.add("tracker.ais_vel_std", &t.ais_vel_std, 0.25, "m/s", 0.01, 10.0, "AIS velocity sigma per axis");
  ps.add("tracker.init_vel_std", &t.init_vel_std, 8.0, "m/s", 0.1, 100.0, "velocity sigma of a new radar track");
  ps.add("tracker.gate", &t.gate, 13.82, "-", 1.0, 100.0, "Mahalanobis gate (chi2 2 dof; 13.82 = 99.9 %)");
  ps.add("tracker.confirm_m", &t.confirm_m, 3, "-", 1, 32, "M of M-of-N confirmation");
  ps.add("tracker.confirm_n", &t.confirm_n, 5, "-", 1, 32, "N of M-of-N confirmation");
  ps.add("tracker.coast_after", &t.coast_after, 10.0, "s", 0.1, 3600.0, "confirmed track reported coasting after");
  ps.add("tracker.delete_after", &t.delete_after, 60.0, "s", 0.1, 3600.0,
         "track deleted when silent this long while the sensors report");
  ps.add("tracker.tentative_timeout", &t.tentative_timeout, 15.0, "s", 0.1, 3600.0, "tentative track deleted after");
  ps.add("tracker.max_input_gap", &t.max_input_gap, 30.0, "s", 0.1, 3600.0,
         "inputs further apart: a sensor outage, not counted as silence of any track");
  ps.add("tracker.max_future", &t.max_future, 1.0, "s", 0.0, 3600.0, "stamps further in the future are refused");
  ps.add("tracker.max_lag", &t.max_lag, 10.0, "s", 0.0, 3600.0, "stamps older than the newest by more are refused");
  ps.add("tracker.max_contacts", &t.max_contacts, 5000, "-", 1, 1000000, "larger radar sweeps are refused");
  ps.add("tracker.max_tracks", &t.max_tracks, 5000, "-", 1, 1000000, "no tracks are started beyond this");
  ps.add("tracker.max_speed", &t.max_speed, 40.0, "m/s", 1.0, 200.0, "faster AIS SOG is refused");
  ps.add("colreg.abaft_beam", &p.abaft_beam_deg, 22.5, "deg", 0.0, 90.0, "overtaking: abaft the beam by more (rule 13)");
  ps.add("colreg.head_on_sector", &p.head_on_sector_deg, 22.5, "deg", 0.0, 90.0, "head-on half sector (seed 000; DNV uses 5)");
  ps.add("colreg.overtake_aspect", &p.overtake_deg, 67.5, "deg", 0.0, 180.0, "DNV theta13Criteria");
  ps.add("colreg.crossing_aspect", &p.crossing_deg, 5.0, "deg", 0.0, 90.0, "DNV theta15Criteria");
  ps.add("colreg.d_colreg", &p.colreg.d_colreg, 6.0 * geo::kNauticalMile, "m", 1.0, inf, "COLREG zone radius");
  ps.add("colreg.cpa_risk", &p.colreg.cpa_risk, 0.7 * geo::kNauticalMile, "m", 1.0, inf, "risk if CPA closer");
  ps.add("colreg.tcpa_max", &p.colreg.tcpa_max, 1800.0, "s", 1.0, inf, "risk if CPA sooner");
}

colreg::ColregParams colreg_params(const NodeParams& p) {
  colreg::ColregParams c = p.colreg;
  c.abaft_beam = geo::deg2rad(p.abaft_beam_deg);
  c.head_on_sector = geo::deg2rad(p.head_on_sector_deg);
  c.overtake_aspect = geo::deg2rad(p.overtake_deg);
  c.crossing_aspect = geo::deg2rad(p.crossing_deg);
  c.validate();
  return c;
}

std::string own_problem(const NodeParams& p, bool have_own, double age) {
  if (!have_own) return "no own state yet";
  return age <= p.own_timeout ? "" : "own state stale";
}

colreg::ShipKinematics own_at(const OwnReport& r, double age) {
  const double vx = r.velocity_valid ? r.sog * std::cos(r.cog) : 0.0, vy = r.velocity_valid ? r.sog * std::sin(r.cog) : 0.0;
  const double hdg = r.heading_valid ? r.heading : std::nan("");
  return {r.x + vx * age, r.y + vy * age, vx, vy, hdg};
}

}  // namespace mpgc::sa
