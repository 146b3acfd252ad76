// What guidance_control refuses on nav/own_state, and how its input messages become the
// controller's inputs (for the DDS side only: a component main that links mpgc_msgs, and the fuzz
// targets in tests/fuzz/). The controller itself refuses bad plans and states (on_plan, on_nav).
// Moved verbatim from components/guidance_control/main.cpp (to_plan; the valid_mask check and the
// NavInput of the nav/own_state callback).
#pragma once

#include <cmath>
#include <string>

#include "mpgc/guidance_control/guidance_control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"

namespace mpgc::guidance_control {

inline PlanInput to_plan(const msg::Path& m) {
  PlanInput p;
  p.plan_id = m.plan_id;
  switch (m.status) {
    case msg::PlanStatus::PLAN_OK: p.kind = PlanKind::Ok; break;
    case msg::PlanStatus::PLAN_RELAXED: p.kind = PlanKind::Relaxed; break;
    case msg::PlanStatus::PLAN_NO_PATH: p.kind = PlanKind::NoPath; break;
    default: p.kind = PlanKind::InvalidInput; break;
  }
  p.reason = m.reason;
  p.stamp = m.header.stamp_ns > 0 ? static_cast<double>(m.header.stamp_ns) * 1e-9 : std::nan("");
  p.effective = m.effective_ns > 0 ? static_cast<double>(m.effective_ns) * 1e-9 : 0.0;
  p.waypoints.reserve(m.waypoints.size());
  for (const auto& w : m.waypoints) p.waypoints.push_back({w.x, w.y, w.speed});
  return p;
}

// nav/own_state: position, heading and velocity flagged valid (values are checked by on_nav).
inline std::string check_nav(const msg::NavState& m) {
  constexpr uint32_t kNeeded = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID;
  if ((m.valid_mask & kNeeded) != kNeeded)
    return "position, heading or velocity not valid (valid_mask " + std::to_string(m.valid_mask) + ")";
  return "";
}

// The controller's own-ship input; without a valid yaw rate r = 0 and *rate_missing is set (the
// PID loses its damping term, so the caller counts it).
inline NavInput to_nav(const msg::NavState& m, bool* rate_missing) {
  double r = m.r;
  *rate_missing = (m.valid_mask & msg::NAV_RATE_VALID) == 0;
  if (*rate_missing) r = 0.0;
  return {m.x, m.y, m.heading, m.u, r};
}

}  // namespace mpgc::guidance_control
