// The one 2-D vector of the project: a point or a velocity in the local NED frame (x north, y east;
// metres or metres per second), and the exact distances every component measures with it: point to
// segment, and the closest approach of two points moving linearly over an interval (seed 000
// eq. 3-4; seed 003 eq. 11-14 without the horizon). The CPA of two ships on constant velocity
// (dcpa, tcpa, range) is colreg::cpa, built on cpa_time below.
//
//   geom::Vec2 a{0, 0}, b{100, 0};
//   double d2 = geom::point_segment_dist2({50, 30}, a, b);            // 900
//   geom::Approach c = geom::closest_approach({0, 100}, {0, -5}, 60);  // c.tau 20 s, c.dist2 0
#pragma once

#include <algorithm>
#include <cmath>

namespace mpgc::geom {

struct Vec2 {
  double x = 0.0;  // [m] north (or [m/s] for velocities)
  double y = 0.0;  // [m] east
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
// z component of a x b in NED, i.e. (a ^ b) . e_D of seed 000 eq. 17 and 19.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm2(Vec2 a) { return dot(a, a); }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline bool finite(Vec2 a) { return std::isfinite(a.x) && std::isfinite(a.y); }

// Squared distance from p to segment [a, b] (a degenerate segment is the point a).
inline double point_segment_dist2(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double l2 = norm2(ab);
  double s = l2 > 0.0 ? dot(p - a, ab) / l2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return norm2(p - (a + s * ab));
}
inline double point_segment_distance(Vec2 p, Vec2 a, Vec2 b) { return std::sqrt(point_segment_dist2(p, a, b)); }

// Distance between segments [a, b] and [c, d]: 0 when they cross, touch or overlap (orientation
// signs), else the least of the four endpoint-to-segment distances.
inline double segment_distance(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  auto orient = [](Vec2 o, Vec2 p, Vec2 q) {
    const double v = cross(p - o, q - o);
    return (v > 0) - (v < 0);
  };
  auto on_box = [](Vec2 p, Vec2 s, Vec2 t) {  // p collinear with [s, t]: within its box?
    return std::min(s.x, t.x) <= p.x && p.x <= std::max(s.x, t.x) && std::min(s.y, t.y) <= p.y &&
           p.y <= std::max(s.y, t.y);
  };
  const int o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return 0.0;
  if ((o1 == 0 && on_box(c, a, b)) || (o2 == 0 && on_box(d, a, b)) || (o3 == 0 && on_box(a, c, d)) ||
      (o4 == 0 && on_box(b, c, d)))
    return 0.0;
  // One root of the least square: sqrt is correctly rounded, hence monotone, so this is bit for
  // bit the least of the four distances.
  return std::sqrt(std::min(std::min(point_segment_dist2(a, c, d), point_segment_dist2(b, c, d)),
                            std::min(point_segment_dist2(c, a, b), point_segment_dist2(d, a, b))));
}

// Time at which |r0 + dv * t| is least, over all t (seed 003 eq. 14; may be negative: the closest
// point is past). 0 without relative motion (|dv|^2 <= min_dv2), where every time is as close.
inline double cpa_time(Vec2 r0, Vec2 dv, double min_dv2 = 0.0) {
  const double vv = norm2(dv);
  return vv > min_dv2 ? -dot(r0, dv) / vv : 0.0;
}

// The closest approach of two points moving linearly during [0, T]: relative position r0 at 0,
// relative velocity dv (own ship along an edge against a target by eq. 3; or two recorded ships
// between samples, with T = 1 and dv the change of the relative position).
struct Approach {
  double dist2;  // [m^2] least squared distance on the interval
  double tau;    // [s] when, in [0, T]
};
inline Approach closest_approach(Vec2 r0, Vec2 dv, double T) {
  const double tau = std::clamp(cpa_time(r0, dv), 0.0, T);
  return {norm2(r0 + tau * dv), tau};
}

}  // namespace mpgc::geom
