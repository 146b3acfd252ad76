#include "mpgc/geom/fixed_obstacle_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <nanoflann.hpp>

#include "segment_tree.hpp"

namespace mpgc::geom {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

struct PointCloud {
  const std::vector<geom::Vec2>* pts;
  size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return dim == 0 ? (*pts)[i].x : (*pts)[i].y; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 2,
                                                   size_t>;

// nanoflann's RadiusResultSet keeps d < r; the map promises d <= r, so accept ties explicitly.
struct InclusiveRadius {
  double r2;
  std::vector<std::pair<size_t, double>>& out;
  size_t size() const { return out.size(); }
  bool full() const { return true; }
  bool addPoint(double d2, size_t i) {
    if (d2 <= r2) out.emplace_back(i, d2);
    return true;
  }
  double worstDist() const { return std::nextafter(r2, kInf); }
};

// The nearest point with a known candidate: the search starts bounded by the candidate's distance,
// so it visits only the kd-tree's cells closer than that. Strictly closer points replace it, as in
// nanoflann's KNNResultSet, and every distance is the tree's own evalMetric: the distance found is
// the same bit for bit as an unbounded search's.
struct BoundedNearest {
  size_t idx;
  double d2;
  size_t size() const { return 1; }
  bool full() const { return true; }
  bool addPoint(double d, size_t i) {
    if (d < d2) {
      d2 = d;
      idx = i;
    }
    return true;
  }
  double worstDist() const { return d2; }
};

void check_query(geom::Vec2 p, const char* what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw std::invalid_argument(std::string(what) + ": query point is not finite (" + std::to_string(p.x) + ", " +
                                std::to_string(p.y) + ")");
}

void check_point(geom::Vec2 p, const std::string& what) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    throw std::invalid_argument(what + " is not finite (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")");
}
}  // namespace

struct FixedObstacleMap::Impl {
  std::vector<geom::Vec2> points;
  std::vector<Polygon> polygons;
  PointCloud cloud{&points};
  KdTree kd;  // over `points` (leaf size 10)
  detail::SegmentTree edges_and_points;  // min distance: polygon edges + points (zero length)
  detail::SegmentTree edges;             // ray crossings: polygon edges only
  BoxNE box{0, 0, 0, 0};
  // Starting candidates for nearest(): the nearest point of each cell's centre, on a grid over the
  // points' box (a query outside takes the closest cell's; any point is a valid start). A query
  // far off a long shore (the canal's walls, kilometres away) otherwise starts from the point of
  // the tree's cell it falls in, often far along the shore, and visits every cell within that
  // distance (issue 20: a quarter of the canal's planning time).
  struct HintGrid {
    double x0 = 0, y0 = 0, inv_h = 0;
    int nx = 0, ny = 0;
    std::vector<uint32_t> idx;
  } hint;

