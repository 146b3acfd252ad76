#include "segment_tree.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mpgc::geom {


namespace detail {

namespace {
double point_box_dist2(geom::Vec2 p, const BoxNE& b) {
  const double dx = std::max({b.min_x - p.x, 0.0, p.x - b.max_x});
  const double dy = std::max({b.min_y - p.y, 0.0, p.y - b.max_y});
  return dx * dx + dy * dy;
}
// Liang-Barsky: does [a, b] meet the closed box?
bool segment_hits_box(geom::Vec2 a, geom::Vec2 b, const BoxNE& box) {
  double t0 = 0.0, t1 = 1.0;
  const double d[2] = {b.x - a.x, b.y - a.y};
  const double lo[2] = {box.min_x - a.x, box.min_y - a.y};
  const double hi[2] = {box.max_x - a.x, box.max_y - a.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (lo[k] > 0.0 || hi[k] < 0.0) return false;
    } else {
      double ta = lo[k] / d[k], tb = hi[k] / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
      if (t0 > t1) return false;
    }
  }
  return true;
}
constexpr uint32_t kLeafSize = 4;

// A cheap lower bound of segment_box_distance for the many boxes a query passes far from: the gap
// between the query's own box and the node's box. `gap_beyond(q, box, d)` is true only when that
// gap exceeds d by far more than rounding, so a node it prunes is one the exact distance would
// prune too: the queries visit the same leaves and return the same values.
bool gap_beyond(const BoxNE& q, const BoxNE& b, double d) {
  const double dx = std::max({b.min_x - q.max_x, 0.0, q.min_x - b.max_x});
  const double dy = std::max({b.min_y - q.max_y, 0.0, q.min_y - b.max_y});
  return dx * dx + dy * dy > d * d * (1.0 + 1e-9);
}
BoxNE box_of(geom::Vec2 a, geom::Vec2 b) {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)};
}
}  // namespace

double segment_box_distance(geom::Vec2 a, geom::Vec2 b, const BoxNE& box) {
  // A point (clearance queries): the distance to the box, which the general case below also
  // gives, bit for bit (a corner's distance to a point is no less than the box's).
  if (a == b) return std::sqrt(point_box_dist2(a, box));
  if (segment_hits_box(a, b, box)) return 0.0;
  // Two disjoint convex sets in the plane: the minimum is between a vertex of one and the other.
  // One root of the least square (sqrt is monotone): the same value as the least distance.
  double d2 = std::min(point_box_dist2(a, box), point_box_dist2(b, box));
  d2 = std::min(d2, geom::point_segment_dist2({box.min_x, box.min_y}, a, b));
  d2 = std::min(d2, geom::point_segment_dist2({box.min_x, box.max_y}, a, b));
  d2 = std::min(d2, geom::point_segment_dist2({box.max_x, box.min_y}, a, b));
  d2 = std::min(d2, geom::point_segment_dist2({box.max_x, box.max_y}, a, b));
  return std::sqrt(d2);
}

SegmentTree::SegmentTree(std::vector<Segment> segs) : segs_(std::move(segs)) {
  if (segs_.empty()) return;
  nodes_.reserve(2 * (segs_.size() / kLeafSize + 1));
  nodes_.push_back({});
  build(0, static_cast<uint32_t>(segs_.size()), nodes_);
}

uint32_t SegmentTree::build(uint32_t first, uint32_t count, std::vector<Node>& out) {
  // Iterative over an explicit stack of (node, first, count) so deep inputs cannot overflow.
  struct Job {
    uint32_t node, first, count;
  };
  std::vector<Job> jobs{{0, first, count}};
  while (!jobs.empty()) {
    const Job j = jobs.back();
    jobs.pop_back();
    BoxNE box{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
              -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    BoxNE cbox = box;  // box of the segment centres, to choose the split axis
    for (uint32_t i = j.first; i < j.first + j.count; ++i) {
      const Segment& s = segs_[i];
      box.min_x = std::min({box.min_x, s.a.x, s.b.x});
      box.max_x = std::max({box.max_x, s.a.x, s.b.x});
      box.min_y = std::min({box.min_y, s.a.y, s.b.y});
      box.max_y = std::max({box.max_y, s.a.y, s.b.y});
      const double cx = 0.5 * (s.a.x + s.b.x), cy = 0.5 * (s.a.y + s.b.y);
      cbox.min_x = std::min(cbox.min_x, cx);
      cbox.max_x = std::max(cbox.max_x, cx);
      cbox.min_y = std::min(cbox.min_y, cy);
      cbox.max_y = std::max(cbox.max_y, cy);
    }
    out[j.node].box = box;
    if (j.count <= kLeafSize) {
      out[j.node].first = j.first;
      out[j.node].count = j.count;
      continue;
    }
    const bool split_x = (cbox.max_x - cbox.min_x) >= (cbox.max_y - cbox.min_y);
    const uint32_t half = j.count / 2;
    auto key = [split_x](const Segment& s) { return split_x ? s.a.x + s.b.x : s.a.y + s.b.y; };
    std::nth_element(segs_.begin() + j.first, segs_.begin() + j.first + half, segs_.begin() + j.first + j.count,
                     [&](const Segment& l, const Segment& r) { return key(l) < key(r); });
    const auto left = static_cast<uint32_t>(out.size());
    out.push_back({});
    out.push_back({});
    out[j.node].first = left;
    out[j.node].count = 0;
    jobs.push_back({left, j.first, half});
    jobs.push_back({left + 1, j.first + half, j.count - half});
  }
  return 0;
}

double SegmentTree::min_distance(geom::Vec2 q0, geom::Vec2 q1, double bound) const {
  double best = bound;
  if (nodes_.empty()) return best;
  struct Item {
    uint32_t node;
    double lb;
  };
  Item stack[128];  // depth <= log2(4e9 / kLeafSize) << 64; two pushes per level
  int top = 0;
  const BoxNE qbox = box_of(q0, q1);
  // The exact box distance, or +inf where the cheap gap already rules the box out against best.
  auto lower = [&](const BoxNE& box) {
    return gap_beyond(qbox, box, best) ? std::numeric_limits<double>::infinity() : segment_box_distance(q0, q1, box);
  };
  stack[top++] = {0, segment_box_distance(q0, q1, nodes_[0].box)};
  while (top > 0) {
    const Item it = stack[--top];
    if (it.lb >= best) continue;
    const Node& n = nodes_[it.node];
    if (n.count > 0) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i)
        best = std::min(best, geom::segment_distance(q0, q1, segs_[i].a, segs_[i].b));
      if (best == 0.0) break;
      continue;
    }
    const double l = lower(nodes_[n.first].box);
    const double r = lower(nodes_[n.first + 1].box);
    // Push the farther child first so the nearer one is searched first and tightens `best`.
    if (l <= r) {
      if (r < best) stack[top++] = {n.first + 1, r};
      if (l < best) stack[top++] = {n.first, l};
    } else {
      if (l < best) stack[top++] = {n.first, l};
      if (r < best) stack[top++] = {n.first + 1, r};
    }
  }
  return best;
}

