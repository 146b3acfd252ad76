// The COLREG model of seed 000 §5 (eq. 11-19) as a predicate on one straight leg of the own ship
// against one target. Reporting (encounter lists, CPA/TCPA, rule 13-15 sectors) uses the shared
// geometry in mpgc/colreg/colreg.hpp; this predicate is the planner's own constraint.
#pragma once

#include <cmath>
#include <cstdint>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/opp/geometry.hpp"

namespace mpgc::opp {

struct ColregParams {
  double overtaking_course_angle = 0.39269908169872414;  // [rad] theta_o of eq. 16: overtaking when the velocities are within it of each other (22.5 deg)
  double head_on_course_angle = 0.39269908169872414;     // [rad] theta_h of §5.5: head-on when one velocity is within it of the other's reciprocal (22.5 deg)
  double epsilon = 1e-3;                          // [-] tolerance of the crossing test, eq. 13
  double min_speed = 0.05;                        // [m/s] below it a vessel has no route to cross
  double port_tolerance = 0.08726646259971647;    // [rad] a pinned head-on or give-way leg may point
                                                  // this far to port of the course it was pinned at (5 deg)
  // Rule 8(b): any alteration to avoid collision must be "large enough to be readily apparent" (a
  // succession of small ones avoided), for a duty and for a stand-on ship that acts. While the
  // range to a pinned target closes, a leg holds the course it was pinned at (within
  // port_tolerance) or is altered by at least this much (colreg_check_apparent). 0: no band.
  double apparent_turn = 0.5235987755982988;      // [rad] 30 deg, the NTNU evaluator's delta_course_app
  // Rule 17(c) binds the stand-on ship's action under 17(a)(ii) for the crossing ship, the action it
  // may take once that ship is near: within this range a leg closing it may not turn to port of
  // course0; farther off a turn (made for another ship) is no such action.
  double port_turn_range = 1e300;                 // [m] (the node sets plan.rule17c_range x d_safety)
  // The guidance turns onto a leg before its first waypoint (at the circle of acceptance, 2.5 ship
  // lengths), so a port leg is judged for 17(c) as begun this far earlier on the course held: the
  // plan turned back at the crossing ship's CPA, the ship 10-20 s before it (DNV 32, 40, 51).
  double port_turn_lead = 0.0;                    // [m] (the node sets plan.rule17c_lead x d_safety)
  // A leg that would pass a target closer than this is a risk of collision to it: only such a
  // port leg is a 17(c) turn "for" it (one passing it 3 km off is not: DNV 30), and only such a
  // head-on leg must have altered (head_on_turn).
  double risk_cpa = 1e300;                        // [m] (the node sets plan.encounter_cpa x d_safety)
  // Rule 14(a), "each shall alter her course to starboard": within act_range of a pinned head-on
  // target, a closing leg that would pass it within risk_cpa is altered to starboard of course0 by
  // at least head_on_turn, not held (Annapolis: the course held to a 109 m passing, 100 m d_safety).
  double act_range = 0.0;                         // [m] (the node sets d_COLREG; 0: not required)
  double head_on_turn = 0.17453292519943295;      // [rad] 10 deg, the NTNU evaluator's theta_sm_lim
  // Rule 8(b): "alteration of course and/or speed": a leg at most (1 - apparent_slowdown) of the
  // speed the encounter began at is a readily apparent action whatever its course (0: never).
  double apparent_slowdown = 0.5;                 // [-] the NTNU evaluator's speed reduction
  // A readily apparent leg aims this far beyond apparent_turn / apparent_slowdown: the evaluation
  // measures the course and speed sailed, which approach a leg's only asymptotically (DNV 47 turned
  // 29.98 deg for 30, DNV 41 slowed 48 % for 50 %).
  double apparent_turn_margin = 0.03490658503988659;  // [rad] 2 deg
  double apparent_slowdown_margin = 0.05;             // [-]
};

// The situation of one leg in the project's one encounter vocabulary (colreg::EncounterType):
// kNone (routes do not meet ahead of both vessels, no head-on geometry), kHeadOn (§5.5),
// kCrossingGiveWay / kCrossingStandOn (§5.4, the target on the own starboard / port side),
// kOvertaking / kOvertaken (§5.3, eq. 16: the own ship the faster / the slower one).
struct ColregCheck {
  colreg::EncounterType situation = colreg::EncounterType::kNone;
  bool compliant = true;
};

// Own ship at x0 with velocity v, target at y0 with velocity w (the positions at the same time).
// Implements: head-on (eq. 19, the target must be on the own port side), then the intersection
// condition (eq. 13-14) with time of arrival at x_c (eq. 15); overtaking (eq. 16) requires the
// target first at x_c; crossing requires eq. 18.
ColregCheck colreg_check(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const ColregParams& p);

// An own-ship obligation fixed for the whole encounter (EncounterMemory, encounters.hpp). The
// per-leg model above re-derives the situation from each leg's own course, so a course change
// made before the target is inside d_COLREG turns a head-on into a "crossing" that may be passed
// starboard to starboard; with the situation pinned when the risk of collision first appears,
// every leg is held to that situation's rule instead.
//
// Pinned obligations are colreg::EncounterType values with a duty for the own ship: kNone (not
// pinned: the per-leg model of eq. 11-19 applies), kHeadOn (rule 14: alter to starboard, pass port
// to port), kCrossingGiveWay (rules 15-16: the target on the starboard side: keep out of its way,
// astern) and kOvertaking (rule 13: keep out of the way of the overtaken vessel) — the own ship's
// duties — and the stand-on situations, whose course and speed the node's stand-on hold keeps:
// kCrossingStandOn (rule 17(c): when the stand-on ship acts, not to port for a ship on her own
// port side) and kOvertaken (not across the overtaking ship's bow, §5.3).
using Obligation = colreg::EncounterType;
// True for the six values above.
bool pinnable(Obligation o);
// True for the own ship's duties: head-on, crossing give-way, overtaking.
bool is_duty(Obligation o);

struct PinnedEncounter {
  Obligation obligation = Obligation::kNone;
  double course0 = 0.0;  // [rad] own course over ground when the situation was fixed
  int track_side = 0;    // [-] side of the target's track the own ship was on then: sign(w ^ (x - y))
  double target_course = 0.0;  // [rad] the target's course then (a new course is a new encounter)
  // The own ship has begun its alteration (EncounterMemoryParams::acted_turn): from then on a
  // closing leg completes a readily apparent one (colreg_check_apparent) instead of returning to
  // course0 — a turn begun and then given up is the "succession of small alterations" of rule
  // 8(b) (a head-on ship that also turns must not make the own ship's turn a half one). Not kept
  // across a restart.
  bool acted = false;
  // ... and once the own course has been altered by apparent_turn, the alteration is made: the
  // band is lifted (the evaluation's rule 8(b) asks the largest alteration to be readily
  // apparent, not every leg: an overtaking ship may then run parallel while it passes). Back
  // within acted_turn of course0 while the risk of collision remains, it was given up, not made:
  // completed is cleared (acted stays).
  bool completed = false;
  double speed0 = std::nan("");  // [m/s] own speed over ground when the situation was fixed (not kept across a restart)
  // Rule 17(c) for a crossing stand-on target: the most starboard own course, relative to course0,
  // held while the target was within port_turn_range on the own port side and closing (NaN before).
  // A closing leg may not turn to port of course0 + held_17c while the target is on the port side
  // of that course: turning back toward it after a starboard alteration made for another ship is
  // altering course to port for it (DNV 27, 30: the return to the route with the crossing ship 2.4
  // km on the port beam). Not kept across a restart.
  double held_17c = std::nan("");
  // ... and it is such a risk now (at the plan's start): then every closing leg to port of that
  // course is a turn for it, however far that leg would pass it (the evaluation judges a turn by
  // the risk before it: DNV 40 turned 50 deg to port to pass astern of a crossing ship 1.3 km on
  // the port bow, predicted CPA 1.2 km in 45 s, on a leg that itself would pass it wider).
  bool at_risk_17c = false;
};

// Side of the target's track (velocity w) that the own ship (at r from the target) is on: +1, -1,
// or 0 on the track line.
inline int track_side(Vec2 w, Vec2 r) {
  const double c = cross(w, r);
  return c > 0.0 ? 1 : (c < 0.0 ? -1 : 0);
}
// Give-way met: the own ship is across the target's track from where it was pinned, astern of it.
inline bool across_astern(const PinnedEncounter& e, Vec2 w, Vec2 r) {
  return e.track_side != 0 && track_side(w, r) != e.track_side && dot(r, w) < 0.0;
}

// One leg's velocity v against one pinned encounter e, with what the checks at every point along
// the leg share (ValidityChecker checks a leg every colreg_spacing): its speed, the encounter's
// directions, and the leg's course relative to them. Each atan2, remainder and sincos is taken
// once a leg, when a check first needs it, by the same expression as a single check would (the
// answers are the same bit for bit). `e` must outlive it.
class PinnedLeg {
 public:
  PinnedLeg(Vec2 v, const PinnedEncounter& e) : v_(v), speed_(norm(v)), e_(e) {}
  Vec2 v() const { return v_; }
  double speed() const { return speed_; }
  const PinnedEncounter& encounter() const { return e_; }
  double turn() const;      // [rad] the leg's course minus course0, in [-pi, pi]
  double turn_17c() const;  // [rad] ... minus course0 + held_17c, rule 17(c)'s course held
  Vec2 ahead() const;       // the direction of course0
  Vec2 along() const;       // the direction of course0 + held_17c

