// The COLREG model of seed 000 §5 (eq. 11-19) as a predicate on one straight leg of the own ship
// against one target. Reporting (encounter lists, CPA/TCPA, rule 13-15 sectors) uses the shared
// geometry in mpgc/colreg/colreg.hpp; this predicate is the planner's own constraint.
#pragma once

#include <cstdint>

#include "mpgc/opp/geometry.hpp"

namespace mpgc::opp {

struct ColregParams {
  double theta_overtaking = 0.39269908169872414;  // [rad] theta_o of eq. 16 (22.5 deg)
  double theta_head_on = 0.39269908169872414;     // [rad] theta_h of §5.5 (22.5 deg)
  double epsilon = 1e-3;                          // [-] tolerance of the crossing test, eq. 13
  double min_speed = 0.05;                        // [m/s] below it a vessel has no route to cross
};

enum class ColregSituation {
  kNone,        // routes do not meet ahead of both vessels and no head-on geometry
  kHeadOn,      // §5.5
  kCrossing,    // §5.4
  kOvertaking,  // §5.3 (eq. 16 holds; either vessel may be the faster one)
};

struct ColregCheck {
  ColregSituation situation = ColregSituation::kNone;
  bool compliant = true;
};

// Own ship at x0 with velocity v, target at y0 with velocity w (the positions at the same time).
// Implements: head-on (eq. 19, the target must be on the own port side), then the intersection
// condition (eq. 13-14) with time of arrival at x_c (eq. 15); overtaking (eq. 16) requires the
// target first at x_c; crossing requires eq. 18.
ColregCheck colreg_check(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const ColregParams& p);

}  // namespace mpgc::opp
