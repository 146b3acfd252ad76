// Spatial queries against the fixed obstacles (seed 000 §4.2): a set F of obstacle points in a
// kd-tree for nearest-obstacle distance, plus the land polygons for exact point-in-land and
// segment-clearance tests. Built by the obstacle manager from the chart, queried by the planner
// and the evaluation locally (no DDS, no clock): the one spatial index for fixed obstacles.
//
//   mpgc::geom::FixedObstacleMap map(points, polygons);  // NED metres
//   double d = map.nearest_distance({x, y});               // eq. 4: compare with d_safety
//   double c = map.segment_clearance(a, b);                 // 0 when the leg touches land
//
// Polygons: each ring is one closed boundary (first point not repeated). Rings that share a
// feature_id combine by the even-odd rule, so a feature's holes (lakes in land, islands in a
// shallow area) and multipolygon parts are expressed as several rings with one feature_id.
// Different features are united: a point is inside land when it is inside any feature.
//
// Which structure answers what:
//   * points  -> nanoflann kd-tree (exact nearest and radius queries), seed 000 §4.2;
//   * segment_clearance / clearance / inside_land -> an own static AABB tree over the polygon
//     edges and the points (as zero-length segments), with exact double-precision geometry.
//     It was chosen over FCL after `./mpgc bench obstacles` measured both (see the README).
// The object is immutable after construction, so concurrent const queries are safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

#include "mpgc/geom/vec2.hpp"

namespace mpgc::geom {

struct Polygon {
  uint32_t feature_id = 0;     // [-] chart feature; rings with one id combine even-odd
  std::vector<geom::Vec2> ring;   // [m] closed ring, first point not repeated, >= 3 points
};

// Axis-aligned box in NED.
struct BoxNE {
  double min_x, min_y, max_x, max_y;  // [m]
  bool contains(geom::Vec2 p) const { return p.x >= min_x && p.x <= max_x && p.y >= min_y && p.y <= max_y; }
  bool intersects(const BoxNE& o) const {
    return !(o.min_x > max_x || o.max_x < min_x || o.min_y > max_y || o.max_y < min_y);
  }
};

class FixedObstacleMap {
 public:
  // An empty map: every distance is +infinity, nothing is land.
  FixedObstacleMap();
  // Throws std::invalid_argument naming the offending point/ring when a coordinate is not finite
  // or a ring has fewer than 3 points.
  FixedObstacleMap(std::vector<geom::Vec2> points, std::vector<Polygon> polygons);
  ~FixedObstacleMap();
  FixedObstacleMap(FixedObstacleMap&&) noexcept;
  FixedObstacleMap& operator=(FixedObstacleMap&&) noexcept;
  FixedObstacleMap(const FixedObstacleMap&) = delete;  // holds index structures; share via shared_ptr
  FixedObstacleMap& operator=(const FixedObstacleMap&) = delete;

  const std::vector<geom::Vec2>& points() const;
  const std::vector<Polygon>& polygons() const;
  bool empty() const { return points().empty() && polygons().empty(); }

  // Distance [m] from p to the nearest obstacle POINT (kd-tree, exact); +inf without points.
  double nearest_distance(geom::Vec2 p) const;
  // Index into points() of the nearest point; SIZE_MAX without points.
  size_t nearest_index(geom::Vec2 p) const;
  // Indices of the points within distance r (inclusive) of p, sorted by distance. r >= 0.
  std::vector<size_t> radius(geom::Vec2 p, double r) const;

  // True when p is inside a polygon (even-odd per feature, union over features). Points exactly
  // on a boundary may go either way; their clearance() is 0 in any case.
  bool inside_land(geom::Vec2 p) const;
  // Exact minimum distance [m] from p to any obstacle point or polygon edge; 0 inside land.
  double clearance(geom::Vec2 p) const;
  // Exact minimum distance [m] from the segment [a, b] to any obstacle (points and polygon
  // edges); 0 when the segment crosses or touches an edge or lies inside land. +inf when empty.
  double segment_clearance(geom::Vec2 a, geom::Vec2 b) const;
  // segment_clearance(a, b) >= d, answered faster: the search stops at the first obstacle closer
  // than d and never explores farther than d (the planner's collision check, seed 000 eq. 4).
  bool segment_clear(geom::Vec2 a, geom::Vec2 b, double d) const;
  // segment_clearance(a, b) == 0 (the leg touches an obstacle or lies in land), answered faster:
  // only the boxes the leg meets are searched.
  bool segment_touches(geom::Vec2 a, geom::Vec2 b) const;

  // Bounding box of every point and ring vertex (all zero when empty).
  BoxNE bounds() const;

 private:
  std::pair<size_t, double> nearest(geom::Vec2 p) const;  // index and squared distance; needs points
  static constexpr size_t kHintMinPoints = 64;  // fewer points: no starting-candidate grid
  static constexpr double kHintCells = 128;     // [-] cells along the points' box's longer side
  void build_hints();
  // No point closer than d to the query [qa, qb], looked for around its piece [a, b] (kd-tree
  // bisection).
  bool points_clear(geom::Vec2 qa, geom::Vec2 qb, geom::Vec2 a, geom::Vec2 b, double d, int depth) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpgc::geom
