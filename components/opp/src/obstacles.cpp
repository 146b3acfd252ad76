#include "mpgc/opp/obstacles.hpp"

#include <limits>
#include <stdexcept>
#include <string>

#include <nanoflann.hpp>

namespace mpgc::opp {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double NoFixedObstacles::nearest(Vec2) const { return kInf; }

DiscObstacles::DiscObstacles(std::vector<Disc> discs) : discs_(std::move(discs)) {
  for (size_t i = 0; i < discs_.size(); ++i) {
    if (!finite(discs_[i].c) || !std::isfinite(discs_[i].r) || discs_[i].r < 0.0)
      throw std::invalid_argument("DiscObstacles: disc " + std::to_string(i) + " has a non-finite centre or bad radius");
  }
}

double DiscObstacles::nearest(Vec2 p) const {
  double best = kInf;
  for (const auto& d : discs_) best = std::min(best, std::max(0.0, norm(p - d.c) - d.r));
  return best;
}

bool DiscObstacles::segment_clear(Vec2 a, Vec2 b, double d) const {
  for (const auto& c : discs_) {
    const double rr = c.r + d;
    if (point_segment_dist2(c.c, a, b) < rr * rr) return false;
  }
  return true;
}

// nanoflann adaptor over the point vector.
struct PointObstacles::Index {
  struct Cloud {
    const std::vector<Vec2>* pts;
    size_t kdtree_get_point_count() const { return pts->size(); }
    double kdtree_get_pt(size_t i, size_t dim) const { return dim == 0 ? (*pts)[i].x : (*pts)[i].y; }
    template <class B>
    bool kdtree_get_bbox(B&) const { return false; }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 2, uint32_t>;
  Cloud cloud;
  Tree tree;
  explicit Index(const std::vector<Vec2>* p) : cloud{p}, tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

PointObstacles::PointObstacles(std::vector<Vec2> points) : points_(std::move(points)) {
  for (size_t i = 0; i < points_.size(); ++i)
    if (!finite(points_[i])) throw std::invalid_argument("PointObstacles: point " + std::to_string(i) + " is not finite");
  if (!points_.empty()) index_ = std::make_unique<Index>(&points_);
}

PointObstacles::~PointObstacles() = default;

double PointObstacles::nearest(Vec2 p) const {
  if (!index_) return kInf;
  uint32_t idx = 0;
  double d2 = 0.0;
  nanoflann::KNNResultSet<double, uint32_t> rs(1);
  rs.init(&idx, &d2);
  const double q[2] = {p.x, p.y};
  index_->tree.findNeighbors(rs, q, nanoflann::SearchParams(0));
  return std::sqrt(d2);
}

namespace {
// Radius result set that stops at the first point closer than d to the segment.
struct SegmentHit {
  using DistanceType = double;
  using IndexType = uint32_t;
  const std::vector<Vec2>* pts;
  Vec2 a, b;
  double r2;  // search radius^2 around the midpoint
  double d2;  // clearance^2 required
  bool hit = false;
  size_t size() const { return hit ? 1 : 0; }
  bool full() const { return true; }
  double worstDist() const { return r2; }
  bool addPoint(double dist2, uint32_t i) {
    if (dist2 >= r2) return true;
    if (point_segment_dist2((*pts)[i], a, b) < d2) {
      hit = true;
      return false;
    }
    return true;
  }
};
}  // namespace

bool PointObstacles::segment_clear(Vec2 a, Vec2 b, double d) const {
  if (!index_) return true;
  return clear_piece(a, b, d, 0);
}

// Exact, by bisection on nearest-point queries: every point within d of [a, b] lies within
// half + d of its midpoint m, so nearest(m) >= half + d proves the piece clear and nearest(m) < d
// proves it blocked. Otherwise the two halves are tried; a small piece (or a deep one) ends with a
// radius search, which then only visits the thin annulus nearest(m) <= r < half + d. Much cheaper
// than one radius search around a long leg passing a densely sampled shore.
bool PointObstacles::clear_piece(Vec2 a, Vec2 b, double d, int depth) const {
  const Vec2 m = 0.5 * (a + b);
  const double half = 0.5 * norm(b - a);
  const double nm = nearest(m);
  if (nm >= half + d) return true;
  if (nm < d) return false;
  if (depth < 24 && half > std::max(0.5, 0.02 * d))
    return clear_piece(a, m, d, depth + 1) && clear_piece(m, b, d, depth + 1);
  SegmentHit rs{&points_, a, b, (half + d) * (half + d), d * d};
  const double q[2] = {m.x, m.y};
  index_->tree.findNeighbors(rs, q, nanoflann::SearchParams(0));
  return !rs.hit;
}

}  // namespace mpgc::opp