  Impl(std::vector<geom::Vec2> p, std::vector<Polygon> g)
      : points(std::move(p)), polygons(std::move(g)), cloud{&points}, kd(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
};

FixedObstacleMap::FixedObstacleMap() : FixedObstacleMap({}, {}) {}

FixedObstacleMap::FixedObstacleMap(std::vector<geom::Vec2> points, std::vector<Polygon> polygons) {
  for (size_t i = 0; i < points.size(); ++i) check_point(points[i], "obstacle point " + std::to_string(i));
  for (size_t k = 0; k < polygons.size(); ++k) {
    const auto& r = polygons[k].ring;
    const std::string name = "polygon " + std::to_string(k) + " (feature " + std::to_string(polygons[k].feature_id) + ")";
    if (r.size() < 3) throw std::invalid_argument(name + " has " + std::to_string(r.size()) + " points, needs >= 3");
    for (size_t i = 0; i < r.size(); ++i) check_point(r[i], name + " vertex " + std::to_string(i));
  }
  if (points.size() >= std::numeric_limits<uint32_t>::max() / 2)
    throw std::invalid_argument("too many obstacle points: " + std::to_string(points.size()));

  std::vector<detail::Segment> all, edges;
  for (const auto& g : polygons)
    for (size_t i = 0; i < g.ring.size(); ++i) edges.push_back({g.ring[i], g.ring[(i + 1) % g.ring.size()], g.feature_id});
  all = edges;
  all.reserve(edges.size() + points.size());
  for (const auto& p : points) all.push_back({p, p, detail::kNoGroup});

  impl_ = std::make_unique<Impl>(std::move(points), std::move(polygons));
  impl_->edges = detail::SegmentTree(std::move(edges));
  impl_->edges_and_points = detail::SegmentTree(std::move(all));
  impl_->box = impl_->edges_and_points.bounds();
  build_hints();
}

void FixedObstacleMap::build_hints() {
  auto& g = impl_->hint;
  const auto& pts = impl_->points;
  if (pts.size() < kHintMinPoints) return;
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const auto& p : pts) {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  const double h = std::max({x1 - x0, y1 - y0, 1.0}) / kHintCells;
  g.x0 = x0, g.y0 = y0, g.inv_h = 1.0 / h;
  g.nx = std::max(1, static_cast<int>(std::ceil((x1 - x0) / h)));
  g.ny = std::max(1, static_cast<int>(std::ceil((y1 - y0) / h)));
  g.idx.resize(static_cast<size_t>(g.nx) * static_cast<size_t>(g.ny));
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) {
      size_t k = 0;
      double d2 = 0;
      nanoflann::KNNResultSet<double, size_t> rs(1);
      rs.init(&k, &d2);
      const double q[2] = {x0 + (i + 0.5) * h, y0 + (j + 0.5) * h};
      impl_->kd.findNeighbors(rs, q, nanoflann::SearchParams());
      g.idx[static_cast<size_t>(i) * static_cast<size_t>(g.ny) + static_cast<size_t>(j)] = static_cast<uint32_t>(k);
    }
}

FixedObstacleMap::~FixedObstacleMap() = default;
FixedObstacleMap::FixedObstacleMap(FixedObstacleMap&&) noexcept = default;
FixedObstacleMap& FixedObstacleMap::operator=(FixedObstacleMap&&) noexcept = default;

const std::vector<geom::Vec2>& FixedObstacleMap::points() const { return impl_->points; }
const std::vector<Polygon>& FixedObstacleMap::polygons() const { return impl_->polygons; }
BoxNE FixedObstacleMap::bounds() const { return impl_->box; }

// The nearest point of a non-empty map: its index and squared distance.
std::pair<size_t, double> FixedObstacleMap::nearest(geom::Vec2 p) const {
  const double q[2] = {p.x, p.y};
  const auto& g = impl_->hint;
  if (g.idx.empty()) {
    size_t idx = 0;
    double d2 = 0;
    nanoflann::KNNResultSet<double, size_t> rs(1);
    rs.init(&idx, &d2);
    impl_->kd.findNeighbors(rs, q, nanoflann::SearchParams());
    return {idx, d2};
  }
  // Clamped as doubles: a far query's cell index would not fit an int.
  const auto i = static_cast<size_t>(std::clamp((p.x - g.x0) * g.inv_h, 0.0, g.nx - 1.0));
  const auto j = static_cast<size_t>(std::clamp((p.y - g.y0) * g.inv_h, 0.0, g.ny - 1.0));
  const size_t k = g.idx[i * static_cast<size_t>(g.ny) + j];
  BoundedNearest rs{k, impl_->kd.distance.evalMetric(q, k, 2)};
  impl_->kd.findNeighbors(rs, q, nanoflann::SearchParams());
  return {rs.idx, rs.d2};
}

size_t FixedObstacleMap::nearest_index(geom::Vec2 p) const {
  check_query(p, "nearest_index");
  return impl_->points.empty() ? std::numeric_limits<size_t>::max() : nearest(p).first;
}

double FixedObstacleMap::nearest_distance(geom::Vec2 p) const {
  check_query(p, "nearest_distance");
  return impl_->points.empty() ? kInf : std::sqrt(nearest(p).second);
}

