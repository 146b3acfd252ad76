// The obstacle manager's decisions, free of DDS and clock (seed 000 §2, §4.2): which region of the
// chart to publish and when, how tracked targets become moving obstacles, and the inline shapes
// a scenario adds to the chart.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace mpgc::obstacle_manager {

// Adds inline shapes written as text, in NED metres, separated by ';':
//   "circle N E R; polygon N1 E1 N2 E2 N3 E3 ...; line N1 E1 N2 E2 ...; point N E"
// (seed 003 Table 3 circles, seed 000 scenario 3 canal walls). Throws ChartError naming the
// shape (by its position, e.g. "shape 2 (polygon)") on any malformed entry.
void add_shapes(ChartBuilder& b, const std::string& spec);

// When to publish which part of the fixed obstacles: the box around the own ship and the mission
// goal, `half_size` beyond each, re-published when the ship is farther than `republish_distance`
// from where it was or the goal changed. The planner counts water beyond the box as unknown (it
// holds every obstacle inside it and nothing beyond), so the box covers the goal: a plan never
// needs to leave it. half_size 0: the whole chart, taken as complete (an infinite region).
struct RegionParams {
  double half_size = 10000.0;           // [m] margin of the published box; 0 = whole chart
  double republish_distance = 2000.0;   // [m] re-centre after moving this far; < half_size
  void validate() const;
};

class RegionPolicy {
 public:
  explicit RegionPolicy(RegionParams p);
  // True when nothing was published yet, the ship left the republish circle, the goal or the
  // chart changed.
  bool needs_update(geom::Vec2 own) const;
  void chart_changed() { dirty_ = true; }
  // The mission goal (nullopt: none); a change makes the region due again.
  void set_goal(std::optional<geom::Vec2> goal);
  // The region to publish for the ship at `own`, and remember it as published.
  BoxNE publish(geom::Vec2 own);
  bool whole_chart() const { return p_.half_size == 0.0; }

 private:
  RegionParams p_;
  std::optional<geom::Vec2> centre_, goal_;
  bool dirty_ = true;
};

// Moving obstacles from tracks (seed 000 eq. 3: the planner extrapolates y_i(t) = y_i + w_i t).
struct DomainParams {
  double min_radius = 50.0;     // [m] circular ship-domain radius when the length is unknown
  double lengths = 2.0;         // [-] radius = max(min_radius, lengths * length overall)
  double max_speed = 40.0;      // [m/s] faster tracks are rejected as implausible
  double max_range = 1.0e6;     // [m] tracks farther than this from the origin are rejected
  // A ship making no way has a track whose velocity is noise (Annapolis: 0.03-0.08 m/s at rest);
  // eq. 3 carries that noise over a plan's horizon (1000 s: 30-80 m, any direction). A track
  // slower than stopped_speed whose speed is within stopped_sigmas x its velocity sigma
  // (sqrt(var_vx + var_vy): 2 covers 98 % of a stopped ship's speeds) is published stopped.
  double stopped_speed = 0.5;   // [m/s] about 1 kn; 0 turns the test off
  double stopped_sigmas = 2.0;  // [-]
  bool tentative = false;       // [-] also pass on tentative tracks
  void validate() const;
};

struct TargetState {
  uint32_t id = 0;
  uint32_t mmsi = 0;
  double x = 0, y = 0;     // [m] NED at the time of validity
  double vx = 0, vy = 0;   // [m/s]
  double var_x = 0, var_y = 0;  // [m^2] position variances (covariance diagonal)
  double var_vx = 0, var_vy = 0;  // [m^2/s^2] velocity variances (covariance diagonal)
  double length = std::numeric_limits<double>::quiet_NaN();  // [m] NaN when unknown
  double since_update = 0;  // [s] since the last measurement, at the time of validity
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

// How long the last track list is used and how its uncertainty grows while nobody measures it
// (issue 15). situational_awareness decides a track's life: it predicts the Kalman covariance to
// the list's stamp (so position_std already grows with since_update there) and deletes a track
// only after tracker.delete_after of silence while its sensors report (a coasting track in a
// sensor outage is listed, its position_std growing). These cover the time after the stamp, which
// only the obstacle manager sees: situational_awareness silent, no new list.
struct AgingParams {
  double max_age = 60.0;       // [s] the last list's obstacles are dropped when it is older
  double timeout = 5.0;        // [s] no track list for this long: the feed is silent
  double speed_std = 1.0;      // [m/s] velocity uncertainty of an unobserved target
  double radius_sigmas = 2.0;  // [-] the domain radius grows by this many times the sigma growth
  void validate() const;
};

// The obstacle `dt` seconds after its time of validity: sigma^2 = sigma0^2 + (speed_std dt)^2 and
// radius = radius0 + radius_sigmas (sigma - sigma0). dt <= 0 returns `o` unchanged, so a list
// published at its own stamp carries exactly to_moving_obstacle's values.
MovingObstacleOut grow_uncertainty(MovingObstacleOut o, double dt, const AgingParams& a);

// The latest track list, held between lists and aged: the obstacle manager's whole moving-obstacle
// logic, fed with times from the caller (no clock here).
//
//   MovingObstacleFeed feed(domain, aging);
//   auto r = feed.receive(list_stamp_ns, targets, now_ns);   // r.rejected: why each target was refused
//   auto out = feed.at(now_ns);                               // every publication cycle
//   if (out.feed == MovingObstacleFeed::Feed::kSilent) ...    // say so on health
class MovingObstacleFeed {
 public:
  MovingObstacleFeed(DomainParams d, AgingParams a);

  struct Received {
    std::vector<std::string> rejected;  // one reason per refused target
    uint32_t deleted = 0, tentative = 0;  // skipped, not errors
  };
  // A track list predicted to `stamp_ns` arrived at `now_ns`; it replaces the previous one.
  Received receive(int64_t stamp_ns, const std::vector<TargetState>& targets, int64_t now_ns);

  enum class Feed { kWaiting, kFresh, kSilent };  // no list yet (within timeout) / fresh / silent
  struct Output {
    int64_t t_valid_ns = 0;  // [ns] the list's stamp (positions hold then); `now` when there is none
    std::vector<MovingObstacleOut> obstacles;  // uncertainty grown to `now`
    std::vector<uint32_t> aged_out;  // track ids dropped for age, each reported once
    Feed feed = Feed::kWaiting;
    double silence = 0;  // [s] since the last list arrived (since the first call when none has)
  };
  // What to publish at `now_ns` (the caller's clock, the same as receive's).
  Output at(int64_t now_ns);
  bool has_list() const { return list_stamp_ns_.has_value(); }

 private:
  DomainParams d_;
  AgingParams a_;
  std::vector<MovingObstacleOut> held_;
  std::optional<int64_t> list_stamp_ns_, arrival_ns_, first_call_ns_;
  std::set<uint32_t> reported_;  // ids already reported as aged out
};

}  // namespace mpgc::obstacle_manager
