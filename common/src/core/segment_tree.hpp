// A static 2-D AABB tree over segments (polygon edges; points as zero-length segments) for exact
// minimum-distance and ray-crossing queries. Private to the library.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "mpgc/geom/fixed_obstacle_map.hpp"

namespace mpgc::geom::detail {

struct Segment {
  geom::Vec2 a, b;
  uint32_t group;  // even-odd group (polygon feature) or kNoGroup for points
};
inline constexpr uint32_t kNoGroup = std::numeric_limits<uint32_t>::max();

// Exact distance from the segment [a, b] to the box (0 when they intersect).
double segment_box_distance(geom::Vec2 a, geom::Vec2 b, const BoxNE& box);

class SegmentTree {
 public:
  SegmentTree() = default;
  explicit SegmentTree(std::vector<Segment> segs);
  size_t size() const { return segs_.size(); }
  // min over segments of segment_distance(q0, q1, s); +inf when empty. Exact: the same
  // per-segment function as a brute-force loop, with branch and bound on exact box distances
  // (a box far beyond the best so far is ruled out by the cheaper gap between boxes first).
  // With `bound`: min(bound, that), searching only where a segment could come closer than bound.
  double min_distance(geom::Vec2 q0, geom::Vec2 q1,
                      double bound = std::numeric_limits<double>::infinity()) const;
  // True when some segment is closer than d to [q0, q1] (same per-segment function).
  bool any_within(geom::Vec2 q0, geom::Vec2 q1, double d) const;
  // True when some segment is at distance 0 from [q0, q1] (min_distance(q0, q1) == 0, the same
  // per-segment function), searching only the boxes the query meets.
  bool any_touching(geom::Vec2 q0, geom::Vec2 q1) const;
  // Groups with an odd number of edges crossing the ray from p towards +y (east).
  bool odd_crossings(geom::Vec2 p) const;
  BoxNE bounds() const;

 private:
  struct Node {
    BoxNE box;
    uint32_t first;  // leaf: first segment; inner: index of the left child (right = left + 1)
    uint32_t count;  // leaf: number of segments; 0 for an inner node
  };
  uint32_t build(uint32_t first, uint32_t count, std::vector<Node>& out);
  template <class Skip, class Hit>
  bool any_segment(geom::Vec2 q0, geom::Vec2 q1, Skip skip, Hit hit) const;
  std::vector<Segment> segs_;
  std::vector<Node> nodes_;
};

}  // namespace mpgc::geom::detail
