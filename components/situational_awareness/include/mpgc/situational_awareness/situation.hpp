// The own ship's picture built from the tracks: CPA/TCPA and COLREG encounter of every
// established track (colreg::assess, the geometry the planner and the evaluation share), and the
// local NED origin recovered from a navigation fix.
#pragma once

#include <cstdint>
#include <vector>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/situational_awareness/tracker.hpp"

namespace mpgc::sa {

struct TrackEncounter {
  uint32_t track_id;
  uint32_t mmsi;
  colreg::Assessment assessment;
  double bearing;  // [rad] true bearing from the own ship
};

// Confirmed and coasting tracks (tentative ones are not yet trusted), each assessed against the
// own ship as constant-velocity ships; the track's heading is unknown, so its course is used.
std::vector<TrackEncounter> encounters(const colreg::ShipKinematics& own, const std::vector<Track>& tracks,
                                       const colreg::ColregParams& p);

// The origin O such that LocalNed(O).to_ned(fix) == ned, i.e. the frame the navigation source
// uses, found by fixed-point iteration (converges to < 1 mm in a few steps for offsets of tens of
// km). Throws std::invalid_argument for non-finite input or when it does not converge.
geo::LatLon origin_from_fix(geo::LatLon fix, geo::NorthEast ned);

}  // namespace mpgc::sa
