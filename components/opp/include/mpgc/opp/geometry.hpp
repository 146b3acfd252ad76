// Small 2-D geometry used by the planner: NED points (x north, y east, metres) and the exact
// distance computations behind every edge check (seed 000 eq. 3-4).
#pragma once

#include <algorithm>
#include <cmath>

namespace mpgc::opp {

struct Vec2 {
  double x = 0.0;  // [m] north (or [m/s] for velocities)
  double y = 0.0;  // [m] east
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z component of a x b in NED, i.e. (a ^ b) . e_D of seed 000 eq. 17 and 19.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm2(Vec2 a) { return dot(a, a); }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline bool finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

// Squared distance from p to segment [a, b].
inline double point_segment_dist2(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double l2 = norm2(ab);
  double s = l2 > 0.0 ? dot(p - a, ab) / l2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return norm2(p - (a + s * ab));
}

// Minimum over tau in [0, T] of |r0 + dv * tau|^2: the closest approach of two points moving
// linearly (own ship along an edge, a target by eq. 3) during the time T the edge takes.
inline double min_dist2_linear(Vec2 r0, Vec2 dv, double T) {
  const double vv = norm2(dv);
  double tau = vv > 0.0 ? -dot(r0, dv) / vv : 0.0;
  tau = std::clamp(tau, 0.0, T);
  return norm2(r0 + tau * dv);
}

}  // namespace mpgc::opp
