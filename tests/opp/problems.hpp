// Problems the planner tests share.
#pragma once

#include <utility>
#include <vector>

#include "mpgc/opp/problem.hpp"

namespace mpgc::opp::test {

// Open water: own ship at the origin heading north (0 rad) at 5 m/s, goal 30 km ahead, a 60 x 40 km box.
inline Problem open_water(std::vector<Target> targets = {}) {
  Problem pb;
  pb.start = {0, 0};
  pb.heading = 0;
  pb.speed = 5;
  pb.goal.p = {30000, 0};
  pb.bounds = {-20000, -20000, 40000, 20000};
  pb.targets = std::move(targets);
  return pb;
}

}  // namespace mpgc::opp::test
