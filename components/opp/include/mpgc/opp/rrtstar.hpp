// COLREG-compliant RRT* optimal path planner of Zaccone 2021 (seed 000 §3-§6), one planner behind
// the planning interface (planner.hpp) under the name "rrtstar".
//
//   mpgc::opp::Params prm;  prm.seed = 7;  prm.validate();   // constraints + objective + budget + RRT*
//   mpgc::opp::Hooks hooks; hooks.elapsed = [&] { return stopwatch(); };   // the caller's clock
//   mpgc::opp::Result r = mpgc::opp::plan(pb, prm, hooks);
#pragma once

#include <string>
#include <vector>

#include "mpgc/opp/planner.hpp"
#include "mpgc/opp/validity.hpp"

namespace mpgc::opp {

// The RRT*'s own parameters (§3, §6).
struct RrtStarParams {
  double step = 500.0;                 // [m] steer step ("range"); also the spacing of the §5 checks
  double goal_bias = 0.05;             // [-] probability of sampling the goal
  double rewire_factor = 1.1;          // [-] scales k_rrt (or r_rrt) as in OMPL
  bool k_nearest = true;               // k-nearest (true) or radius neighbourhood
  bool connect_goal = true;            // try an edge to the goal from every new node within step
                                       // (false: only goal samples connect, as OMPL's RRTstar)
  int restart_after = 0;               // [-] iterations without improvement after which a fresh tree
                                       //     is grown (best kept); 0 = one tree (plain RRT*)
  bool informed = false;               // once a path of cost c exists, sample only where a
                                       // cheaper one can pass: the ellipse with foci start and
                                       // goal and length c / gamma_l (Gammell 2014; every other
                                       // cost term is >= 0, so the set is exact, never too small)
  double compliant_share = 0.5;        // [-] budget share after which a compliant pass still
                                       //     without any solution gives way to the relaxed pass
                                       //     (first to the pinned obligations alone, when a
                                       //     target has one, for half the rest; then none)
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

// Everything one RRT* plan takes, in one place for tests and benchmarks.
struct Params : ConstraintParams, ObjectiveParams, Budget, RrtStarParams {
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
  // The constraints as the RRT* checks them (§5 every step along a leg).
  ConstraintParams constraints() const;
};

// Plans one path: compliant pass first (if Problem::colreg), relaxed pass when the compliant one
// found nothing within its share of the budget. `warm` (may be empty) is a previous path re-used
// as an initial solution candidate if it is still valid from the new start.
Result plan(const Problem& problem, const Params& params, const Hooks& hooks = {},
            const std::vector<Vec2>& warm = {});

// Exact validity of a whole path (used by tests and by the warm start); see
// ValidityChecker::check_path.
std::string check_path(const Problem& problem, const Params& params, const std::vector<Vec2>& path, bool colreg);

// Cost terms of eq. 5-9 for a path at constant speed.
CostTerms path_cost(const Problem& problem, const Params& params, const std::vector<Vec2>& path);

class RrtStar final : public Planner {
 public:
  std::string name() const override { return "rrtstar"; }
  // plan.step, plan.goal_bias, plan.rewire_factor, plan.k_nearest, plan.connect_goal,
  // plan.informed, plan.restart_after, plan.compliant_share.
  void declare(rt::ParamSet& ps) override;
  Result solve(const Request& rq, const Hooks& hooks = {}) override;
  RrtStarParams& params() { return p_; }

 private:
  RrtStarParams p_;
};

}  // namespace mpgc::opp
