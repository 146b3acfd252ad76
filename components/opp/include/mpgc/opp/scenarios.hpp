// Reference problems shared by tests and the benchmark: the three scenarios of seed 000 §7
// (Table 1) and a 100 x 100 world with discs (notes/ompl-baseline.md).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mpgc/opp/obstacles.hpp"
#include "mpgc/opp/rrtstar.hpp"

namespace mpgc::opp {

struct Scenario {
  std::string name;
  Problem problem;                         // problem.fixed points into `fixed`
  Params params;
  std::shared_ptr<FixedObstacles> fixed;   // owner of the fixed obstacles (may be null)
};

// Seed 000 §7, scenario n in {1, 2, 3}, in metres with `lpp` metres per ship length: map 100 x 100
// Lpp, start [0, 0] heading 45 deg, goal [100, 100] Lpp, d_safety = 10 Lpp, targets of Table 1.
// Speeds are not in the paper: every ship sails at `speed` (the same for all, which puts target 1
// of scenario 1 on a collision course). Scenario 3 adds canal walls as points 1 Lpp apart, 25 Lpp
// either side of the diagonal (the paper gives no width).
// (see random_points / random_targets for the growth benchmark).
Scenario paper_scenario(int n, double lpp = 100.0, double speed = 6.0);

// Scenario 1 with its targets frozen into discs of radius d_safety at the positions they hold when
// the own ship, on the straight route, is closest to them: a static 2-D problem both our RRT* and
// OMPL's RRTstar can solve with the same validity checker.
Scenario paper_scenario1_frozen(double lpp = 100.0, double speed = 6.0);

// The 100 x 100 world with 5 discs, start (5, 5), goal (95, 95), straight-line bound 127.28;
// path length only, no turning limit, no safety margin beyond the discs.
Scenario disc_world();

// `n` extra targets on crossing tracks (deterministic from `seed`), for growth measurements.
std::vector<Target> random_targets(const Problem& pb, int n, double speed, uint64_t seed);
// `n` random fixed points on 40 round islands kept at least `keep_out` from the straight route.
std::vector<Vec2> random_points(const Problem& pb, int n, double keep_out, uint64_t seed);

}  // namespace mpgc::opp
