// Local NED frame <-> WGS84 latitude/longitude through GeographicLib's LocalCartesian
// (exact ellipsoidal transformation about the origin; heights are taken as 0).
#pragma once

#include <memory>
#include <stdexcept>

#include "mpgc/geom/vec2.hpp"

namespace mpgc::geo {

struct LatLon {
  double lat;  // [rad]
  double lon;  // [rad]
};

using NorthEast = geom::Vec2;  // [m] x north, y east

// Throws std::invalid_argument naming the value when lat/lon is not finite or out of range.
void check_latlon(double lat_rad, double lon_rad);

class LocalNed {
 public:
  explicit LocalNed(LatLon origin);
  ~LocalNed();
  LocalNed(const LocalNed&);
  LocalNed& operator=(const LocalNed&);
  LatLon origin() const { return origin_; }
  NorthEast to_ned(LatLon p) const;
  LatLon to_latlon(NorthEast p) const;

 private:
  struct Impl;
  LatLon origin_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpgc::geo
