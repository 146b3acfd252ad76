// The COLREG model of seed 000 §5 (eq. 11-19) as a predicate on one straight leg of the own ship
// against one target, plus a reporting classification (head-on, crossing, overtaking) with CPA.
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

// Closest point of approach of two constant-velocity points: tcpa [s] (may be negative) and cpa [m].
struct Cpa {
  double tcpa = 0.0;
  double cpa = 0.0;
};
Cpa closest_approach(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w);

// Reporting view of one encounter (mirrors msg::EncounterType / OwnRole without DDS).
enum class EncounterType { kNone, kHeadOn, kCrossingGiveWay, kCrossingStandOn, kOvertaking, kOvertaken };
enum class OwnRole { kNone, kGiveWay, kStandOn, kBothGiveWay };
struct EncounterInfo {
  EncounterType type = EncounterType::kNone;
  OwnRole role = OwnRole::kNone;
  double cpa = 0.0;      // [m]
  double tcpa = 0.0;     // [s]
  double range = 0.0;    // [m]
  double bearing = 0.0;  // [rad] true bearing own -> target
};
// kNone when the target is beyond d_colreg or the §5 geometry gives no encounter.
EncounterInfo classify_encounter(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, double d_colreg, const ColregParams& p);

}  // namespace mpgc::opp