 private:
  double course() const;
  Vec2 v_;
  double speed_;
  const PinnedEncounter& e_;
  mutable double course_ = std::nan(""), turn_ = std::nan(""), turn_17c_ = std::nan("");
  mutable Vec2 ahead_{std::nan(""), 0.0}, along_{std::nan(""), 0.0};
};

// One leg (own at x0 with velocity v, target at y0 with velocity w, same time) against a pinned
// obligation. A leg on which the range opens is clear. Otherwise head-on: the target on the port
// side (eq. 19) and no alteration to port of course0 beyond port_tolerance; crossing stand-on,
// within port_turn_range: no alteration to port of course0 + held_17c beyond port_tolerance while
// the target is on the port side of that course (rule 17(c)); give-way: no
// alteration to port, and where the routes meet ahead of both (eq. 13-14) the target reaches x_c
// first (eq. 15), until the own ship is across the target's track astern of it; overtaking: the
// target first at x_c (§5.3).
ColregCheck colreg_check_pinned(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const PinnedEncounter& e, const ColregParams& p);
// The same at a point x0 of a leg (the target at y0 then). The points come by reference: the
// planner's innermost check, and passed by value the callee's packing of each Vec2 into one
// register stalled on store forwarding (half of its own time in s1_colreg's profile).
ColregCheck colreg_check_pinned(const Vec2& x0, const Vec2& y0, const Vec2& w, const PinnedLeg& leg, const ColregParams& p);

// Rule 8(b) for a leg against a pinned obligation (the full COLREG level only: the first
// relaxation drops it, "if the circumstances of the case admit"): false when the range closes
// along the leg and its course is altered from course0 by more than port_tolerance but less than
// apparent_turn (to starboard; to either side when overtaking or overtaken), unless its speed is
// reduced by apparent_slowdown from speed0. A give-way leg already across the target's track
// astern is free. With it, rule 14(a): a closing head-on leg within act_range that would pass
// within risk_cpa has altered to starboard by head_on_turn at least (at any speed).
bool colreg_check_apparent(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const PinnedEncounter& e, const ColregParams& p);
bool colreg_check_apparent(const Vec2& x0, const Vec2& y0, const Vec2& w, const PinnedLeg& leg, const ColregParams& p);

}  // namespace mpgc::opp
