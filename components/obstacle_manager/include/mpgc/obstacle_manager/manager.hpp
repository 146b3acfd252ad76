// The obstacle manager's decisions, free of DDS and clock (seed 000 §2, §4.2): which region of the
// chart to publish and when, how tracked targets become moving obstacles, and the inline shapes
// a scenario adds to the chart.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace mpgc::obstacle_manager {

// Adds inline shapes written as text, in NED metres, separated by ';':
//   "circle N E R; polygon N1 E1 N2 E2 N3 E3 ...; line N1 E1 N2 E2 ...; point N E"
// (seed 003 Table 3 circles, seed 000 scenario 3 canal walls). Throws ChartError naming the
// shape (by its position, e.g. "shape 2 (polygon)") on any malformed entry.
void add_shapes(ChartBuilder& b, const std::string& spec);

// When to publish which part of the fixed obstacles: a square of half side `half_size` around the
// own ship, re-centred when the ship is farther than `republish_distance` from the last centre.
struct RegionParams {
  double half_size = 10000.0;           // [m] half side of the published square; 0 = whole chart
  double republish_distance = 2000.0;   // [m] re-centre after moving this far; < half_size
  void validate() const;
};

class RegionPolicy {
 public:
  explicit RegionPolicy(RegionParams p);
  // True when nothing was published yet, the ship left the republish circle, or the chart changed.
  bool needs_update(PointNE own) const;
  void chart_changed() { dirty_ = true; }
  // The region to publish for the ship at `own`, and remember it as published.
  BoxNE publish(PointNE own, const BoxNE& chart_bounds);
  bool whole_chart() const { return p_.half_size == 0.0; }

 private:
  RegionParams p_;
  std::optional<PointNE> centre_;
  bool dirty_ = true;
};

// Moving obstacles from tracks (seed 000 eq. 3: the planner extrapolates y_i(t) = y_i + w_i t).
struct DomainParams {
  double min_radius = 50.0;     // [m] circular ship-domain radius when the length is unknown
  double lengths = 2.0;         // [-] radius = max(min_radius, lengths * length overall)
  double max_speed = 40.0;      // [m/s] faster tracks are rejected as implausible
  double max_range = 1.0e6;     // [m] tracks farther than this from the origin are rejected
  bool tentative = false;       // [-] also pass on tentative tracks
  void validate() const;
};

struct TargetState {
  uint32_t id = 0;
  uint32_t mmsi = 0;
  double x = 0, y = 0;     // [m] NED at the time of validity
  double vx = 0, vy = 0;   // [m/s]
  double var_x = 0, var_y = 0;  // [m^2] position variances (covariance diagonal)
  double length = std::numeric_limits<double>::quiet_NaN();  // [m] NaN when unknown
  bool tentative = false;
  bool deleted = false;
};

struct MovingObstacleOut {
  uint32_t id = 0, mmsi = 0;
  double x = 0, y = 0, vx = 0, vy = 0;  // [m], [m/s]
  double radius = 0;                     // [m] circular ship domain
  double position_std = 0;               // [m] one sigma, the larger axis
};

// Empty when the target can be used; otherwise why not ("not finite", "speed 95 m/s > 40", ...).
// Deleted and (unless enabled) tentative tracks give "deleted" / "tentative": not errors, skipped.
std::string check_target(const TargetState& t, const DomainParams& p);
MovingObstacleOut to_moving_obstacle(const TargetState& t, const DomainParams& p);

}  // namespace mpgc::obstacle_manager
