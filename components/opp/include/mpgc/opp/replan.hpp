// When to plan again (seed 000 §6): at a fixed rate, and at once when the goal changes or a
// target's predicted track (eq. 3) moved away from the one the last plan assumed. The decision
// logic of the component, kept here so it is tested without DDS.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

struct ReplanParams {
  double period = 15.0;            // [s] fixed re-planning period (paper: 15 s)
  double track_threshold = 300.0;  // [m] deviation of a predicted target position that triggers a plan
  double track_horizon = 300.0;    // [s] the predictions are compared at 0, horizon/2 and horizon
  double min_interval = 2.0;       // [s] event-triggered plans no closer than this
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

class ReplanPolicy {
 public:
  explicit ReplanPolicy(ReplanParams p);
  // A non-empty reason when a plan is due at time t [s] for goal `goal_id` and the targets as
  // predicted at t (Target::p at time t).
  std::string due(double t, uint32_t goal_id, const std::vector<Target>& targets) const;
  // Records the plan made at time t with these inputs; after a failed plan (`ok` false: no path or
  // invalid input) the next one is due after min_interval instead of a whole period.
  void planned(double t, uint32_t goal_id, const std::vector<Target>& targets, bool ok = true);

 private:
  ReplanParams p_;
  bool any_ = false;
  bool ok_ = true;
  double t_last_ = 0.0;
  uint32_t goal_id_ = 0;
  std::vector<Target> targets_;  // as predicted at t_last_
};

}  // namespace mpgc::opp
