// COLREG-compliant RRT* optimal path planner of Zaccone 2021 (seed 000 §3-§6).
//
//   mpgc::opp::Problem pb;  pb.start = {0, 0}; pb.heading = 0.8; pb.speed = 6; pb.goal.p = {1e4, 1e4};
//   pb.fixed = &obstacles;  pb.targets = {...};  pb.bounds = {...};
//   mpgc::opp::Params prm;  prm.seed = 7;  prm.validate();
//   mpgc::opp::Hooks hooks; hooks.elapsed = [&] { return stopwatch(); };   // the caller's clock
//   mpgc::opp::Result r = mpgc::opp::plan(pb, prm, hooks);
//
// No DDS, no clock, no global state: time enters only through Hooks::elapsed, randomness only
// through Params::seed (same inputs, same seed -> the same path, bit for bit).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
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
};

struct Goal {
  Vec2 p;                                                   // [m] arrival point
  double heading = std::numeric_limits<double>::quiet_NaN();  // [rad] desired arrival heading; NaN = any
  double heading_tolerance = 3.141592653589793;            // [rad] accepted |last leg course - heading|
};

struct Bounds {
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;  // [m] sampling region (NED)
};

struct Problem {
  Vec2 start;                          // [m] own position at t = 0
  double heading = 0.0;                // [rad] own heading, clockwise from north
  double speed = 0.0;                  // [m/s] own planned speed (> 0): times along the path, eq. 3
  Goal goal;
  Bounds bounds;                       // must contain start and goal
  const FixedObstacles* fixed = nullptr;  // nullptr = open water
  std::vector<Target> targets;
  bool colreg = true;                  // require §5 compliance first (relax only if none, §6)
};

// How much of COLREG an edge must meet: every rule (§5 per leg, pinned obligations), the pinned
// obligations alone (the first relaxation), or none (§6).
enum class ColregLevel { kNone, kPinned, kFull };

struct Params {
  // Constraints (§4.1, §4.2, §5).
  double safety_distance = 1000.0;     // [m] d_safety, eq. 4
  double colreg_distance = 3000.0;     // [m] d_COLREG (> d_safety): COLREG checked inside it, §5
  double max_turn = 1.0471975511965976;  // [rad] limit of |theta_p|, eq. 2 (>= pi disables it)
  bool turn_limit_at_start = true;     // also limit the first waypoint's turn from the own heading
  bool escape_start = false;           // start within d_safety of an obstacle or target: plan anyway,
                                       // legs from the start may not get closer than they start
                                       // (false: Status::kInvalidInput)
  ColregParams colreg;                 // theta_o, theta_h (22.5 deg), eq. 13 tolerance
  // Cost weights of eq. 5.
  double gamma_s = 0.0;                // [1/rad^2] steering, eq. 6
  double gamma_f = 0.0;                // [m] margin from fixed obstacles, eq. 7 (sum of 1/d)
  double gamma_m = 0.0;                // [m] margin from targets, eq. 8
  double gamma_l = 1.0;                // [1/m] path length, eq. 9
  double min_margin = 1.0;             // [m] floor of d in the 1/d terms of eq. 7-8
  // RRT* (§3).
  double step = 500.0;                 // [m] steer step ("range")
  double goal_bias = 0.05;             // [-] probability of sampling the goal
  double rewire_factor = 1.1;          // [-] scales k_rrt (or r_rrt) as in OMPL
  bool k_nearest = true;               // k-nearest (true) or radius neighbourhood
  bool connect_goal = true;            // try an edge to the goal from every new node within step
  int restart_after = 0;               // [-] iterations without improvement after which a fresh tree
                                       //     is grown (best kept); 0 = one tree (plain RRT*)
  // Budgets.
  int max_iterations = 20000;          // [-] per plan (both passes together), <= 2e6
  double time_budget = 0.5;            // [s] per plan, measured with Hooks::elapsed (if given)
  double compliant_share = 0.5;        // [-] budget share after which a compliant pass still
                                       //     without any solution gives way to the relaxed pass
                                       //     (first to the pinned obligations alone, when a
                                       //     target has one, for half the rest; then none)
  uint64_t seed = 1;                   // [-] std::mt19937_64 seed
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

struct Waypoint {
  Vec2 p;          // [m]
  double t = 0.0;  // [s] planned arrival time from t = 0 at constant speed
};

enum class Status {
  kOk,            // path found; COLREG-compliant when Problem::colreg
  kRelaxed,       // no compliant path within the budget; COLREG relaxed (§6)
  kNoPath,        // no path at all within the budget; see reason
  kInvalidInput,  // the problem was rejected; see reason
};
const char* to_string(Status s);

struct CostTerms {  // weighted terms of eq. 5 (total = smooth + fixed + moving + length)
  double total = 0, smooth = 0, fixed = 0, moving = 0, length = 0;
};

struct Stats {
  int iterations = 0;            // [-] both passes
  int iterations_compliant = 0;  // [-] of the compliant pass
  int nodes = 0;                 // [-] tree size of the pass that produced the path
  int first_solution_iteration = -1;
  double first_solution_time = -1.0;  // [s] by Hooks::elapsed (-1 if none or no clock)
  double planning_time = 0.0;    // [s] by Hooks::elapsed
  uint64_t edge_checks = 0;      // [-] full edge validity checks
  int rewires = 0;               // [-]
  int restarts = 0;              // [-] fresh trees grown (Params::restart_after)
  bool warm_started = false;
};

struct Result {
  Status status = Status::kNoPath;
  std::string reason;
  bool colreg_compliant = false;  // §5 held on every edge
  bool relaxed = false;
  std::vector<Waypoint> path;     // start first, goal last
  CostTerms cost;
  Stats stats;
};

struct Hooks {
  // Seconds since an arbitrary origin, monotonic; empty: iteration budget only (deterministic).
  std::function<double()> elapsed;
  // Called after every iteration with the iteration count and the best cost so far (inf if none).
  std::function<void(int iteration, double best_cost)> progress;
  // Extra stop condition (e.g. shutdown), checked every iteration.
  std::function<bool()> stop;
};

// Plans one path: compliant pass first (if Problem::colreg), relaxed pass when the compliant one
// found nothing within its share of the budget. `warm` (may be empty) is a previous path re-used
// as an initial solution candidate if it is still valid from the new start.
Result plan(const Problem& problem, const Params& params, const Hooks& hooks = {},
            const std::vector<Vec2>& warm = {});

// Exact validity of a whole path (used by tests and by the warm start): turning limit (eq. 2),
// safety distance to fixed obstacles and to every target at its eq. 3 position (eq. 4), and, if
// `colreg`, §5 compliance on every leg. Returns an empty string or the first violation.
std::string check_path(const Problem& problem, const Params& params, const std::vector<Vec2>& path, bool colreg);

// Cost terms of eq. 5-9 for a path at constant speed.
CostTerms path_cost(const Problem& problem, const Params& params, const std::vector<Vec2>& path);

}  // namespace mpgc::opp
