// A planning problem as every planner behind the interface sees it (OMPL's ProblemDefinition and
// the constraint part of its SpaceInformation): the own ship and its goal, the moving targets with
// their pinned COLREG obligations, the fixed obstacles, the sampling bounds, and the named
// parameters of the constraints (seed 000 §4-§5) and of the objective (eq. 5-9).
//
//   opp::Problem pb;  pb.start = {0, 0}; pb.heading = 0.8; pb.speed = 6; pb.goal.p = {1e4, 1e4};
//   pb.bounds = {-3000, -3000, 13000, 13000};  pb.fixed = &obstacles;  pb.targets = {...};
//   std::string why = opp::check_problem(pb, constraints);   // "" = plannable
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/opp/colreg.hpp"
#include "mpgc/opp/geometry.hpp"
#include "mpgc/opp/obstacles.hpp"

namespace mpgc::opp {

// A moving obstacle at the plan's time origin t = 0, extrapolated linearly (eq. 3).
struct Target {
  uint32_t id = 0;  // [-] track id (reporting only)
  Vec2 p;           // [m] position at t = 0
  Vec2 v;           // [m/s] velocity
  PinnedEncounter pinned;  // COLREG obligation fixed for the encounter (EncounterMemory); kNone:
                           // the per-leg model of §5
  double margin = 0.0;     // [m] kept beyond d_safety from this target (eq. 4): its position
                           // uncertainty, which grows while nobody measures it (issue 15)
};

struct Goal {
  Vec2 p;                                                     // [m] arrival point
  double heading = std::numeric_limits<double>::quiet_NaN();  // [rad] desired arrival heading; NaN = any
  double heading_tolerance = 3.141592653589793;               // [rad] accepted |last leg course - heading|
};

struct Bounds {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;  // [m] sampling region (NED)
  bool contains(Vec2 p) const { return p.x >= min_x && p.x <= max_x && p.y >= min_y && p.y <= max_y; }
  // p lies at least d inside (every side; a box is convex, so a segment whose ends do lies inside too).
  bool contains_by(Vec2 p, double d) const {
    return p.x - min_x >= d && max_x - p.x >= d && p.y - min_y >= d && max_y - p.y >= d;
  }
  Bounds intersect(const Bounds& o) const {
    return {std::max(min_x, o.min_x), std::max(min_y, o.min_y), std::min(max_x, o.max_x), std::min(max_y, o.max_y)};
  }
};

struct Problem {
  Vec2 start;                          // [m] own position at t = 0
  double heading = 0.0;                // [rad] own heading, clockwise from north
  double speed = 0.0;                  // [m/s] own planned speed (> 0): times along the path, eq. 3
  Goal goal;
  Bounds bounds;                       // must contain start and goal
  const FixedObstacles* fixed = nullptr;  // nullptr = open water
  // The region the chart was published for (obstacles/fixed): beyond it the water is unknown, so a
  // leg keeps its fixed clearance from the region's edge as from land (issue 15). nullopt: the
  // obstacles are complete everywhere (tests, benchmark worlds, a chart published whole).
  std::optional<Bounds> charted;
  std::vector<Target> targets;
  bool colreg = true;                  // require §5 compliance first (relax only if none, §6)
};

// How much of COLREG an edge must meet: every rule (§5 per leg, pinned obligations); the pinned
// duties and rule 17(c) (the first relaxation: a stand-on ship may act, 17(b), but not to port for
// a crossing ship on its port side, which the rules ask "if the circumstances of the case admit");
// the pinned duties alone; or none (§6).
enum class ColregLevel { kNone, kPinned, kPinned17c, kFull };

// The constraints of §4.1, §4.2 and §5: what the validity checker enforces.
struct ConstraintParams {
  double safety_distance = 1000.0;     // [m] d_safety, eq. 4
  double colreg_distance = 3000.0;     // [m] d_COLREG (> d_safety): COLREG checked inside it, §5
  double max_turn = 1.0471975511965976;  // [rad] limit of |theta_p|, eq. 2 (>= pi disables it)
  bool turn_limit_at_start = true;     // also limit the first waypoint's turn from the own heading
  bool escape_start = false;           // start within d_safety of an obstacle or target: plan anyway,
                                       // legs from the start may not get closer than they start
                                       // (false: Status::kInvalidInput)
  ColregParams colreg;                 // theta_o, theta_h of eq. 16 and §5.5 (22.5 deg), eq. 13 tolerance
  double colreg_spacing = 500.0;       // [m] §5 is checked at a leg's start and every this far along
                                       // it, as the chain of waypoints a long leg stands for (the
                                       // RRT* sets its step: a long edge must not jump over the zone)
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

// The weights of the objective, eq. 5.
struct ObjectiveParams {
  double gamma_s = 0.0;                // [1/rad^2] steering, eq. 6
  double gamma_f = 0.0;                // [m] margin from fixed obstacles, eq. 7 (sum of 1/d)
  double gamma_m = 0.0;                // [m] margin from targets, eq. 8
  double gamma_l = 1.0;                // [1/m] path length, eq. 9
  double min_margin = 1.0;             // [m] floor of d in the 1/d terms of eq. 7-8
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

// [m] widest sampling box planned in: start and goal within 1000 km of the frame's origin, plus margins.
inline constexpr double kMaxBoundsSide = 2.5e6;

// Why the problem cannot be planned (non-finite or out-of-bounds start or goal, a start or goal
// inside d_safety, a goal not d_safety inside the charted region, too many targets), or "" when it can.
std::string check_problem(const Problem& pb, const ConstraintParams& c);

// Why the charted region does not hold the problem (own ship outside it, goal not `d` inside it),
// or "" (also with no region).
std::string beyond_chart(const Problem& pb, double d);

// Number formatting of the reasons (6 significant digits).
std::string fmt(double v);

}  // namespace mpgc::opp