// Depth-first over the boxes `skip` does not rule out; true at the first segment whose distance to
// [q0, q1] (the same per-segment function as min_distance) `hit` accepts.
template <class Skip, class Hit>
bool SegmentTree::any_segment(geom::Vec2 q0, geom::Vec2 q1, Skip skip, Hit hit) const {
  if (nodes_.empty()) return false;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    if (skip(n.box)) continue;
    if (n.count == 0) {
      stack[top++] = n.first + 1;
      stack[top++] = n.first;
      continue;
    }
    for (uint32_t i = n.first; i < n.first + n.count; ++i)
      if (hit(geom::segment_distance(q0, q1, segs_[i].a, segs_[i].b))) return true;
  }
  return false;
}

bool SegmentTree::any_within(geom::Vec2 q0, geom::Vec2 q1, double d) const {
  const BoxNE qbox = box_of(q0, q1);
  return any_segment(
      q0, q1, [&](const BoxNE& b) { return gap_beyond(qbox, b, d) || !(segment_box_distance(q0, q1, b) < d); },
      [d](double dist) { return dist < d; });
}

bool SegmentTree::any_touching(geom::Vec2 q0, geom::Vec2 q1) const {
  const BoxNE qbox = box_of(q0, q1);
  // The cheap gap prunes only far above rounding (1 um); the exact box distance decides the rest
  // as min_distance's bound does.
  return any_segment(
      q0, q1, [&](const BoxNE& b) { return gap_beyond(qbox, b, 1e-6) || segment_box_distance(q0, q1, b) > 0.0; },
      [](double dist) { return dist == 0.0; });
}

bool SegmentTree::odd_crossings(geom::Vec2 p) const {
  if (nodes_.empty()) return false;
  // Cast the ray towards the nearest side of the root box: fewer nodes to visit. Parity is the
  // same for every direction (points exactly on a boundary aside). In (u, v) the ray is +v.
  const BoxNE& root = nodes_[0].box;
  const double reach[4] = {root.max_y - p.y, p.y - root.min_y, root.max_x - p.x, p.x - root.min_x};
  int dir = 0;
  for (int k = 1; k < 4; ++k)
    if (reach[k] < reach[dir]) dir = k;
  if (reach[dir] < 0.0) return false;  // outside the box of every edge
  auto uv = [dir](geom::Vec2 q) -> std::pair<double, double> {
    switch (dir) {
      case 0: return {q.x, q.y};    // east
      case 1: return {q.x, -q.y};   // west
      case 2: return {q.y, q.x};    // north
      default: return {q.y, -q.x};  // south
    }
  };
  auto box_uv = [dir](const BoxNE& b, double& umin, double& umax, double& vmax) {
    switch (dir) {
      case 0: umin = b.min_x; umax = b.max_x; vmax = b.max_y; break;
      case 1: umin = b.min_x; umax = b.max_x; vmax = -b.min_y; break;
      case 2: umin = b.min_y; umax = b.max_y; vmax = b.max_x; break;
      default: umin = b.min_y; umax = b.max_y; vmax = -b.min_x; break;
    }
  };
  const auto [pu, pv] = uv(p);
  std::vector<uint32_t> groups;
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[stack[--top]];
    double umin, umax, vmax;
    box_uv(n.box, umin, umax, vmax);
    if (pu < umin || pu > umax || pv > vmax) continue;
    if (n.count == 0) {
      stack[top++] = n.first;
      stack[top++] = n.first + 1;
      continue;
    }
    for (uint32_t i = n.first; i < n.first + n.count; ++i) {
      const auto [au, av] = uv(segs_[i].a);
      const auto [bu, bv] = uv(segs_[i].b);
      // Half-open rule on u so a ray through a vertex counts exactly one of its two edges.
      if ((au > pu) == (bu > pu)) continue;
      const double v = av + (pu - au) * (bv - av) / (bu - au);
      if (v > pv) groups.push_back(segs_[i].group);
    }
  }
  std::sort(groups.begin(), groups.end());
  for (size_t i = 0; i < groups.size();) {
    size_t j = i;
    while (j < groups.size() && groups[j] == groups[i]) ++j;
    if ((j - i) % 2 == 1) return true;
    i = j;
  }
  return false;
}

BoxNE SegmentTree::bounds() const { return nodes_.empty() ? BoxNE{0, 0, 0, 0} : nodes_[0].box; }

}  // namespace detail
}  // namespace mpgc::geom
