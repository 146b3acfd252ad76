// The obstacle manager component's logic without DDS or a clock (mpgc_obstacle_manager's main.cpp
// is wiring around it): its named parameters, the chart files (and when they changed on disk),
// the chart and the region of it published for the own ship, the check of the run's origin, and
// what the component says when the track feed falls silent, empties and comes back.
//
//   om::NodeParams p;  om::declare(ps, p);  ps.validate_and_apply();  p.validate();
//   om::FixedFeed fixed(p, frame, om::chart_files(p.files, shared_dir));
//   if (auto part = fixed.own_at(own)) publish(*part);
//   om::TracksHealth health(p.aging);  for (auto& n : health.update(feed.at(now), feed.has_list())) ...
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/manager.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::obstacle_manager {

struct NodeParams {
  std::string files;         // chart files, comma separated (.000 S-57 cells, .geojson)
  std::string shapes;        // inline NED shapes (see add_shapes)
  double origin_lat = 0;     // [deg] NED origin, must be the run's origin
  double origin_lon = 0;     // [deg]
  double watch_period = 5;   // [s] chart file change check; 0 = never
  double moving_period = 0.5;  // [s] obstacles/moving period
  double origin_tolerance = 100;  // [m] NavState x,y vs lat/lon through our origin
  ChartParams chart;
  RegionParams region;
  DomainParams domain;
  AgingParams aging;

  void validate() const;  // throws std::invalid_argument
  geo::LocalNed frame() const;  // the NED frame of chart.origin_lat/lon
  std::string chart_name() const;  // what obstacles/fixed says it came from
};

// Declares every parameter of the component.
void declare(rt::ParamSet& ps, NodeParams& p);

// The files of chart.files: comma separated, blanks trimmed; a relative path that does not exist
// is taken under `shared_dir` when it exists there ("" = nowhere else).
std::vector<std::string> chart_files(const std::string& list, const std::string& shared_dir);
// Modification times of the chart files and their S-57 updates (.001 ... beside a .000).
std::string chart_stamp(const std::vector<std::string>& files);
// The chart of the files and the inline shapes. Throws ChartError.
ObstacleSet load_chart(const NodeParams& p, const geo::LocalNed& frame, const std::vector<std::string>& files);
// The box around every polygon and point.
BoxNE chart_bounds(const ObstacleSet& s);

// The fixed obstacles as published: the chart (reloaded when its files change) and the region of
// it around the own ship and the goal (the whole chart when region.half_size is 0).
class FixedFeed {
 public:
  FixedFeed(const NodeParams& p, const geo::LocalNed& frame, std::vector<std::string> files);  // loads; throws
  const ObstacleSet& chart() const { return chart_; }
  bool whole_chart() const { return region_.whole_chart(); }

  struct Part {
    uint32_t version = 0;  // 1, 2, ... one per publication
    BoxNE box;             // the region
    ObstacleSet obstacles;  // what of the chart lies in it
  };
  // The part to publish around `centre` now.
  Part publish(geom::Vec2 centre);
  // The own ship is at `own`: the part to publish when it left the republish circle (or first).
  std::optional<Part> own_at(geom::Vec2 own);
  // The mission goal is `goal` (nullopt: none): the part to publish when that changed the region.
  std::optional<Part> goal_at(std::optional<geom::Vec2> goal);
  // The whole chart needs no own position: published at once for planners that start first.
  std::optional<Part> at_start();
  // Files changed on disk: reloads them and returns what to publish (around the last own position,
  // or the whole chart; nullopt: nothing yet). Unchanged: nullopt, `changed` false. A reload that
  // fails throws and keeps the previous chart (the change is not tried again until the next one).
  std::optional<Part> reload_if_changed(bool* changed);

 private:
  void set_chart(ObstacleSet s);
  NodeParams p_;
  geo::LocalNed frame_;
  std::vector<std::string> files_;
  std::string stamp_;
  ObstacleSet chart_;
  RegionPolicy region_;
  std::optional<geom::Vec2> own_;
  uint32_t version_ = 0;
};

// NavState's x,y against its lat/lon through chart.origin: the offset [m] the first time it exceeds
// nav.origin_tolerance (the origin is then likely not the run's), once.
class OriginCheck {
 public:
  OriginCheck(const geo::LocalNed& frame, double tolerance) : frame_(frame), tolerance_(tolerance) {}
  std::optional<double> check(double x, double y, double lat, double lon);

 private:
  geo::LocalNed frame_;
  double tolerance_;
  bool warned_ = false;
};

// What the component says of the track feed each cycle: tracks aged out, the feed falling silent
// (once per change), the list emptied by age, the tracks coming back.
class TracksHealth {
 public:
  explicit TracksHealth(const AgingParams& a) : a_(a) {}
  struct Note {
    bool warn = false;        // else info
    std::string log;          // "" = no log line
    std::string counter;      // "" = none
    std::size_t count = 1;
    std::optional<std::string> problem;  // the "tracks" health problem ("" clears it)
  };
  std::vector<Note> update(const MovingObstacleFeed::Output& out, bool has_list);

 private:
  AgingParams a_;
  MovingObstacleFeed::Feed last_ = MovingObstacleFeed::Feed::kWaiting;
  bool emptied_ = false;  // silent and every track aged out
};

}  // namespace mpgc::obstacle_manager
