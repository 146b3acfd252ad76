// ./mpgc bench obstacles [--seed N] [--chart FILE.000]
// Side by side in one run: build and query times of the nanoflann kd-tree against brute force
// for 1e3, 1e5 and 1e6 points; segment-clearance and land queries of the library's exact AABB
// tree against brute force and FCL (BVHModel<OBBRSS> of vertical wall triangles) on the real
// US4MD81M cell. Every comparison also counts disagreements, so speed never hides a wrong answer.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <fcl/fcl.h>
#include <nanoflann.hpp>

#include "mpgc/geo/angles.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace om = mpgc::obstacle_manager;
using mpgc::geom::Vec2;

namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Cloud {
  const std::vector<mpgc::geom::Vec2>* pts;
  size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(size_t i, size_t d) const { return d == 0 ? (*pts)[i].x : (*pts)[i].y; }
  template <class B>
  bool kdtree_get_bbox(B&) const {
    return false;
  }
};
using Kd = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 2, size_t>;

double brute_nearest(const std::vector<mpgc::geom::Vec2>& pts, mpgc::geom::Vec2 q) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pts) {
    const double dx = p.x - q.x, dy = p.y - q.y;
    best = std::min(best, dx * dx + dy * dy);
  }
  return std::sqrt(best);
}
size_t brute_radius(const std::vector<mpgc::geom::Vec2>& pts, mpgc::geom::Vec2 q, double r) {
  size_t n = 0;
  for (const auto& p : pts) {
    const double dx = p.x - q.x, dy = p.y - q.y;
    n += dx * dx + dy * dy <= r * r;
  }
  return n;
}

