#include "mpgc/opp/colreg.hpp"

#include <cmath>
#include <limits>

#include "mpgc/geo/angles.hpp"

namespace mpgc::opp {

namespace {

// Eq. 11-15: time difference (own minus target) of arrival at the routes' intersection x_c, or
// NaN when the routes do not meet ahead of both vessels (eq. 13-14).
double arrival_difference(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, double c, const ColregParams& p) {
  if (1.0 - std::fabs(c) <= p.epsilon) return std::nan("");
  const Vec2 d = y0 - x0;
  const double vxw = cross(v, w);
  const double s = cross(d, w) / vxw, q = cross(d, v) / vxw;
  return (s > 0.0 && q > 0.0) ? s - q : std::nan("");
}

// Distance at the closest approach, on present courses, of a target at y0 (velocity w) to the own
// ship at x0 (velocity v).
double miss_distance(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w) {
  return std::sqrt(geom::closest_approach(x0 - y0, v - w, std::numeric_limits<double>::infinity()).dist2);
}

}  // namespace

bool pinnable(Obligation o) {
  return o == Obligation::kNone || o == Obligation::kHeadOn || o == Obligation::kCrossingGiveWay ||
         o == Obligation::kOvertaking || o == Obligation::kCrossingStandOn || o == Obligation::kOvertaken;
}

bool is_duty(Obligation o) {
  return o == Obligation::kHeadOn || o == Obligation::kCrossingGiveWay || o == Obligation::kOvertaking;
}

double PinnedLeg::course() const {
  if (std::isnan(course_)) course_ = std::atan2(v_.y, v_.x);
  return course_;
}

double PinnedLeg::turn() const {
  if (std::isnan(turn_)) turn_ = std::remainder(course() - e_.course0, 2.0 * geo::kPi);
  return turn_;
}

double PinnedLeg::turn_17c() const {
  if (std::isnan(turn_17c_))
    turn_17c_ = std::remainder(course() - (e_.course0 + (std::isnan(e_.held_17c) ? 0.0 : e_.held_17c)), 2.0 * geo::kPi);
  return turn_17c_;
}

Vec2 PinnedLeg::ahead() const {
  if (std::isnan(ahead_.x)) ahead_ = {std::cos(e_.course0), std::sin(e_.course0)};
  return ahead_;
}

Vec2 PinnedLeg::along() const {
  if (std::isnan(along_.x)) {
    const double ref = e_.course0 + (std::isnan(e_.held_17c) ? 0.0 : e_.held_17c);
    along_ = {std::cos(ref), std::sin(ref)};
  }
  return along_;
}

ColregCheck colreg_check_pinned(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const PinnedEncounter& e, const ColregParams& p) {
  return colreg_check_pinned(x0, y0, w, PinnedLeg(v, e), p);
}

ColregCheck colreg_check_pinned(const Vec2& x0, const Vec2& y0, const Vec2& w, const PinnedLeg& leg, const ColregParams& p) {
  const PinnedEncounter& e = leg.encounter();
  const Vec2 v = leg.v();
  if (e.obligation == Obligation::kNone) return colreg_check(x0, v, y0, w, p);
  ColregCheck out;
  out.situation = e.obligation;
  const double vn = leg.speed(), wn = norm(w);
  if (vn < p.min_speed) return out;
  const Vec2 d = y0 - x0;
  // The leg's course is taken only where needed: most legs are decided before (the range opens).
  auto port_turn = [&] { return leg.turn() < -p.port_tolerance; };
  // Rule 17(c) forbids turning toward the crossing ship while it is still on the port bow of the
  // course held (ahead of the beam, to port), even on a leg along which the range does not close
  // (DNV 12: a port turn round the ship's bow at d_safety, the range constant), if it is a risk now
  // or the leg passes it within risk_cpa: a leg back to the route that passes a ship 16 km off
  // wider than that is no action for it (paper s1_unexpected).
  if (e.obligation == Obligation::kCrossingStandOn && norm(d) <= p.port_turn_range && dot(d, leg.ahead()) > 0.0 &&
      cross(leg.ahead(), d) < 0.0 && port_turn() && (e.at_risk_17c || miss_distance(x0, v, y0, w) < p.risk_cpa)) {
    out.compliant = false;
    return out;
  }
  if (e.obligation == Obligation::kCrossingStandOn) {  // 17(c): not to port for a ship on the port side
    const Vec2 along = leg.along();
    const bool to_port = leg.turn_17c() < -p.port_tolerance;
    if (!to_port) return out;
    // Judged where the ship begins the turn, port_turn_lead back along the course held, and as
    // the evaluation judges whom a turn is for: a ship at risk on the course held then (its CPA
    // ahead within risk_cpa), even if the range opens along the new leg (DNV 51: a port turn to
    // pass astern of the crossing ship 2.6 km ahead, its CPA 1.1 km in 210 s), or one the leg
    // itself would close within risk_cpa.
    // The speed held is the encounter's (speed0): a port turn combined with slowing down so that
    // the ship passes ahead is still a turn to port for it (DNV 48 turned 34 deg to port at 1.5
    // m/s with the crossing ship 3.2 km on the port bow, CPA 1.7 km at 5 m/s).
    const double uh = std::isfinite(e.speed0) && e.speed0 >= p.min_speed ? e.speed0 : vn;
    const Vec2 xe = x0 - p.port_turn_lead * along, ye = y0 - (p.port_turn_lead / uh) * w, de = ye - xe;
    if (!(norm(de) <= p.port_turn_range && cross(along, de) < 0.0)) return out;
    const Vec2 held = uh * along;
    const bool held_risk = geom::cpa_time(de, w - held) > 0.0 && miss_distance(xe, held, ye, w) < p.risk_cpa;
    const bool leg_risk = dot(de, v - w) > 0.0 && miss_distance(xe, v, ye, w) < p.risk_cpa;
    out.compliant = !(e.at_risk_17c || held_risk || leg_risk);
    return out;
  }
  if (dot(d, v - w) <= 0.0) return out;  // the range opens along this leg: being cleared
  const double dt = wn < p.min_speed ? std::nan("") : arrival_difference(x0, v, y0, w, dot(v, w) / (vn * wn), p);
  switch (e.obligation) {
    case Obligation::kHeadOn: out.compliant = cross(v, d) < 0.0 && !port_turn(); break;
    case Obligation::kCrossingGiveWay: {
      if (across_astern(e, w, x0 - y0)) return out;
      out.compliant = !(dt <= 0.0) && !port_turn();
      break;
    }
    case Obligation::kOvertaking:
    case Obligation::kOvertaken: out.compliant = !(dt <= 0.0); break;  // §5.3: not across its bow
    default: break;  // kNone handled above
  }
  return out;
}

bool colreg_check_apparent(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const PinnedEncounter& e, const ColregParams& p) {
  return colreg_check_apparent(x0, y0, w, PinnedLeg(v, e), p);
}

bool colreg_check_apparent(const Vec2& x0, const Vec2& y0, const Vec2& w, const PinnedLeg& leg, const ColregParams& p) {
  const PinnedEncounter& e = leg.encounter();
  const Vec2 v = leg.v();
  if (e.obligation == Obligation::kNone) return true;
  if (leg.speed() < p.min_speed || dot(y0 - x0, v - w) <= 0.0) return true;  // not closing: no action owed
  if (e.obligation == Obligation::kCrossingGiveWay && across_astern(e, w, x0 - y0)) return true;
  const double turn = leg.turn();
  // Rule 14 also after an alteration was made: coming back to the meeting course near the ship is
  // meeting it again (Annapolis: 31 deg to starboard and back within a minute, 2.9 km off).
  if (e.obligation == Obligation::kHeadOn && turn < p.head_on_turn && norm(y0 - x0) <= p.act_range &&
      miss_distance(x0, v, y0, w) < p.risk_cpa)
    return false;
  if (!(p.apparent_turn > p.port_tolerance) || e.completed) return true;
  if (p.apparent_slowdown > 0.0 && leg.speed() <= (1.0 - p.apparent_slowdown - p.apparent_slowdown_margin) * e.speed0)
    return true;
  const bool either = e.obligation == Obligation::kOvertaking || e.obligation == Obligation::kOvertaken;
  const double a = either ? std::fabs(turn) : turn, need = p.apparent_turn + p.apparent_turn_margin;
  if (e.acted) return a >= need;
  return !(a > p.port_tolerance && a < need);
}

ColregCheck colreg_check(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const ColregParams& p) {
  ColregCheck out;
  const double vn = norm(v), wn = norm(w);
  if (vn < p.min_speed || wn < p.min_speed) return out;  // a drifting target has no route (§5.2)
  const double c = dot(v, w) / (vn * wn);
  const Vec2 d = y0 - x0;
  // §5.5 head-on: routes within theta_h (head_on_course_angle) of reciprocal -> the target must be on the port side (eq. 19).
  if (c < -std::cos(p.head_on_course_angle)) {
    out.situation = colreg::EncounterType::kHeadOn;
    if (!(cross(v, d) < 0.0)) {
      out.compliant = false;
      return out;
    }
  }
  // §5.2 intersection condition, eq. 13 (numerically safe form of eq. 12).
  if (1.0 - std::fabs(c) <= p.epsilon) return out;
  // Solution of eq. 11: x_c = x0 + s v = y0 + q w.
  const double vxw = cross(v, w);
  const double s = cross(d, w) / vxw;
  const double q = cross(d, v) / vxw;
  if (!(s > 0.0 && q > 0.0)) return out;  // eq. 14: x_c must lie ahead of both vessels
  // eq. 15: |x_c - x0|/|v| - |x_c - y0|/|w| = s - q (> 0: the target is first at x_c).
  const double dt = s - q;
  if (c > std::cos(p.overtaking_course_angle)) {  // eq. 16
    out.situation = vn > wn ? colreg::EncounterType::kOvertaking : colreg::EncounterType::kOvertaken;
    out.compliant = dt > 0.0;  // the overtaken route must be crossed behind the other vessel
    return out;
  }
  if (out.situation != colreg::EncounterType::kHeadOn)
    out.situation = cross(v, d) > 0.0 ? colreg::EncounterType::kCrossingGiveWay : colreg::EncounterType::kCrossingStandOn;
  out.compliant = out.compliant && (vxw * dt < 0.0);  // eq. 18 (eq. 17 x eq. 15)
  return out;
}

}  // namespace mpgc::opp
