#include "mpgc/scenario_runner/scenario_obstacles.hpp"

#include <cmath>
#include <sstream>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/obstacle_manager/node.hpp"

namespace mpgc::scenario_runner {

namespace om = obstacle_manager;

namespace {

// "circle N E R" with three finite numbers and R > 0; anything else is left to add_shapes, which
// names what is wrong.
std::optional<Circle> exact_circle(const std::string& item) {
  std::istringstream in(item);
  std::string kind;
  double n = 0, e = 0, r = 0;
  std::string extra;
  if (!(in >> kind) || kind != "circle" || !(in >> n >> e >> r) || (in >> extra)) return std::nullopt;
  if (!std::isfinite(n) || !std::isfinite(e) || !std::isfinite(r) || !(r > 0.0)) return std::nullopt;
  return Circle{{n, e}, r};
}

}  // namespace

FixedObstacles scenario_obstacles(const Scenario& s, const std::string& shared_dir) {
  om::ChartParams cp;
  if (const auto it = s.params.find("obstacle_manager"); it != s.params.end()) {
    // The chart's own reading of depth: the evaluation takes the same draught as the run.
    if (const auto d = it->second.find("chart.draught"); d != it->second.end()) cp.draught = std::stod(d->second);
    if (const auto d = it->second.find("chart.depth_areas"); d != it->second.end())
      cp.depth_areas = d->second == "true" || d->second == "1";
  }
  om::ChartBuilder b(geo::LocalNed({geo::deg2rad(s.origin_lat_deg), geo::deg2rad(s.origin_lon_deg)}), cp);
  std::string files;
  for (const auto& f : s.chart_files) files += (files.empty() ? "" : ",") + f;
  for (const auto& f : om::chart_files(files, shared_dir)) b.load_file(f);
  FixedObstacles out;
  std::string rest;
  std::istringstream all(s.chart_shapes);
  for (std::string item; std::getline(all, item, ';');) {
    if (auto c = exact_circle(item)) out.circles.push_back(*c);
    else rest += item + ";";
  }
  om::add_shapes(b, rest);
  const om::ObstacleSet set = b.take();
  for (const auto& p : set.polygons) out.polygons.push_back({p.ring});
  add_point_obstacles(out, set.points, 0.5);  // point features; the polygons' boundary points are dropped
  return out;
}

}  // namespace mpgc::scenario_runner
