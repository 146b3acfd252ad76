// COLREG geometry shared by situational awareness, the planner and the evaluation: closest point
// of approach of two constant-velocity ships, relative bearings, and the encounter type of rules
// 13-15. Pure functions in the local NED frame (x north, y east, metres, radians clockwise from
// north); no DDS, no clock.
//
//   colreg::ShipKinematics own{0, 0, 5, 0}, tgt{4000, 100, -5, 0};
//   colreg::Cpa c = colreg::cpa(own, tgt);            // c.dcpa ~ 100 m, c.tcpa ~ 400 s
//   colreg::Assessment a = colreg::assess(own, tgt, colreg::ColregParams{});  // a.type == kHeadOn
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mpgc/geo/angles.hpp"

namespace mpgc::colreg {

// Position and velocity over ground of one ship. `heading` is the bow direction used for relative
// bearings (COLREG sectors are defined by the lights, i.e. the heading); NaN means "use the course
// over ground", which is what AIS-less radar tracks and the DNV generator provide.
struct ShipKinematics {
  double x = 0.0;   // [m] north
  double y = 0.0;   // [m] east
  double vx = 0.0;  // [m/s] north velocity over ground
  double vy = 0.0;  // [m/s] east velocity over ground
  double heading = std::numeric_limits<double>::quiet_NaN();  // [rad] NaN: course over ground

