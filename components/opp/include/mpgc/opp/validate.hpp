// What opp refuses on its input topics, as functions of the message (for the DDS side only: a
// component main that links mpgc_msgs, and the fuzz targets in tests/fuzz/). Each returns why a
// sample is unusable, or "" to take it: the validator argument of Component::subscribe.
// Moved verbatim from components/opp/main.cpp (check_nav, check_goal, check_moving, finite2).
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

inline bool finite2(double a, double b) { return std::isfinite(a) && std::isfinite(b); }

// nav/own_state: position and heading valid and finite (the start of every plan).
inline std::string check_nav(const msg::NavState& s) {
  const uint32_t need = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID;
  if ((s.valid_mask & need) != need) return "position or heading flagged invalid";
  if (!finite2(s.x, s.y) || !std::isfinite(s.heading)) return "non-finite position or heading";
  if (std::hypot(s.x, s.y) > 1e6) return "position more than 1000 km from the origin of the local frame";
  return "";
}

// plan/goal: a finite goal, a heading that is NaN (any) or finite with a tolerance, speeds and
// distances finite and >= 0.
inline std::string check_goal(const msg::MissionGoal& g) {
  if (!finite2(g.x, g.y)) return "non-finite goal position";
  // The local NED frame is flat: a goal beyond 1000 km is not one to plan to (a fuzzed 1.1e16 m
  // goal took 6 minutes and 5 GB in one plan).
  if (std::hypot(g.x, g.y) > 1e6) return "goal more than 1000 km from the origin of the local frame";
  if (std::isinf(g.heading)) return "infinite goal heading (NaN means any)";
  if (std::isfinite(g.heading) && !(g.heading_tolerance >= 0 && std::isfinite(g.heading_tolerance)))
    return "heading_tolerance must be finite and >= 0";
  if (!(std::isfinite(g.cruise_speed) && g.cruise_speed >= 0)) return "cruise_speed must be finite and >= 0";
  if (!(std::isfinite(g.safety_distance) && g.safety_distance >= 0)) return "safety_distance must be finite and >= 0";
  return "";
}

// obstacles/moving: at most 10000 obstacles, each with a finite position and velocity.
inline std::string check_moving(const msg::MovingObstacles& m) {
  if (m.obstacles.size() > 10000) return "more than 10000 moving obstacles";
  for (size_t i = 0; i < m.obstacles.size(); ++i) {
    const auto& o = m.obstacles[i];
    if (!finite2(o.x, o.y) || !finite2(o.vx, o.vy))
      return "obstacle " + std::to_string(i) + " (id " + std::to_string(o.id) + ") has a non-finite position or velocity";
  }
  return "";
}

// obstacles/fixed: a region that is not NaN and not empty (an infinite side: the chart is
// complete that way, as the obstacle manager publishes a chart it publishes whole).
inline std::string check_fixed(const msg::FixedObstacles& m) {
  for (double v : {m.region_min_x, m.region_min_y, m.region_max_x, m.region_max_y})
    if (std::isnan(v)) return "region bound is NaN";
  if (!(m.region_max_x > m.region_min_x) || !(m.region_max_y > m.region_min_y)) return "region is empty";
  return "";
}

inline Bounds region_of(const msg::FixedObstacles& m) {
  return {m.region_min_x, m.region_min_y, m.region_max_x, m.region_max_y};
}

}  // namespace mpgc::opp
