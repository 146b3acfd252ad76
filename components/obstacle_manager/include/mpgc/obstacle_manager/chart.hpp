// Chart input: GeoJSON and S-57 ENC cells (through GDAL/OGR) plus inline scenario shapes, turned
// into the fixed-obstacle set of seed 000 §4.2 in local NED: polygons for exact land tests and the
// boundaries densified into points for the kd-tree.
//
//   ChartParams p;  p.spacing = 20; p.draught = 6;
//   ChartBuilder b(mpgc::geo::LocalNed({lat0, lon0}), p);
//   b.load_file(".../US4MD81M.000");          // LNDARE, COALNE, OBSTRN, WRECKS, shallow DEPARE
//   b.add_circle({1000, 500}, 200, "Cir01");  // seed 003 Table 3
//   ObstacleSet set = b.take();
//   FixedObstacleMap map(set.points, set.polygons);
//
// Every malformed input (unreadable or truncated file, unclosed ring, self-intersection, empty
// geometry, latitude/longitude out of range) throws ChartError naming the file, layer and feature.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace mpgc::obstacle_manager {

class ChartError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ChartParams {
  double spacing = 20.0;   // [m] distance between densified boundary points, > 0
  double draught = 5.0;    // [m] depth areas with DRVAL1 below this are obstacles (S-57 DEPARE, or
                           //     any GeoJSON feature carrying a DRVAL1 property)
  bool depth_areas = true; // [-] treat shallow depth areas as obstacles at all
  size_t max_points = 20'000'000;  // [-] refuse charts that would densify to more points
  // Throws std::invalid_argument naming the bad field.
  void validate() const;
};

// Fixed obstacles in NED. Polygon feature ids index `features`.
struct ObstacleSet {
  std::vector<geom::Vec2> points;       // [m] densified boundaries and point features
  std::vector<Polygon> polygons;     // [m] areas (holes share the feature id, even-odd)
  std::vector<std::string> features; // feature_id -> "source:layer:fid" for messages
  std::map<std::string, size_t> layer_counts;  // features taken per layer, e.g. "LNDARE" -> 183
  std::map<std::string, size_t> skipped;       // features left out per reason, e.g. "DEPARE deep"
};

// Points every `spacing` metres along the closed ring (vertices included, closing edge included).
std::vector<geom::Vec2> densify_ring(const std::vector<geom::Vec2>& ring, double spacing);
// Points every `spacing` metres along the open polyline (both ends included).
std::vector<geom::Vec2> densify_line(const std::vector<geom::Vec2>& line, double spacing);

// The fixed obstacles of `set` a planner needs inside `region`: the points inside it and every
// polygon whose bounding box meets it (kept whole so inside tests stay exact near the border).
ObstacleSet crop(const ObstacleSet& set, const BoxNE& region);

class ChartBuilder {
 public:
  ChartBuilder(geo::LocalNed frame, ChartParams params);

  // Loads a chart by file name: *.000 (S-57 ENC cell; updates .001, .002, ... beside it are
  // applied) or *.geojson / *.json (WGS84 lon/lat: Polygon, MultiPolygon, LineString,
  // MultiLineString, Point, MultiPoint). Returns the number of features taken.
  size_t load_file(const std::string& path);

  // Inline scenario shapes, already in NED [m]. `name` names the shape in errors.
  // A ring must be simple (no self-intersection); first point not repeated.
  void add_polygon(const std::vector<geom::Vec2>& ring, const std::string& name);
  // A circle as a circumscribed polygon (every point of the circle is inside it).
  void add_circle(geom::Vec2 centre, double radius, const std::string& name);
  // An open line (canal wall, breakwater): a zero-area there-and-back ring, so it has edges for
  // clearance but never an inside.
  void add_line(const std::vector<geom::Vec2>& line, const std::string& name);
  void add_point(geom::Vec2 p, const std::string& name);

  const ObstacleSet& result() const { return set_; }
  ObstacleSet take() { return std::move(set_); }
  const geo::LocalNed& frame() const { return frame_; }

 private:
  uint32_t new_feature(const std::string& name);
  void add_ring(std::vector<geom::Vec2> ring, uint32_t id);
  void check_size(const std::string& name) const;
  geo::LocalNed frame_;
  ChartParams p_;
  ObstacleSet set_;
  friend struct OgrReader;
};

}  // namespace mpgc::obstacle_manager
