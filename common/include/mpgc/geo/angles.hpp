// Angle conventions of design.md: radians, clockwise from north, wrapped to (-pi, pi].
#pragma once

#include <cmath>

namespace mpgc::geo {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kKnot = 1852.0 / 3600.0;  // [m/s] per knot
inline constexpr double kNauticalMile = 1852.0;   // [m]

inline constexpr double deg2rad(double d) { return d * kPi / 180.0; }
inline constexpr double rad2deg(double r) { return r * 180.0 / kPi; }

// Wraps to (-pi, pi]. NaN and infinities come back as NaN.
inline double wrap_pi(double a) {
  if (!std::isfinite(a)) return std::nan("");
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

// Wraps to [0, 2pi).
inline double wrap_2pi(double a) {
  if (!std::isfinite(a)) return std::nan("");
  a = std::fmod(a, 2.0 * kPi);
  return a < 0.0 ? a + 2.0 * kPi : a;
}

// Smallest signed difference a - b, in (-pi, pi].
inline double angle_diff(double a, double b) { return wrap_pi(a - b); }

// Course of the vector (north, east), clockwise from north.
inline double course_of(double north, double east) { return std::atan2(east, north); }

}  // namespace mpgc::geo
