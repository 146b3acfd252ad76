#include "mpgc/opp/colreg.hpp"

#include <cmath>

namespace mpgc::opp {

ColregCheck colreg_check(Vec2 x0, Vec2 v, Vec2 y0, Vec2 w, const ColregParams& p) {
  ColregCheck out;
  const double vn = norm(v), wn = norm(w);
  if (vn < p.min_speed || wn < p.min_speed) return out;  // a drifting target has no route (§5.2)
  const double c = dot(v, w) / (vn * wn);
  const Vec2 d = y0 - x0;
  // §5.5 head-on: routes within theta_h of reciprocal -> the target must be on the port side (eq. 19).
  if (c < -std::cos(p.theta_head_on)) {
    out.situation = ColregSituation::kHeadOn;
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
  if (c > std::cos(p.theta_overtaking)) {  // eq. 16
    out.situation = ColregSituation::kOvertaking;
    out.compliant = dt > 0.0;  // the overtaken route must be crossed behind the other vessel
    return out;
  }
  if (out.situation != ColregSituation::kHeadOn) out.situation = ColregSituation::kCrossing;
  out.compliant = out.compliant && (vxw * dt < 0.0);  // eq. 18 (eq. 17 x eq. 15)
  return out;
}

}  // namespace mpgc::opp
