// The objective of the planning interface (OMPL's OptimizationObjective): the cost of seed 000
// eq. 5 as the sum of steering (eq. 6), margins from fixed obstacles (eq. 7) and from targets
// (eq. 8) at the waypoints, and path length (eq. 9). Planners that grow paths leg by leg add
// edge_cost per leg; path_cost gives the terms of a whole path.
#pragma once

#include <vector>

#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

struct CostTerms {  // weighted terms of eq. 5 (total = smooth + fixed + moving + length)
  double total = 0, smooth = 0, fixed = 0, moving = 0, length = 0;
};

class Objective {
 public:
  // Keeps references: `pb` and `w` must outlive the objective.
  Objective(const Problem& pb, const ObjectiveParams& w);

  const ObjectiveParams& weights() const { return w_; }
  // Node term of eq. 7 (weighted).
  double fixed_term(Vec2 p) const {
    if (w_.gamma_f == 0.0) return 0.0;
    return fixed_term_at(fixed_->nearest(p));
  }
  // The same term from the clearance fixed().nearest(p) already known (a planner that keeps it).
  double fixed_term_at(double clearance) const {
    if (w_.gamma_f == 0.0) return 0.0;
    return w_.gamma_f / std::max(clearance, w_.min_margin);
  }
  bool uses_fixed() const { return w_.gamma_f != 0.0; }
  // Node term of eq. 8 (weighted): the nearest target at time t.
  double moving_term(Vec2 p, double t) const;
  // Steering term of eq. 6 at the node the leg leaves (weighted); eq. 6 sums k = 1..p-1, so the
  // root's leg costs nothing.
  double steer_term(Vec2 dir, Vec2 seg, double len, bool at_root) const;
  // Cost added by the leg a -> b (eq. 5 increment): steering at a, margins at b (fixed_b: its
  // fixed_term, reused), length.
  double edge_cost(Vec2 dir, bool at_root, Vec2 seg, double len, double fixed_b, Vec2 b, double tb) const {
    return edge_sum(steer_term(dir, seg, len, at_root), fixed_b, moving_term(b, tb), len);
  }
  // The same sum from its terms. With steer = 0 it is a lower bound of the edge's cost in floating
  // point too (the steering term is >= 0 and rounding is monotone), so a search can refuse an edge
  // on the bound before it pays for the steering term's acos, with the same result.
  double edge_sum(double steer, double fixed_b, double moving_b, double len) const {
    return steer + fixed_b + moving_b + w_.gamma_l * len;
  }
  // The terms of a whole path at the problem's constant speed.
  CostTerms path_cost(const std::vector<Vec2>& path) const;

 private:
  const Problem& pb_;
  const ObjectiveParams& w_;
  NoFixedObstacles none_;
  const FixedObstacles* fixed_;
};

}  // namespace mpgc::opp