std::vector<size_t> FixedObstacleMap::radius(geom::Vec2 p, double r) const {
  check_query(p, "radius");
  if (!(r >= 0.0) || !std::isfinite(r))
    throw std::invalid_argument("radius: r = " + std::to_string(r) + " must be finite and >= 0");
  std::vector<size_t> out;
  if (impl_->points.empty()) return out;
  std::vector<std::pair<size_t, double>> found;
  InclusiveRadius rs{r * r, found};
  const double q[2] = {p.x, p.y};
  impl_->kd.findNeighbors(rs, q, nanoflann::SearchParams());
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return a.second < b.second || (a.second == b.second && a.first < b.first); });
  out.reserve(found.size());
  for (const auto& f : found) out.push_back(f.first);
  return out;
}

bool FixedObstacleMap::inside_land(geom::Vec2 p) const {
  check_query(p, "inside_land");
  return impl_->edges.odd_crossings(p);
}

double FixedObstacleMap::clearance(geom::Vec2 p) const {
  check_query(p, "clearance");
  if (inside_land(p)) return 0.0;
  // The nearest point by the kd-tree, the nearest edge by the segment tree: the same exact value
  // as segment_clearance(p, p), faster on dense point sets. The point's distance bounds the edge
  // search: only boxes closer than it are visited.
  return impl_->edges.min_distance(p, p, nearest_distance(p));
}

// Exact, by bisection on nearest-point queries: every point within d of the piece [a, b] of the
// query [qa, qb] lies within half + d of its midpoint m, so nearest(m) > half + d proves the piece
// clear and nearest(m) < d proves it blocked (each with a margin far above rounding). Otherwise the
// two halves are tried; a small piece (or a deep one) ends with a radius search, which then only
// visits the thin annulus around m, and judges each point found by the same segment_distance to
// the whole query as the segment tree (so ties come out as in segment_clearance). Much cheaper
// than one search around a long leg passing a densely sampled shore.
bool FixedObstacleMap::points_clear(geom::Vec2 qa, geom::Vec2 qb, geom::Vec2 a, geom::Vec2 b, double d, int depth) const {
  const geom::Vec2 m = 0.5 * (a + b);
  const double half = 0.5 * geom::norm(b - a);
  const double tol = 1e-9 * (1.0 + half + d);
  const double nm = nearest_distance(m);
  if (nm > half + d + tol) return true;
  if (nm + tol < d) return false;
  if (depth < 24 && half > std::max(0.5, 0.02 * d))
    return points_clear(qa, qb, a, m, d, depth + 1) && points_clear(qa, qb, m, b, d, depth + 1);
  std::vector<std::pair<size_t, double>> found;
  const double r = half + d + tol;
  InclusiveRadius rs{r * r, found};
  const double q[2] = {m.x, m.y};
  impl_->kd.findNeighbors(rs, q, nanoflann::SearchParams());
  for (const auto& f : found) {
    const geom::Vec2 p = impl_->points[f.first];
    if (geom::segment_distance(qa, qb, p, p) < d) return false;
  }
  return true;
}

double FixedObstacleMap::segment_clearance(geom::Vec2 a, geom::Vec2 b) const {
  check_query(a, "segment_clearance");
  check_query(b, "segment_clearance");
  // Without an edge crossing, the whole segment is on the side of `a`; so one inside test suffices.
  if (inside_land(a)) return 0.0;
  return impl_->edges_and_points.min_distance(a, b);
}

}  // namespace mpgc::geom

namespace mpgc::geom {

bool FixedObstacleMap::segment_touches(geom::Vec2 a, geom::Vec2 b) const {
  check_query(a, "segment_touches");
  check_query(b, "segment_touches");
  return inside_land(a) || impl_->edges_and_points.any_touching(a, b);
}

bool FixedObstacleMap::segment_clear(geom::Vec2 a, geom::Vec2 b, double d) const {
  check_query(a, "segment_clear");
  check_query(b, "segment_clear");
  if (std::isnan(d)) throw std::invalid_argument("segment_clear: distance is NaN");
  if (inside_land(a)) return d <= 0.0;
  if (impl_->edges.any_within(a, b, d)) return false;
  return impl_->points.empty() || points_clear(a, b, a, b, d, 0);
}

}  // namespace mpgc::geom