  static ShipKinematics from_course(double x, double y, double course, double speed,
                                    double heading = std::numeric_limits<double>::quiet_NaN()) {
    return {x, y, speed * std::cos(course), speed * std::sin(course), heading};
  }
  double speed() const { return std::hypot(vx, vy); }
  double course() const { return geo::course_of(vx, vy); }
  // Heading if known, else course over ground (course of a ship at rest is 0 = north).
  double bow() const { return std::isfinite(heading) ? heading : course(); }
  bool finite() const {
    return std::isfinite(x) && std::isfinite(y) && std::isfinite(vx) && std::isfinite(vy) && !std::isinf(heading);
  }
};

// Closest point of approach of two ships on constant velocity (seed 003 eq. 11-14; seed 002 §3
// step 1). tcpa < 0 means the CPA is in the past (the ships are opening); with no relative motion
// tcpa = 0 and dcpa = range.
struct Cpa {
  double dcpa;   // [m] distance at the CPA
  double tcpa;   // [s] time from now to the CPA
  double range;  // [m] current distance
};
Cpa cpa(const ShipKinematics& own, const ShipKinematics& target);

// The widest single manoeuvre from now: one turn (on a circle of turn_radius at the new speed,
// or at once when 0) to a constant course and speed, held; the targets keep their velocities.
// What a start allows at best with one alteration: when no course and speed keeps a distance,
// no single manoeuvre can (seed 002's 0.7 NM claim is for starts that allow it, issue 18).
// Instant speed changes and a steady turn from the first second make it a bound from above.
struct EscapeParams {
  std::vector<double> speed_fractions{1.0};  // [-] of the own speed, each in (0, 1]
  double course_step = geo::deg2rad(1.0);    // [rad] alterations 0, +-step, ... up to +-180 deg
  double turn_radius = 0.0;                  // [m] steady turning radius; 0: the turn is instant
  double dt = 1.0;                           // [s] sampling of the distances along the turn
  bool starboard_only = false;               // no alteration to port (rules 14, 15 and 17(c) prefer starboard)
  double max_alteration = geo::kPi;          // [rad] no larger course change (a planner's reach, e.g. a grid ahead)
  void validate() const;                     // throws std::invalid_argument naming the field
};
struct Escape {
  double alteration = 0.0;  // [rad] the course change, + to starboard (turned that way)
  double course = 0.0;      // [rad] the course then held
  double speed = 0.0;       // [m/s]
  double min_distance = std::numeric_limits<double>::infinity();  // [m] least distance to any target from now on
  int target = -1;          // index of the target at that distance; -1 without targets
};
Escape best_escape(const ShipKinematics& own, const std::vector<ShipKinematics>& targets, const EscapeParams& p);

// True bearing of the target from the own ship, (-pi, pi].
double bearing(const ShipKinematics& own, const ShipKinematics& target);
// beta: bearing of the target relative to the own bow, (-pi, pi], positive to starboard.
double relative_bearing(const ShipKinematics& own, const ShipKinematics& target);
// alpha (aspect): bearing of the own ship relative to the target's bow, (-pi, pi].
inline double aspect(const ShipKinematics& own, const ShipKinematics& target) {
  return relative_bearing(target, own);
}

enum class EncounterType {
  kNone,             // no risk of collision, or outside every rule sector
  kHeadOn,           // rule 14: both give way to starboard
  kCrossingGiveWay,  // rule 15: target on own starboard side, own ship gives way
  kCrossingStandOn,  // rule 15/17: target on own port side, own ship stands on
  kOvertaking,       // rule 13: own ship overtakes the target (gives way)
  kOvertaken         // rule 13: the target overtakes the own ship (own ship stands on)
};
enum class Role { kNone, kGiveWay, kStandOn, kBothGiveWay };

const char* to_string(EncounterType t);
// The DNV ship-traffic-generator names: "head-on", "crossing-give-way", "crossing-stand-on",
// "overtaking-give-way", "overtaking-stand-on", "noRiskCollision".
const char* dnv_name(EncounterType t);
Role role_of(EncounterType t);
const char* to_string(Role r);  // "none", "give-way", "stand-on", "both-give-way"

// Thresholds of the classification. Defaults: seed 000 §5 (abaft_beam = head_on_sector = 22.5 deg) for the
// sectors and the DNV ship-traffic-generator for the aspect tolerances (encounter_settings.json:
// theta13Criteria, theta15Criteria); from_dnv_settings() takes all four angles from that file.
struct ColregParams {
  // Rule 13: a ship "more than 22.5 deg abaft the beam" is overtaking; the stern sector is
  // |beta| > 90 deg + abaft_beam (seed 000 eq. 16; DNV theta15 = [90 + abaft_beam, 270 - abaft_beam]).
  double abaft_beam = geo::deg2rad(22.5);  // [rad]
  // Rule 14: head-on when each ship sees the other within head_on_sector of its bow (seed 000 §5.5
  // assumes 22.5 deg; DNV theta14Criteria uses 5 deg).
  double head_on_sector = geo::deg2rad(22.5);  // [rad]
  // Overtaking: the overtaken ship must be within this of the overtaking ship's bow (DNV
  // theta13Criteria, 67.5 deg).
  double overtake_aspect = geo::deg2rad(67.5);  // [rad]
  // Crossing: the give-way ship may appear up to this far to the other ship's starboard and still
  // be "on its port side" (DNV theta15Criteria, 5 deg).
  double crossing_aspect = geo::deg2rad(5.0);  // [rad]
  // Risk of collision: targets farther than d_colreg (seed 000 §5.1), opening (tcpa < 0), passing
  // wider than cpa_risk or later than tcpa_max are kNone. Infinity disables a limit.
  double d_colreg = 6.0 * geo::kNauticalMile;   // [m]
  double cpa_risk = 0.7 * geo::kNauticalMile;   // [m] seed 002 §4 safe CPA
  double tcpa_max = 30.0 * 60.0;                // [s] DNV situationLength

  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
  // Sector angles from a DNV encounter_settings.json ("classification" object); the risk limits
  // keep their defaults. Throws std::runtime_error naming the file and the missing/bad key.
  static ColregParams from_dnv_settings(const std::string& path);
};

// Rule sector from the two relative bearings only (no range or CPA test), in the DNV generator's
// order: overtaken, overtaking, head-on, crossing give-way, crossing stand-on, else kNone.
// beta = relative_bearing(own, target), alpha = aspect(own, target).
EncounterType classify_sectors(double beta, double alpha, const ColregParams& p);

struct Assessment {
  EncounterType type;    // kNone when there is no risk of collision
  EncounterType sector;  // what the bearings alone say (type before the risk test)
  Role role;
  Cpa cpa;
  double beta;   // [rad] relative bearing of the target from the own bow
  double alpha;  // [rad] relative bearing of the own ship from the target's bow
  bool risk;     // inside d_colreg, closing, dcpa < cpa_risk and tcpa < tcpa_max
};
// Full assessment of one target. Non-finite kinematics throw std::invalid_argument.
Assessment assess(const ShipKinematics& own, const ShipKinematics& target, const ColregParams& p);
inline EncounterType classify(const ShipKinematics& own, const ShipKinematics& target, const ColregParams& p) {
  return assess(own, target, p).type;
}

}  // namespace mpgc::colreg
