// What obstacle_manager refuses on nav/own_state, and how a sa/tracks track becomes the
// TargetState that check_target / to_moving_obstacle judge (for the DDS side only: a component
// main that links mpgc_msgs, and the fuzz targets in tests/fuzz/; like msg_convert.hpp).
// Moved verbatim from components/obstacle_manager/main.cpp (the NavState validator lambda and the
// TargetState filling in the obstacles/moving timer).
#pragma once

#include <cmath>
#include <string>

#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/obstacle_manager/manager.hpp"

namespace mpgc::obstacle_manager {

// nav/own_state: a valid, finite position (the centre of the published region).
inline std::string check_nav(const msg::NavState& s) {
  if (!(s.valid_mask & msg::NAV_POSITION_VALID)) return "position not valid";
  if (!std::isfinite(s.x) || !std::isfinite(s.y)) return "position not finite";
  return "";
}

// plan/goal: a finite goal within DomainParams' range of the origin (the region is stretched to
// cover it; a goal 1e16 m away must not make it the size of the chart's numbers).
inline std::string check_goal(const msg::MissionGoal& g, double max_range) {
  if (!std::isfinite(g.x) || !std::isfinite(g.y)) return "goal position not finite";
  if (std::hypot(g.x, g.y) > max_range)
    return "goal farther than " + std::to_string(static_cast<long long>(max_range / 1000)) + " km from the origin";
  return "";
}

// One track of sa/tracks as the ship-domain code takes it (check_target says whether to use it).
inline TargetState target_state(const msg::Track& t) {
  TargetState ts;
  ts.id = t.id;
  ts.mmsi = t.mmsi;
  ts.x = t.x;
  ts.y = t.y;
  ts.vx = t.vx;
  ts.vy = t.vy;
  ts.var_x = t.cov[0];
  ts.var_y = t.cov[5];
  ts.var_vx = t.cov[10];
  ts.var_vy = t.cov[15];
  ts.length = t.length;
  ts.since_update = t.since_update;
  ts.tentative = t.status == msg::TrackStatus::TRACK_TENTATIVE;
  ts.deleted = t.status == msg::TrackStatus::TRACK_DELETED;
  return ts;
}

}  // namespace mpgc::obstacle_manager
