// The planning interface, in the manner of OMPL's Planner: a planner has a name and declares its
// own parameters (units, ranges); it solves a Request (the problem, its constraints, objective and
// budget) within the budget and returns the same Result whatever the algorithm: a status with its
// reason, the path, the cost terms of eq. 5 and statistics. Planners are made by name through the
// registry (registry.hpp, parameter plan.planner); the RRT* of seed 000 is one (rrtstar.hpp).
//
//   std::unique_ptr<opp::Planner> p = opp::make_planner("rrtstar");
//   p->declare(params);  params.validate_and_apply();      // plan.step, plan.goal_bias, ...
//   opp::Result r = p->solve({problem, constraints, objective, budget}, hooks);
//
// No DDS, no clock, no global state: time enters only through Hooks::elapsed, randomness only
// through Budget::seed (same request, same seed -> the same path, bit for bit).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "mpgc/opp/objective.hpp"
#include "mpgc/opp/problem.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::opp {

// What one plan may spend.
struct Budget {
  int max_iterations = 20000;          // [-] per plan (every pass together), <= 2e6
  double time_budget = 0.5;            // [s] per plan, measured with Hooks::elapsed (if given)
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

struct Stats {
  int iterations = 0;            // [-] every pass
  int iterations_compliant = 0;  // [-] of the compliant pass
  int nodes = 0;                 // [-] search size (tree nodes) of the pass that produced the path
  int first_solution_iteration = -1;
  double first_solution_time = -1.0;  // [s] by Hooks::elapsed (-1 if none or no clock)
  double planning_time = 0.0;    // [s] by Hooks::elapsed
  uint64_t edge_checks = 0;      // [-] full edge validity checks
  int rewires = 0;               // [-]
  int restarts = 0;              // [-] fresh trees grown (RrtStarParams::restart_after)
  bool warm_started = false;
};

struct Result {
  Status status = Status::kNoPath;
  std::string reason;
  bool colreg_compliant = false;  // §5 held on every edge
  bool relaxed = false;
  std::vector<Waypoint> path;     // start first, goal last
  bool kept = false;              // the previous path (Request::warm), still valid, returned as it is
  bool margin_reduced = false;    // the planner's own margin beyond d_safety given up (dijkstra-sv's safe CPA, §3 Step 5)
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

// One planning request. `warm` (may be empty) is a previous path a planner may re-use as an
// initial solution if it is still valid from the new start.
struct Request {
  const Problem& problem;
  ConstraintParams constraints;
  ObjectiveParams objective;
  Budget budget;
  std::vector<Vec2> warm;
};

class Planner {
 public:
  virtual ~Planner() = default;
  // The name plan.planner selects it by ("rrtstar").
  virtual std::string name() const = 0;
  // Binds the planner's own parameters (name, unit, range, description) into `ps`; their values
  // are the planner's after ps.validate_and_apply(). Shared parameters (constraints, objective,
  // budget) are the caller's.
  virtual void declare(rt::ParamSet& ps) = 0;
  // Plans one path. Never throws on bad input: it comes back as Status::kInvalidInput with the
  // reason. Safe to call concurrently on one planner (the speed tries of plan_node run at once):
  // a solve keeps its search state to itself and only reads the declared parameters.
  virtual Result solve(const Request& rq, const Hooks& hooks = {}) = 0;
  // True for a planner that returns the previous path (Result::kept) while it stays valid, rather
  // than a new search at every re-plan: plan_node then asks it at that path's own speed too.
  virtual bool keeps_plan() const { return false; }
};

// The Result of a found path: status (relaxed or not), compliance by `check`, the cost terms by
// `objective` and the waypoint times at the problem's speed. Shared by every planner.
Result finish(const Problem& pb, const std::vector<Vec2>& pts, bool relaxed, const class ValidityChecker& check,
              const Objective& objective);

// The waypoints of a previous path (`Request::warm`) still ahead of `start`: those after the leg
// nearest to it.
std::vector<Vec2> warm_tail(const std::vector<Vec2>& warm, Vec2 start);

}  // namespace mpgc::opp
