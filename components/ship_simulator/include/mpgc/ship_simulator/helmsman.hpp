// A rule-following helmsman for target ships (issue 17 part 3): a simple master who gives way or
// stands on by COLREG, so that encounters with a manoeuvring target can be tested (head-on "both
// turn to starboard", a crossing target that gives way, a stand-on target that holds).
//
// Pure and deterministic: no DDS, no clock, no randomness. Called once per simulator step with the
// target's own kinematics, the course and speed its route orders, and the other ships it sees
// (the own ship and the other targets, ground truth). The classification of rules 13-15 and the
// CPA are colreg::assess / colreg::cpa (common/): one vocabulary with the planner and evaluation.
//
//   Helmsman h(HelmsmanParams{});
//   HelmOrder o = h.decide(me, route_course, route_speed, {{0, own_ship}, {257000002, other}});
//   // o.course / o.speed: what to steer; o.mode: route, give-way, stand-on or acting alone
//
// What it does (from the target's point of view, for every ship that is a risk of collision:
// inside d_colreg, closing, predicted CPA below cpa_risk, TCPA below tcpa_max, rule 7):
// * head-on (rule 14), crossing give-way (rules 15, 16), overtaking (rule 13): alters course to
//   starboard by at least `alteration` (rule 8(b): readily apparent), more in 10 deg steps up to
//   `max_alteration` until the predicted CPA with every ship it gives way to is at least cpa_risk
//   (rule 8(d): passing at a safe distance; crossing, this passes astern, rule 15); holds that
//   course until each such ship is passed and clear (abaft the beam and opening, or beyond
//   d_colreg), then returns to its route;
// * crossing stand-on, overtaken (rule 17(a)(i)): keeps the course and speed it had when the risk
//   appeared, until the other ship is passed and clear;
// * rule 17(a)(ii)/(b) (`act_alone`): a stand-on ship whose give-way ship has not acted when close
//   (range below act_alone_range and predicted CPA below act_alone_cpa) acts itself, to starboard
//   by the same rule as above (never to port: rule 17(c));
// * a give-way duty to one ship wins over a stand-on duty to another (the stand-on hold is then
//   broken; the simple helmsman does not weigh conflicting obligations further).
// It does not: reduce speed, look at land or depth, use sound signals, or judge restricted
// visibility (rule 19); a ship that does not risk collision is ignored.
#pragma once

#include <cstdint>
#include <vector>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_simulator {

struct HelmsmanParams {
  // Rule 7 risk of collision, as colreg::ColregParams (the sectors of rules 13-15 keep their
  // defaults there). The duty is taken as soon as the risk appears inside d_colreg: early action
  // (rule 16).
  double d_colreg = 6.0 * geo::kNauticalMile;  // [m] ships farther away are not assessed
  double cpa_risk = 1.0 * geo::kNauticalMile;  // [m] predicted CPA below this is a risk
  double tcpa_max = 20.0 * 60.0;               // [s] a CPA farther in time is no risk yet
  // Rule 8(b): the alteration to starboard, at least `alteration`, increased in steps of
  // `alteration_step` up to `max_alteration` until every give-way ship passes at cpa_risk or more.
  double alteration = geo::deg2rad(35.0);      // [rad]
  double max_alteration = geo::deg2rad(90.0);  // [rad]
  double alteration_step = geo::deg2rad(10.0);  // [rad]
  // Rule 17(a)(ii)/(b): the stand-on ship acts itself when the give-way ship is closer than
  // act_alone_range and still predicted to pass closer than act_alone_cpa.
  bool act_alone = true;
  double act_alone_range = 1.0 * geo::kNauticalMile;  // [m]
  double act_alone_cpa = 0.25 * geo::kNauticalMile;   // [m]

  // Throws std::invalid_argument naming the first bad field (with its unit).
  void validate() const;
  // The rule 7 thresholds as colreg parameters (sectors: colreg defaults).
  colreg::ColregParams colreg_params() const;
};

// A ship the helmsman sees. `id` identifies it from step to step (0: the own ship, else the MMSI).
struct SeenShip {
  uint32_t id = 0;
  colreg::ShipKinematics k;
};

enum class HelmMode {
  kRoute,     // no duty: follow the route
  kGiveWay,   // altered to starboard for a ship it gives way to (rules 13, 14, 15, 16)
  kStandOn,   // holding course and speed (rule 17(a)(i))
  kActAlone,  // stand-on, acting itself because the give-way ship did not (rule 17(a)(ii), (b))
};
const char* to_string(HelmMode m);

struct HelmOrder {
  double course = 0.0;  // [rad] course to steer
  double speed = 0.0;   // [m/s]
  HelmMode mode = HelmMode::kRoute;
};

class Helmsman {
 public:
  explicit Helmsman(HelmsmanParams p);  // validates p
  // One decision. `me`: the target's position and velocity over ground (heading = course);
  // route_course [rad] / route_speed [m/s]: what its route (and scripted manoeuvres) order now.
  // Non-finite kinematics of another ship are skipped (never used), of `me` throw.
  HelmOrder decide(const colreg::ShipKinematics& me, double route_course, double route_speed,
                   const std::vector<SeenShip>& others);
  HelmMode mode() const { return mode_; }
  const HelmsmanParams& params() const { return p_; }

 private:
  enum class Duty { kGiveWay, kStandOn, kActAlone };
  struct Engaged {
    uint32_t id;
    Duty duty;
  };
  double avoidance_course(const colreg::ShipKinematics& me, double speed, const std::vector<SeenShip>& others) const;

  HelmsmanParams p_;
  colreg::ColregParams cp_;
  HelmMode mode_ = HelmMode::kRoute;
  std::vector<Engaged> engaged_;  // ships with a duty, until passed and clear
  double base_course_ = 0.0;      // [rad] course the alteration is measured from
  double alteration_ = 0.0;       // [rad] current alteration to starboard of base_course_
  double hold_course_ = 0.0, hold_speed_ = 0.0;  // stand-on: what is kept
  double last_course_ = 0.0, last_speed_ = 0.0;  // the previous order
  bool started_ = false;
};

}  // namespace mpgc::ship_simulator
