// The validity checker of the planning interface (OMPL's StateValidityChecker and MotionValidator
// in one): whether a leg of the own ship may be sailed. Turn limit (eq. 2), clearance from fixed
// obstacles (eq. 4 along the whole leg), time-dependent clearance from every target at its eq. 3
// position (eq. 3-4), and COLREG at a level: §5 per leg and the pinned obligations of the
// encounter memory. Every planner checks its motions here, so all of them answer to the same rules.
//
//   opp::ValidityChecker v(problem, constraints);
//   if (v.turn_ok(dir, b - a, len, at_root) && v.fixed_clear(a, b) &&
//       v.moving(a, t_a, b, len, opp::ColregLevel::kFull) == opp::ValidityChecker::kValid) ...
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

class ValidityChecker {
 public:
  // Keeps references: `pb` and `c` must outlive the checker.
  ValidityChecker(const Problem& pb, const ConstraintParams& c);

  // What makes a leg invalid (the counters of a no-path reason).
  enum Reject { kValid = 0, kTurn, kTarget, kColreg, kFixed, kGoalHeading, kRejectCount };

  const Problem& problem() const { return pb_; }
  const ConstraintParams& constraints() const { return c_; }
  const FixedObstacles& fixed() const { return *fixed_; }
  bool has_targets() const { return !pb_.targets.empty(); }
  bool turn_limited() const { return cos_turn_ > -1.5; }

  // eq. 2: |theta| <= max_turn, as cos(theta) >= cos(max_turn). `dir` is the unit incoming
  // direction, `seg` the leg (length `len`); the first leg is exempt unless turn_limit_at_start.
  bool turn_ok(Vec2 dir, Vec2 seg, double len, bool at_root) const {
    if (!turn_limited() || (at_root && !c_.turn_limit_at_start)) return true;
    return dot(dir, seg) >= (cos_turn_ - 1e-12) * len;
  }
  // The last leg's course within the goal's heading tolerance (§6).
  bool goal_heading_ok(Vec2 seg) const;
  // Fixed clearance distance of a leg: d_safety, or from the start with escape_start, what the
  // start already keeps (a leg may not get closer than it starts).
  double fixed_distance(bool from_start) const { return from_start ? start_fixed_d_ : c_.safety_distance; }
  // [m] distance from p to the nearest fixed obstacle or to the edge of the charted region.
  double fixed_clearance(Vec2 p) const;
  // eq. 4 along the whole leg a -> b at distance d, from the chart's obstacles and from the unknown
  // water beyond its region (a box: the leg is inside it by d when both ends are).
  bool fixed_clear(Vec2 a, Vec2 b, double d) const {
    if (pb_.charted && !(pb_.charted->contains_by(a, d) && pb_.charted->contains_by(b, d))) return false;
    return fixed_->segment_clear(a, b, d);
  }
  // The same answer when the obstacles' clearances of both ends, ca = fixed().nearest(a) and
  // cb = fixed().nearest(b), are known: a distance is 1-Lipschitz, so every point of the leg is
  // at least min(ca, cb, (ca + cb - |ab|) / 2) from every obstacle, and an end closer than d
  // blocks the leg. Only a margin far above rounding decides here; the rest goes to the exact
  // segment_clear. Most legs of a tree in open water need no search of the chart.
  bool fixed_clear(Vec2 a, Vec2 b, double d, double ca, double cb) const {
    if (pb_.charted && !(pb_.charted->contains_by(a, d) && pb_.charted->contains_by(b, d))) return false;
    const double tol = certificate_tol(a, b, d);
    if (std::min(ca, cb) < d - tol) return false;
    if (std::min({ca, cb, 0.5 * (ca + cb - norm(b - a))}) >= d + tol) return true;
    return fixed_->segment_clear(a, b, d);
  }
  // True when fixed_clear(a, b, d, ca, cb) refuses every leg ending at b from any a with
  // max(|a.x|, |a.y|) <= reach, whatever ca: b is closer than d (by more than the certificate's
  // margin, whose bound reach gives).
  bool fixed_blocks_end(Vec2 b, double cb, double d, double reach) const {
    return cb < d - certificate_tol({reach, reach}, b, d);
  }
  // The same answer when only a's clearance is known, ca = fixed_clearance(a) (the charted
  // region's edge included): every point of a short leg is within |ab| of a, so a leg shorter than
  // ca - d is clear without a search (an APF step, seed 003: most of apf-vo's time was these).
  bool fixed_clear_from(Vec2 a, double ca, Vec2 b, double d) const {
    if (ca - norm(b - a) >= d + certificate_tol(a, b, d)) return true;
    return fixed_clear(a, b, d);
  }
  // [m] fixed().nearest(p): the obstacles' clearance alone (without the charted region's edge).
  double fixed_nearest(Vec2 p) const { return fixed_->nearest(p); }
  // eq. 3-4 along the leg a -> b (length len) started at time ta, against every target (at
  // d_safety + its margin), plus
  // COLREG at `level`. `escape`: a leg from a start already inside d_safety of a target may not
  // get closer to it than it starts (escape_start).
  Reject moving(Vec2 a, double ta, Vec2 b, double len, ColregLevel level, bool escape = false) const;

  // Exact validity of a whole path at constant speed: every check above on every leg and the
  // arrival heading. Returns "" or the first violation.
  std::string check_path(const std::vector<Vec2>& path, bool colreg) const;
  // The same at a COLREG level (a relaxed one: the duties pinned, rule 17(c) or not).
  std::string check_path(const std::vector<Vec2>& path, ColregLevel level) const;

 private:
  // Only a margin far above the rounding of the distances decides by a certificate.
  static double certificate_tol(Vec2 a, Vec2 b, double d) {
    return 1e-3 + 1e-6 * (std::fabs(d) + std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y)}));
  }
  const Problem& pb_;
  const ConstraintParams& c_;
  NoFixedObstacles none_;
  const FixedObstacles* fixed_;
  double cos_turn_, dc2_, inv_u_, start_fixed_d_;
  bool goal_any_heading_;
};

}  // namespace mpgc::opp
