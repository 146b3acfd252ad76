#include "mpgc/opp/validity.hpp"

#include <algorithm>
#include <cmath>

namespace mpgc::opp {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

ValidityChecker::ValidityChecker(const Problem& pb, const ConstraintParams& c) : pb_(pb), c_(c) {
  fixed_ = pb.fixed ? pb.fixed : &none_;
  cos_turn_ = c.max_turn >= kPi ? -2.0 : std::cos(c.max_turn);
  dc2_ = c.colreg_distance * c.colreg_distance;
  inv_u_ = 1.0 / pb.speed;
  goal_any_heading_ = !std::isfinite(pb.goal.heading) || pb.goal.heading_tolerance >= kPi;
  start_fixed_d_ = c.safety_distance;
  if (c.escape_start) start_fixed_d_ = std::min(c.safety_distance, fixed_clearance(pb.start) * (1.0 - 1e-9));
}

double ValidityChecker::fixed_clearance(Vec2 p) const {
  double d = fixed_->nearest(p);
  if (pb_.charted) {
    const Bounds& r = *pb_.charted;
    d = std::min(d, std::max(0.0, std::min({p.x - r.min_x, r.max_x - p.x, p.y - r.min_y, r.max_y - p.y})));
  }
  return d;
}

bool ValidityChecker::goal_heading_ok(Vec2 seg) const {
  if (goal_any_heading_) return true;
  const double course = std::atan2(seg.y, seg.x);
  double d = std::fabs(std::remainder(course - pb_.goal.heading, 2.0 * kPi));
  return d <= pb_.goal.heading_tolerance;
}

ValidityChecker::Reject ValidityChecker::moving(Vec2 a, double ta, Vec2 b, double len, ColregLevel level,
                                                bool escape) const {
  if (pb_.targets.empty()) return kValid;
  const Vec2 vel = (pb_.speed / len) * (b - a);
  const double T = len * inv_u_;
  for (const Target& tg : pb_.targets) {
    const Vec2 y = tg.p + ta * tg.v;
    const Vec2 r0 = a - y;
    const double ds = c_.safety_distance + tg.margin;
    const double lim = escape ? std::min(ds * ds, norm2(r0) * (1.0 - 1e-9)) : ds * ds;
    if (geom::closest_approach(r0, vel - tg.v, T).dist2 < lim) return kTarget;  // eq. 3-4
    const bool pinned = tg.pinned.obligation != Obligation::kNone;
    // The first relaxation keeps the own ship's duties, rule 8(b)'s readily apparent action among
    // them; a stand-on target is then unconstrained (rule 17(b): it may act as best aids to avoid
    // collision).
    const Obligation o = tg.pinned.obligation;
    if (level == ColregLevel::kNone || (level == ColregLevel::kPinned && !is_duty(o)) ||
        (level == ColregLevel::kPinned17c && !is_duty(o) && o != Obligation::kCrossingStandOn))
      continue;
    // §5 at the leg's start and every colreg_spacing along it (a long leg must not jump over the
    // zone). A pinned obligation holds from the moment the risk of collision was found, at any
    // range: crossing ahead of a give-way target just outside d_COLREG is still crossing ahead.
    const PinnedLeg leg(vel, tg.pinned);
    for (double s = 0.0; s < len; s += c_.colreg_spacing) {
      const Vec2 xs = a + (s / len) * (b - a);
      const Vec2 ys = y + (s * inv_u_) * tg.v;
      if ((pinned || norm2(xs - ys) < dc2_) && !colreg_check_pinned(xs, ys, tg.v, leg, c_.colreg).compliant)
        return kColreg;
      if (pinned && (level == ColregLevel::kFull || is_duty(o)) && !colreg_check_apparent(xs, ys, tg.v, leg, c_.colreg))
        return kColreg;
    }
  }
  return kValid;
}

std::string ValidityChecker::check_path(const std::vector<Vec2>& path, bool colreg) const {
  return check_path(path, colreg ? ColregLevel::kFull : ColregLevel::kNone);
}

std::string ValidityChecker::check_path(const std::vector<Vec2>& path, ColregLevel level) const {
  if (path.size() < 2) return "path has fewer than 2 waypoints";
  Vec2 dir{std::cos(pb_.heading), std::sin(pb_.heading)};
  double len_acc = 0.0;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    const Vec2 a = path[i], b = path[i + 1];
    const Vec2 seg = b - a;
    const double len = norm(seg);
    const std::string leg = "leg " + std::to_string(i) + ": ";
    if (!(len > 0.0)) return leg + "zero length";
    if (!turn_ok(dir, seg, len, i == 0)) return leg + "turning angle exceeds max_turn (eq. 2)";
    const bool esc = i == 0 && c_.escape_start;
    // A path checked from its own first point: the escape distance is that point's.
    const double dfix = esc ? std::min(c_.safety_distance, fixed_clearance(a) * (1.0 - 1e-9)) : c_.safety_distance;
    if (!fixed_clear(a, b, dfix)) return leg + "closer than d_safety to a fixed obstacle or to unknown water beyond the chart";
    const auto r = moving(a, len_acc / pb_.speed, b, len, level, esc);
    if (r == kTarget) return leg + "closer than d_safety to a target (eq. 3-4)";
    if (r == kColreg) return leg + "not COLREG-compliant (§5)";
    dir = (1.0 / len) * seg;
    len_acc += len;
  }
  if (!goal_heading_ok(path.back() - path[path.size() - 2])) return "arrival heading outside the tolerance";
  return "";
}

}  // namespace mpgc::opp