void bench_points(std::mt19937_64& rng) {
  std::printf("\n== kd-tree (nanoflann, used by FixedObstacleMap) vs brute force; uniform points in 20 km x 20 km ==\n");
  std::printf("%9s | %10s %10s | %12s %12s %8s | %12s %12s %8s | %s\n", "points", "build kd", "build map", "nearest kd",
              "nearest bf", "speedup", "radius kd", "radius bf", "speedup", "disagreements");
  std::printf("%9s | %10s %10s | %12s %12s %8s | %12s %12s %8s |\n", "", "[ms]", "[ms]", "[us/query]", "[us/query]", "",
              "[us/query]", "[us/query]", "");
  std::uniform_real_distribution<double> u(-10000.0, 10000.0);
  for (size_t n : {size_t{1000}, size_t{100000}, size_t{1000000}}) {
    std::vector<mpgc::geom::Vec2> pts(n);
    for (auto& p : pts) p = {u(rng), u(rng)};
    double t0 = now_s();
    Cloud cloud{&pts};
    Kd kd(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    const double build_kd = now_s() - t0;
    t0 = now_s();
    om::FixedObstacleMap map(pts, {});
    const double build_map = now_s() - t0;

    const int nq = 100000, nq_bf = static_cast<int>(std::max<size_t>(50, 200000000 / n / 20));
    std::vector<mpgc::geom::Vec2> qs(nq);
    for (auto& q : qs) q = {u(rng), u(rng)};
    double sink = 0;
    t0 = now_s();
    for (const auto& q : qs) sink += map.nearest_distance(q);
    const double q_kd = (now_s() - t0) / nq;
    int bad = 0;
    t0 = now_s();
    for (int i = 0; i < nq_bf; ++i) {
      const double d = brute_nearest(pts, qs[i]);
      bad += d != map.nearest_distance(qs[i]);
    }
    const double q_bf = (now_s() - t0) / nq_bf;
    const double r = 200.0;
    t0 = now_s();
    size_t found = 0;
    for (int i = 0; i < nq / 10; ++i) found += map.radius(qs[i], r).size();
    const double r_kd = (now_s() - t0) / (nq / 10);
    t0 = now_s();
    for (int i = 0; i < nq_bf; ++i) bad += brute_radius(pts, qs[i], r) != map.radius(qs[i], r).size();
    const double r_bf = (now_s() - t0) / nq_bf;
    std::printf("%9zu | %10.2f %10.2f | %12.3f %12.1f %7.0fx | %12.3f %12.1f %7.0fx | %d of %d (sink %.0f, %zu)\n", n,
                build_kd * 1e3, build_map * 1e3, q_kd * 1e6, q_bf * 1e6, q_bf / q_kd, r_kd * 1e6, r_bf * 1e6,
                r_bf / r_kd, bad, 2 * nq_bf, sink / nq, found);
  }
}

// FCL: every edge becomes a vertical wall (2 triangles, z in [-1, 1]); the query segment too. The
// distance between two such walls is the 2-D segment distance.
void add_wall(std::vector<fcl::Vector3d>& v, std::vector<fcl::Triangle>& t, mpgc::geom::Vec2 a, mpgc::geom::Vec2 b) {
  const auto k = v.size();
  v.emplace_back(a.x, a.y, -1.0);
  v.emplace_back(b.x, b.y, -1.0);
  v.emplace_back(b.x, b.y, 1.0);
  v.emplace_back(a.x, a.y, 1.0);
  t.emplace_back(k, k + 1, k + 2);
  t.emplace_back(k, k + 2, k + 3);
}

std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> wall_model(const std::vector<std::pair<mpgc::geom::Vec2, mpgc::geom::Vec2>>& segs) {
  std::vector<fcl::Vector3d> v;
  std::vector<fcl::Triangle> t;
  for (const auto& s : segs) add_wall(v, t, s.first, s.second);
  auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  m->beginModel();
  m->addSubModel(v, t);
  m->endModel();
  return m;
}

void bench_chart(std::mt19937_64& rng, const std::string& chart) {
  std::printf("\n== segment clearance and land test on the real cell %s ==\n", chart.c_str());
  const mpgc::geo::LocalNed frame({mpgc::geo::deg2rad(38.70), mpgc::geo::deg2rad(-76.31)});
  om::ChartParams cp;
  cp.spacing = 20.0;
  cp.draught = 5.0;
  double t0 = now_s();
  om::ChartBuilder b(frame, cp);
  b.load_file(chart);
  auto set = b.take();
  const double t_load = now_s() - t0;
  size_t nedges = 0;
  for (const auto& g : set.polygons) nedges += g.ring.size();
  std::printf("load (GDAL S-57, updates applied, to NED, densify 20 m): %.0f ms -> %zu points, %zu rings, %zu edges\n",
              t_load * 1e3, set.points.size(), set.polygons.size(), nedges);
  t0 = now_s();
  om::FixedObstacleMap map(set.points, set.polygons);
  std::printf("FixedObstacleMap build (kd-tree + 2 AABB trees): %.0f ms\n", (now_s() - t0) * 1e3);
  // Edges only, for a like-for-like comparison with FCL, in a 30 km square at the cell's centre
  // (FCL's OBBRSS build over the whole cell takes many seconds).
  const auto full = map.bounds();
  const double cx = 0.5 * (full.min_x + full.max_x), cy = 0.5 * (full.min_y + full.max_y);
  const om::BoxNE sub{cx - 15000.0, cy - 15000.0, cx + 15000.0, cy + 15000.0};
  const auto part = om::crop(set, sub);
  t0 = now_s();
  om::FixedObstacleMap edges_only({}, part.polygons);
  const double t_own_build = now_s() - t0;
  std::vector<std::pair<mpgc::geom::Vec2, mpgc::geom::Vec2>> segs;
  for (const auto& g : part.polygons)
    for (size_t i = 0; i < g.ring.size(); ++i) segs.push_back({g.ring[i], g.ring[(i + 1) % g.ring.size()]});
  t0 = now_s();
  auto fcl_chart = wall_model(segs);
  fcl::CollisionObjectd chart_obj(fcl_chart);
  const double t_fcl_build = now_s() - t0;

  std::uniform_real_distribution<double> ux(sub.min_x, sub.max_x), uy(sub.min_y, sub.max_y), ang(-M_PI, M_PI);
  std::uniform_real_distribution<double> len(50.0, 2000.0);
  const int nq = 20000, nq_bf = 200, nq_fcl = 2000;
  std::vector<std::pair<mpgc::geom::Vec2, mpgc::geom::Vec2>> qs(nq);
  for (auto& q : qs) {
    const mpgc::geom::Vec2 a{ux(rng), uy(rng)};
    const double l = len(rng), th = ang(rng);
    q = {a, {a.x + l * std::cos(th), a.y + l * std::sin(th)}};
  }
  auto brute_edges = [&](mpgc::geom::Vec2 a, mpgc::geom::Vec2 c) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& s : segs) best = std::min(best, mpgc::geom::segment_distance(a, c, s.first, s.second));
    return best;
  };
  // Own tree, edges only (the inside test adds 0 for legs starting on land; compare raw distance).
  double sink = 0;
  t0 = now_s();
  for (const auto& q : qs) sink += edges_only.segment_clearance(q.first, q.second);
  const double t_own = (now_s() - t0) / nq;
  int bad_own = 0;
  t0 = now_s();
  for (int i = 0; i < nq_bf; ++i) {
    const double bf = edges_only.inside_land(qs[i].first) ? 0.0 : brute_edges(qs[i].first, qs[i].second);
    bad_own += bf != edges_only.segment_clearance(qs[i].first, qs[i].second);
  }
  const double t_bf = (now_s() - t0) / nq_bf;
  double fcl_max_err = 0.0;
  t0 = now_s();
  for (int i = 0; i < nq_fcl; ++i) {
    auto qm = wall_model({qs[i]});
    fcl::CollisionObjectd qo(qm);
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(&qo, &chart_obj, req, res);
    sink += res.min_distance;
  }
  const double t_fcl = (now_s() - t0) / nq_fcl;
  for (int i = 0; i < nq_bf; ++i) {
    auto qm = wall_model({qs[i]});
    fcl::CollisionObjectd qo(qm);
    fcl::DistanceRequestd req;
    fcl::DistanceResultd res;
    fcl::distance(&qo, &chart_obj, req, res);
    const double exact = brute_edges(qs[i].first, qs[i].second);
    fcl_max_err = std::max(fcl_max_err, std::abs(std::max(0.0, res.min_distance) - exact));
  }
  std::printf("segment clearance, legs 50-2000 m, polygon edges only (%zu rings, %zu edges in a 30 km square):\n",
              part.polygons.size(), segs.size());
  std::printf("  %-34s build %8.1f ms   query %9.2f us   disagreements with brute force %d of %d\n", "own AABB tree (exact)",
              t_own_build * 1e3, t_own * 1e6, bad_own, nq_bf);
  std::printf("  %-34s build %8.1f ms   query %9.2f us   max |error| vs exact %.3g m (%d legs)\n", "FCL 0.7 OBBRSS walls",
              t_fcl_build * 1e3, t_fcl * 1e6, fcl_max_err, nq_bf);
  std::printf("  %-34s                  query %9.1f us\n", "brute force", t_bf * 1e6);
  std::printf("  ratios: brute/own %.0fx, FCL/own %.1fx\n", t_bf / t_own, t_fcl / t_own);

  // Full map (points + edges), as the planner uses it.
  t0 = now_s();
  for (const auto& q : qs) sink += map.segment_clearance(q.first, q.second);
  const double t_full = (now_s() - t0) / nq;
  t0 = now_s();
  int land = 0;
  for (const auto& q : qs) land += map.inside_land(q.first);
  const double t_land = (now_s() - t0) / nq;
  t0 = now_s();
  for (const auto& q : qs) sink += map.nearest_distance(q.first);
  const double t_near = (now_s() - t0) / nq;
  t0 = now_s();
  int clear = 0;
  for (const auto& q : qs) clear += map.segment_clear(q.first, q.second, 200.0);
  const double t_clear = (now_s() - t0) / nq;
  std::printf("full map (%zu points + %zu edges): segment_clearance %.2f us, inside_land %.2f us (%d of %d on land), "
              "nearest_distance %.2f us, segment_clear(d = 200 m) %.2f us (%d of %d clear)  (sink %.3g)\n",
              map.points().size(), nedges, t_full * 1e6, t_land * 1e6, land, nq, t_near * 1e6, t_clear * 1e6, clear, nq, sink);
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t seed = 1;
  const char* data = std::getenv("MPGC_SHARED_DATA");
  std::string chart = std::string(data ? data : "../shared/data") + "/chart/US4MD81M/US4MD81M.000";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seed") && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (!std::strcmp(argv[i], "--chart") && i + 1 < argc) {
      chart = argv[++i];
    } else {
      std::fprintf(stderr, "usage: mpgc_bench_obstacles [--seed N] [--chart FILE.000|.geojson]\n");
      return 2;
    }
  }
  std::printf("mpgc_bench_obstacles seed %llu\n", static_cast<unsigned long long>(seed));
  std::mt19937_64 rng(seed);
  try {
    bench_points(rng);
    bench_chart(rng, chart);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
