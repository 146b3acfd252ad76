#include "mpgc/situational_awareness/situation.hpp"

#include <cmath>
#include <stdexcept>

namespace mpgc::sa {

std::vector<TrackEncounter> encounters(const colreg::ShipKinematics& own, const std::vector<Track>& tracks,
                                       const colreg::ColregParams& p) {
  std::vector<TrackEncounter> out;
  out.reserve(tracks.size());
  for (const Track& t : tracks) {
    if (t.status == TrackStatus::kTentative) continue;
    const colreg::ShipKinematics k{t.x(0), t.x(1), t.x(2), t.x(3)};
    if (!k.finite()) continue;
    out.push_back({t.id, t.mmsi, colreg::assess(own, k, p), colreg::bearing(own, k)});
  }
  return out;
}

geo::LatLon origin_from_fix(geo::LatLon fix, geo::NorthEast ned) {
  geo::check_latlon(fix.lat, fix.lon);
  if (!std::isfinite(ned.x) || !std::isfinite(ned.y))
    throw std::invalid_argument("origin_from_fix: NED position is not finite");
  // First guess: step back from the fix by the NED offset in the fix's own tangent plane; then
  // move the guess by the residual seen from it until the fix maps onto `ned`.
  geo::LatLon o = geo::LocalNed(fix).to_latlon({-ned.x, -ned.y});
  for (int i = 0; i < 20; ++i) {
    const geo::LocalNed frame(o);
    const geo::NorthEast got = frame.to_ned(fix);
    const double ex = got.x - ned.x, ey = got.y - ned.y;
    if (std::hypot(ex, ey) < 1e-4) return o;
    o = frame.to_latlon({ex, ey});
  }
  throw std::invalid_argument("origin_from_fix: no convergence (offset too large?)");
}

}  // namespace mpgc::sa
