#include "mpgc/geo/geodesy.hpp"

#include <cmath>
#include <string>

#include <GeographicLib/LocalCartesian.hpp>

#include "mpgc/geo/angles.hpp"

namespace mpgc::geo {

void check_latlon(double lat, double lon) {
  if (!std::isfinite(lat) || std::fabs(lat) > kPi / 2)
    throw std::invalid_argument("latitude " + std::to_string(rad2deg(lat)) + " deg is outside [-90, 90]");
  if (!std::isfinite(lon) || std::fabs(lon) > kPi)
    throw std::invalid_argument("longitude " + std::to_string(rad2deg(lon)) + " deg is outside [-180, 180]");
}

struct LocalNed::Impl {
  GeographicLib::LocalCartesian lc;
};

LocalNed::LocalNed(LatLon origin) : origin_(origin) {
  check_latlon(origin.lat, origin.lon);
  impl_ = std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(rad2deg(origin.lat), rad2deg(origin.lon), 0.0)});
}
LocalNed::~LocalNed() = default;
LocalNed::LocalNed(const LocalNed& o) : origin_(o.origin_), impl_(std::make_unique<Impl>(*o.impl_)) {}
LocalNed& LocalNed::operator=(const LocalNed& o) {
  origin_ = o.origin_;
  impl_ = std::make_unique<Impl>(*o.impl_);
  return *this;
}

NorthEast LocalNed::to_ned(LatLon p) const {
  check_latlon(p.lat, p.lon);
  double e = 0, n = 0, u = 0;
  impl_->lc.Forward(rad2deg(p.lat), rad2deg(p.lon), 0.0, e, n, u);
  return {n, e};
}

LatLon LocalNed::to_latlon(NorthEast p) const {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw std::invalid_argument("NED position is not finite");
  // The NED plane is tangent at the origin; find the point on the ellipsoid (h = 0) under (x, y)
  // so that to_ned(to_latlon(p)) == p. The up offset converges in a few steps (h changes by
  // ~1e-6 of the offset per step).
  double lat = 0, lon = 0, h = 0, up = 0;
  for (int i = 0; i < 4; ++i) {
    impl_->lc.Reverse(p.y, p.x, up, lat, lon, h);
    up -= h;
  }
  return {deg2rad(lat), deg2rad(lon)};
}

}  // namespace mpgc::geo
