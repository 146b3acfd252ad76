#include "mpgc/opp/apf_vo.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/opp/colreg.hpp"
#include "mpgc/opp/validity.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::opp {

namespace {

Vec2 unit_of(double course) { return {std::cos(course), std::sin(course)}; }
double course_of(Vec2 d) { return geo::course_of(d.x, d.y); }
// Starboard of a direction in NED (x north, y east): 90 deg clockwise.
Vec2 starboard_of(Vec2 d) { return {-d.y, d.x}; }

// The distance below which a step may not come to the fixed obstacles: d_safety, or what the
// point already keeps when it is closer (escape_start: never closer than it is).
double keep_distance(const ValidityChecker& check, double clearance) {
  const double ds = check.constraints().safety_distance;
  return clearance >= ds ? ds : clearance * (1.0 - 1e-9);
}

}  // namespace

std::vector<Vec2> apf_path(const ValidityChecker& check, Vec2 from, Vec2 to, const ApfParams& p, int max_steps,
                           int* steps, std::string* why, Vec2 dir0) {
  const double ds = check.constraints().safety_distance;
  // A ship turns at most max_turn at a waypoint (eq. 2 of the interface): each step turns at
  // most that from the one before (from dir0 at the first), so the raw path is sailable.
  const double max_turn = check.turn_limited() ? check.constraints().max_turn : 4.0;
  Vec2 prev = norm(dir0) > 0.0 ? (1.0 / norm(dir0)) * dir0 : Vec2{0, 0};
  std::vector<Vec2> pts{from};
  Vec2 q = from;
  double best = norm(to - q);
  int since_best = 0;
  bool escaping = false;  // following the tangent force (eq. 9-10) until the goal is nearer
  double escape_from = 0.0;
  Vec2 escape_sign{0, 0};  // +1/-1 in x: which of the two tangents
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return std::vector<Vec2>{};
  };
  for (int k = 0; k < max_steps; ++k) {
    if (steps) ++*steps;
    const Vec2 dg = to - q;
    const double dist = norm(dg);
    const double cq = check.fixed_clearance(q);
    if (dist <= p.step && check.fixed_clear_from(q, cq, to, keep_distance(check, cq))) {
      pts.push_back(to);
      return pts;
    }
    // Eq. 1-2 with the forces normalised before they are added (§5.3, Fig. 15): the attraction
    // towards the goal, the repulsion along the gradient of the distance to the nearest obstacle
    // (-grad U_rep of eq. 1 points there) within rho0 beyond d_safety. With both of unit length the
    // gains lambda, mu of Table 4 cancel.
    const Vec2 att = (1.0 / dist) * dg;
    Vec2 rep{0, 0};
    if (std::isfinite(cq) && cq - ds < p.rho0) {
      const double h = 1.0;  // [m] central differences of the shared clearance
      const Vec2 g{(check.fixed_clearance(q + Vec2{h, 0}) - check.fixed_clearance(q - Vec2{h, 0})) / (2 * h),
                   (check.fixed_clearance(q + Vec2{0, h}) - check.fixed_clearance(q - Vec2{0, h})) / (2 * h)};
      if (norm(g) > 0.0) rep = (1.0 / norm(g)) * g;
    }
    Vec2 f = att + rep;
    const bool has_rep = norm2(rep) > 0.0;
    const bool opposed = has_rep && dot(rep, att) <= -std::cos(p.opposed_angle);  // eq. 9: F_rep = -F_att
    const bool stalled = since_best >= p.stall_steps;
    if (p.tangent_force && has_rep && (opposed || stalled || escaping)) {
      // Eq. 9-10: the extra force along a tangent of the obstacle from q. With no circle known (a
      // chart), the tangent of the obstacle's distance contour, perpendicular to the repulsion; the
      // one on the goal's side, starboard of the attraction when the goal is straight behind it.
      const Vec2 t1{-rep.y, rep.x};
      if (!escaping) {
        escaping = true;
        escape_from = best;
        const double side = dot(t1, att);
        escape_sign.x = std::fabs(side) > 1e-9 ? (side > 0 ? 1.0 : -1.0) : (dot(t1, starboard_of(att)) > 0 ? 1.0 : -1.0);
      }
      f = escape_sign.x * t1;
    } else if (!p.tangent_force && (norm(f) < 1e-9 || stalled)) {
      return fail("APF stuck in a local minimum at (" + fmt(q.x) + ", " + fmt(q.y) + ")");
    }
    if (!(norm(f) > 1e-12)) return fail("APF resultant force vanished at (" + fmt(q.x) + ", " + fmt(q.y) + ")");
    Vec2 dir = (1.0 / norm(f)) * f;
    if (norm2(prev) > 0.0 && max_turn < geo::kPi) {
      const double turn = std::atan2(cross(prev, dir), dot(prev, dir));
      if (std::fabs(turn) > max_turn) {
        const double a = std::copysign(max_turn * (1.0 - 1e-9), turn);
        dir = {prev.x * std::cos(a) - prev.y * std::sin(a), prev.x * std::sin(a) + prev.y * std::cos(a)};
      }
    }
    // A step that would cut into d_safety turns away from the obstacle until it is clear.
    Vec2 next = q + p.step * dir;
    const double dk = keep_distance(check, cq);
    for (int j = 1; j <= 8 && !check.fixed_clear_from(q, cq, next, dk); ++j) {
      const Vec2 d2 = dir + (0.25 * j) * rep;
      if (!(norm(d2) > 0.0)) continue;
      next = q + (p.step / norm(d2)) * d2;
      if (j == 8 && !check.fixed_clear_from(q, cq, next, dk))
        return fail("APF step within d_safety of a fixed obstacle at (" + fmt(q.x) + ", " + fmt(q.y) + ")");
    }
    prev = (1.0 / norm(next - q)) * (next - q);
    q = next;
    pts.push_back(q);
    const double d = norm(to - q);
    if (d < best - 1e-6) {
      best = d;
      since_best = 0;
    } else {
      ++since_best;
    }
    if (escaping && best < escape_from - p.step) {
      escaping = false;
      since_best = 0;
    }
  }
  return fail("APF did not reach the goal in " + std::to_string(max_steps) + " steps");
}

namespace {
void dp_split(const std::vector<Vec2>& pts, size_t i, size_t j, double eps,
              const std::function<bool(Vec2, Vec2)>& keep_whole, std::vector<char>& keep) {
  if (j <= i + 1) return;
  double dmax = -1.0;
  size_t imax = (i + j) / 2;
  for (size_t k = i + 1; k < j; ++k) {
    const double d = point_segment_dist2(pts[k], pts[i], pts[j]);
    if (d > dmax) {  // Algorithm 1 lines 4-8, keeping the farthest point
      dmax = d;
      imax = k;
    }
  }
  if (std::sqrt(dmax) > eps || (keep_whole && !keep_whole(pts[i], pts[j]))) {
    keep[imax] = 1;
    dp_split(pts, i, imax, eps, keep_whole, keep);
    dp_split(pts, imax, j, eps, keep_whole, keep);
  }
}
}  // namespace

namespace {
std::vector<char> dp_flags(const std::vector<Vec2>& pts, double epsilon, const std::function<bool(Vec2, Vec2)>& keep_whole) {
  std::vector<char> keep(pts.size(), 0);
  if (pts.empty()) return keep;
  keep.front() = keep.back() = 1;
  dp_split(pts, 0, pts.size() - 1, epsilon, keep_whole, keep);
  return keep;
}
}  // namespace

std::vector<Vec2> douglas_peucker(const std::vector<Vec2>& pts, double epsilon,
                                  const std::function<bool(Vec2, Vec2)>& keep_whole) {
  if (pts.size() <= 2) return pts;
  const std::vector<char> keep = dp_flags(pts, epsilon, keep_whole);
  std::vector<Vec2> out;
  for (size_t k = 0; k < pts.size(); ++k)
    if (keep[k]) out.push_back(pts[k]);
  return out;
}

namespace {
// Index of the target whose VO (time-thresholded, eq. 18) holds the own velocity `vel` at x, t:
// DCPA below the risk distance and 0 <= TCPA <= epsilon (eq. 11-14 by colreg::cpa); the one with the
// earliest TCPA, or -1.
int in_vo(const Problem& pb, const ConstraintParams& c, const VoParams& p, Vec2 x, double t, Vec2 vel) {
  int hit = -1;
  double first = std::numeric_limits<double>::infinity();
  const colreg::ShipKinematics own{x.x, x.y, vel.x, vel.y};
  for (size_t k = 0; k < pb.targets.size(); ++k) {
    const Target& tg = pb.targets[k];
    const Vec2 y = tg.p + t * tg.v;
    const colreg::Cpa a = colreg::cpa(own, {y.x, y.y, tg.v.x, tg.v.y});
    const double r = p.dcpa_factor * (c.safety_distance + tg.margin);
    if (a.dcpa < r && a.tcpa >= 0.0 && a.tcpa <= p.tcpa_threshold && a.tcpa < first) {
      first = a.tcpa;
      hit = static_cast<int>(k);
    }
  }
  return hit;
}
}  // namespace

VoDecision vo_decide(const Problem& pb, const ConstraintParams& c, const VoParams& p, Vec2 x, double t, double u,
                     double course0, int forced) {
  VoDecision d;
  d.target = forced >= 0 ? forced : in_vo(pb, c, p, x, t, u * unit_of(course0));
  d.risk = d.target >= 0;
  if (!d.risk) return d;
  const Target& tg = pb.targets[d.target];
  const Vec2 y = tg.p + t * tg.v, v = u * unit_of(course0);
  // The encounter: the obligation pinned for it (EncounterMemory); for a course the shared checker
  // refuses (forced), the encounter of its per-leg model (§5, eq. 16-18), which judged the course;
  // else the rule sectors of the project's colreg::assess (the risk is the VO's own, eq. 18). The
  // sectors alone saw TS3 of the seed 003 case, overtaken 5 km on the port beam, as crossing, stood
  // on, and sailed the refused course: every full-speed plan relaxed, the ship trailed at 25 %.
  const Obligation per_leg = forced >= 0 ? colreg_check(x, v, y, tg.v, c.colreg).situation : Obligation::kNone;
  d.situation = tg.pinned.obligation != Obligation::kNone ? tg.pinned.obligation
                : per_leg != Obligation::kNone
                    ? per_leg
                    : colreg::assess({x.x, x.y, v.x, v.y}, {y.x, y.y, tg.v.x, tg.v.y}, colreg::ColregParams{}).sector;
  // The reachable courses within max_change each side (constraint 2) outside every VO: the first
  // free one is C1 (eq. 19, the VO's edge on that side), the free courses beyond it the set VA.
  const int n = static_cast<int>(std::floor(p.max_change / p.resolution + 1e-9));
  double c1[2] = {NAN, NAN}, width[2] = {0, 0};
  for (int s = 0; s < 2; ++s) {
    const double sign = s == 0 ? 1.0 : -1.0;  // 0: starboard (clockwise), 1: port
    for (int i = 1; i <= n; ++i) {
      const double th = course0 + sign * i * p.resolution;
      if (in_vo(pb, c, p, x, t, u * unit_of(th)) >= 0) continue;
      if (std::isnan(c1[s])) c1[s] = th;
      width[s] += p.resolution;
    }
  }
  d.width_starboard = width[0];
  d.width_port = width[1];
  using E = colreg::EncounterType;
  int s = 0;
  if (!pb.colreg) {
    // COLREG not required (seed 000 §6): no rule picks the side or keeps a stand-on ship on her
    // course; the side whose VO edge C1 (eq. 19) is the smaller alteration, starboard when equal.
    const double inf = std::numeric_limits<double>::infinity();
    const double a0 = std::isnan(c1[0]) ? inf : std::fabs(geo::angle_diff(c1[0], course0));
    const double a1 = std::isnan(c1[1]) ? inf : std::fabs(geo::angle_diff(c1[1], course0));
    s = a1 < a0 ? 1 : 0;
  } else {
    switch (d.situation) {
      case E::kCrossingStandOn:
      case E::kOvertaken:
        return d;  // constraint (5): the stand-on ship keeps her course and speed
      case E::kOvertaking:
        s = width[0] >= width[1] ? 0 : 1;  // eq. 21
        break;
      default:
        s = 0;  // head-on (rule 14), crossing give-way (rule 15), and a risk outside the sectors
    }
  }
  const double sign = s == 0 ? 1.0 : -1.0;
  d.side = s == 0 ? VoSide::kStarboard : VoSide::kPort;
  const double c2 = course0 + sign * p.max_change;
  d.c1 = std::isnan(c1[s]) ? c2 : c1[s];
  d.course = geo::wrap_pi(0.5 * (d.c1 + c2));  // eq. 20
  d.c1 = geo::wrap_pi(d.c1);
  return d;
}

void ApfVo::declare(rt::ParamSet& ps) {
  ps.add("plan.apf.step", &apf_.step, 200.0, "m", 1.0, 1e5, "apf-vo: APF step (seed 003 Table 4)");
  ps.add("plan.apf.rho0", &apf_.rho0, 1000.0, "m", 0.0, 1e6,
         "apf-vo: range of the repulsive field beyond d_safety (eq. 1 rho_0)");
  ps.add("plan.apf.dp_epsilon", &apf_.dp_epsilon, 500.0, "m", 0.0, 1e6,
         "apf-vo: Douglas-Peucker threshold (Algorithm 1, Table 4)");
  ps.add("plan.apf.tangent_force", &apf_.tangent_force, true,
         "apf-vo: the extra tangent force that escapes local minima (eq. 9-10); false: typical APF");
  ps.add("plan.apf.opposed_angle", &apf_.opposed_angle, geo::deg2rad(5.0), "rad", 0.0, geo::deg2rad(90.0),
         "apf-vo: repulsion within this of the reversed attraction counts as opposed (eq. 9)");
  ps.add("plan.apf.stall_steps", &apf_.stall_steps, 25, "-", 1, 100000,
         "apf-vo: steps without getting nearer the goal that count as a local minimum");
  ps.add("plan.vo.tcpa_threshold", &vo_.tcpa_threshold, 900.0, "s", 1.0, 1e5,
         "apf-vo: time threshold epsilon of the VO set (§4.3, eq. 18)");
  ps.add("plan.vo.dcpa_factor", &vo_.dcpa_factor, 1.2, "-", 1.0, 10.0,
         "apf-vo: DCPA below this x (d_safety + target margin) is a risk");
  ps.add("plan.vo.max_change", &vo_.max_change, geo::deg2rad(90.0), "rad", 0.08, 1.5708,
         "apf-vo: feasible course change each side (§4.3 constraint 2)");
  ps.add("plan.vo.resolution", &vo_.resolution, geo::deg2rad(0.5), "rad", geo::deg2rad(0.05), geo::deg2rad(5.0),
         "apf-vo: course grid of the VO sets");
  ps.add("plan.vo.extend", &vo_.extend, 60.0, "s", 1.0, 3600.0,
         "apf-vo: an avoidance leg whose return to the route is not valid yet is held this much longer");
  ps.add("plan.vo.max_manoeuvres", &vo_.max_manoeuvres, 20, "-", 1, 1000, "apf-vo: avoidance legs in one plan");
  ps.add("plan.vo.checker_trigger", &vo_.checker_trigger, true,
         "apf-vo: also manoeuvre where the course held fails the shared COLREG check (false: the VO set alone)");
}

Result ApfVo::solve(const Request& rq, const Hooks& hooks) {
  Result res;
  const Problem& pb = rq.problem;
  const double t0 = hooks.elapsed ? hooks.elapsed() : 0.0;
  auto done = [&](Result r) {
    r.stats.planning_time = hooks.elapsed ? hooks.elapsed() - t0 : 0.0;
    return r;
  };
  try {
    rq.constraints.validate();
    rq.objective.validate();
    rq.budget.validate();
  } catch (const std::exception& e) {
    res.status = Status::kInvalidInput;
    res.reason = e.what();
    return done(res);
  }
  if (std::string why = check_problem(pb, rq.constraints); !why.empty()) {
    res.status = Status::kInvalidInput;
    res.reason = why;
    return done(res);
  }
  const ConstraintParams& c = rq.constraints;
  const ValidityChecker check(pb, c);
  const Objective objective(pb, rq.objective);
  const double u = pb.speed;
  const ColregLevel level = pb.colreg ? ColregLevel::kFull : ColregLevel::kNone;
  int steps = 0;
  uint64_t checks = 0;

  // The global path (§4.2): APF, then Douglas-Peucker with the chord of every kept span clear of
  // the fixed obstacles (a compressed leg must not cut a corner into d_safety).
  // A kept point where the compressed path turns more than max_turn gets the farthest raw points of
  // its two spans back (the raw steps themselves turn less).
  auto global = [&](Vec2 from, Vec2 dir0, std::string* why) {
    const std::vector<Vec2> raw =
        apf_path(check, from, pb.goal.p, apf_, std::max(1, rq.budget.max_iterations - steps), &steps, why, dir0);
    if (raw.size() <= 2) return raw;
    const double dk = keep_distance(check, check.fixed_clearance(from));
    const std::function<bool(Vec2, Vec2)> clear = [&](Vec2 a, Vec2 b) {
      ++checks;
      return check.fixed_clear(a, b, dk);
    };
    std::vector<char> keep = dp_flags(raw, apf_.dp_epsilon, clear);
    for (bool changed = true; changed;) {
      changed = false;
      std::vector<size_t> k;
      for (size_t i = 0; i < raw.size(); ++i)
        if (keep[i]) k.push_back(i);
      Vec2 in = dir0;
      for (size_t m = 0; m + 1 < k.size(); ++m) {
        const Vec2 seg = raw[k[m + 1]] - raw[k[m]];
        const bool ok = norm2(in) == 0.0 || check.turn_ok((1.0 / norm(in)) * in, seg, norm(seg), m == 0);
        if (!ok) {
          // Split the span into this waypoint and the one out of it.
          for (size_t a : {m == 0 ? m : m - 1, m}) {
            if (k[a + 1] > k[a] + 1) {
              size_t far = k[a] + 1;
              double dmax = -1.0;
              for (size_t i = k[a] + 1; i < k[a + 1]; ++i) {
                const double d = point_segment_dist2(raw[i], raw[k[a]], raw[k[a + 1]]);
                if (d > dmax) {
                  dmax = d;
                  far = i;
                }
              }
              keep[far] = 1;
              changed = true;
              break;
            }
          }
          if (changed) break;
        }
        in = seg;
      }
    }
    // Points the refinement kept on a straight stretch (a turn below 0.5 deg) add nothing.
    std::vector<Vec2> out;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (!keep[i]) continue;
      if (out.size() >= 2) {
        const Vec2 x = out.back() - out[out.size() - 2], y = raw[i] - out.back();
        if (std::fabs(std::atan2(cross(x, y), dot(x, y))) < 0.0087 && clear(out[out.size() - 2], raw[i])) {
          out.back() = raw[i];
          continue;
        }
      }
      out.push_back(raw[i]);
    }
    return out;
  };
  std::string why;
  std::vector<Vec2> g = global(pb.start, unit_of(pb.heading), &why);
  if (g.empty()) {
    res.status = Status::kNoPath;
    res.reason = why;
    res.stats.iterations = steps;
    return done(res);
  }

  // The local path (§4.3): sail the global path; where the own velocity first falls in a target's
  // VO set (stage 1) turn to the avoidance course of stage 2, hold it until that target's TCPA is 0
  // (stage 3), then follow a new global path from there.
  std::vector<Vec2> pts{pb.start};
  Vec2 pos = pb.start, dir_in = unit_of(pb.heading);
  double t = 0.0;
  size_t idx = 1;
  int manoeuvres = 0;
  const double scan = std::max(1.0, 0.25 * c.safety_distance / u);  // [s] stage 1 is checked this often
  std::vector<std::string> notes;
  while (idx < g.size()) {
    if (hooks.stop && hooks.stop()) break;
    const Vec2 b = g[idx];
    const Vec2 seg = b - pos;
    const double len = norm(seg);
    if (!(len > 1e-6)) {
      ++idx;
      continue;
    }
    const double course = course_of(seg);
    // Sails the whole leg to b along the global path.
    auto sail_leg = [&] {
      pts.push_back(b);
      dir_in = (1.0 / len) * seg;
      pos = b;
      t += len / u;
      ++idx;
    };
    double s_hit = -1.0;
    VoDecision d;
    if (manoeuvres < vo_.max_manoeuvres) {
      for (double s = 0.0; s < len; s += u * scan) {
        const Vec2 x = pos + (s / len) * seg;
        d = vo_decide(pb, c, vo_, x, t + s / u, u, course);
        if (d.risk && d.side != VoSide::kNone) {
          s_hit = s;
          break;
        }
        if (!vo_.checker_trigger || level == ColregLevel::kNone) continue;
        // The piece of the course held up to the next check, by the shared checker.
        const double l = std::min(u * scan, len - s);
        const Vec2 xe = pos + ((s + l) / len) * seg;
        ++checks;
        if (check.moving(x, t + s / u, xe, l, level) != ValidityChecker::kColreg) continue;
        int who = -1;
        for (size_t k = 0; k < pb.targets.size() && who < 0; ++k) {
          Problem one = pb;
          one.targets = {pb.targets[k]};
          if (ValidityChecker(one, c).moving(x, t + s / u, xe, l, level) == ValidityChecker::kColreg)
            who = static_cast<int>(k);
        }
        if (who < 0) continue;
        d = vo_decide(pb, c, vo_, x, t + s / u, u, course, who);
        if (d.side != VoSide::kNone) {
          s_hit = s;
          break;
        }
      }
    }
    if (s_hit < 0.0) {
      sail_leg();
      continue;
    }
    const Vec2 p = pos + (s_hit / len) * seg;
    const double tp = t + s_hit / u;
    if (s_hit > 0.0) dir_in = (1.0 / len) * seg;
    // Candidate avoidance courses: the centre of the chosen set first (eq. 20), then the others of
    // that set by distance from it; each within the turn limit (eq. 2 of seed 000, the interface's).
    const double sign = d.side == VoSide::kStarboard ? 1.0 : -1.0;
    std::vector<double> cands;
    for (double a = 0.0; a <= vo_.max_change + 1e-9; a += vo_.resolution) {
      const double th = course + sign * a;
      if (sign * geo::angle_diff(th, d.c1) < -1e-9) continue;  // inside the VO, short of C1
      cands.push_back(th);
    }
    std::stable_sort(cands.begin(), cands.end(), [&](double x, double y) {
      return std::fabs(geo::angle_diff(x, d.course)) < std::fabs(geo::angle_diff(y, d.course));
    });
    const Target& tg = pb.targets[d.target];
    // The fixed clearance of p, and of each leg end e below, once: the nests below ask for it
    // per course, per hold and per rejoin waypoint (seed 003: most of apf-vo's time).
    const double cp = check.fixed_clearance(p), kp = keep_distance(check, cp);
    bool placed = false;
    Vec2 best_end{};
    double best_t = 0.0;
    size_t rejoin = 0;
    bool have_fallback = false;
    // COLREG first; relaxed as §6 of seed 000 only when no course of the set is valid with it.
    for (const ColregLevel lv : {level, ColregLevel::kPinned17c, ColregLevel::kPinned, ColregLevel::kNone}) {
      if (have_fallback || (lv != ColregLevel::kNone && level == ColregLevel::kNone)) break;
      for (double th : cands) {
        const Vec2 dir = unit_of(th);
        const Vec2 vel = u * dir;
        if (!check.turn_ok(dir_in, dir, 1.0, pts.size() == 1 && s_hit == 0.0)) continue;
        const Vec2 y = tg.p + tp * tg.v;
        const double tcpa = colreg::cpa({p.x, p.y, vel.x, vel.y}, {y.x, y.y, tg.v.x, tg.v.y}).tcpa;
        double hold = std::max(tcpa, scan);
        // The avoidance leg, then its return: held longer while the return is not yet valid.
        for (int ext = 0; ext <= 2.0 * vo_.tcpa_threshold / vo_.extend; ++ext, hold += vo_.extend) {
          const Vec2 e = p + (u * hold) * dir;
          ++checks;
          if (check.moving(p, tp, e, u * hold, lv, c.escape_start && pts.size() == 1) != ValidityChecker::kValid ||
              !check.fixed_clear_from(p, cp, e, kp))
            break;
          if (!have_fallback) {
            have_fallback = true;
            best_end = e;
            best_t = tp + hold;
          }
          // Back to the global path: the first of its remaining waypoints reachable by a valid leg.
          bool have_ce = false;  // e's fixed clearance and keep distance, at the first leg that needs them
          double ce = 0.0, ke = 0.0;
          for (size_t j = idx; j < g.size() && !placed; ++j) {
            const Vec2 r = g[j] - e;
            const double rl = norm(r);
            if (!(rl > 1e-6)) continue;
            ++checks;
            if (!check.turn_ok(dir, r, rl, false) || check.moving(e, tp + hold, g[j], rl, lv) != ValidityChecker::kValid)
              continue;
            if (!have_ce) have_ce = true, ce = check.fixed_clearance(e), ke = keep_distance(check, ce);
            if (check.fixed_clear_from(e, ce, g[j], ke)) {
              best_end = e;
              best_t = tp + hold;
              rejoin = j;
              placed = true;
            }
          }
          if (placed) break;
        }
        if (placed) break;
      }
    }
    ++manoeuvres;
    if (!have_fallback) {
      notes.push_back("no valid avoidance course for target " + std::to_string(tg.id));
      // Sail on along the global path: the checker's verdict below says what that costs.
      sail_leg();
      continue;
    }
    if (s_hit > 0.0) pts.push_back(p);
    pts.push_back(best_end);
    dir_in = (1.0 / norm(best_end - p)) * (best_end - p);
    pos = best_end;
    t = best_t;
    if (placed) {
      idx = rejoin;
    } else {
      // No rejoin within reach: a new global path from the avoidance leg's end.
      std::string w;
      g = global(pos, dir_in, &w);
      if (g.empty()) {
        res.status = Status::kNoPath;
        res.reason = "after the avoidance of target " + std::to_string(tg.id) + ": " + w;
        res.stats.iterations = steps;
        return done(res);
      }
      idx = 1;
    }
    notes.push_back(std::string("target ") + std::to_string(tg.id) + " " + colreg::to_string(d.situation) + ": " +
                    (d.side == VoSide::kStarboard ? "starboard" : "port") + " to " +
                    fmt(geo::rad2deg(geo::wrap_2pi(course_of(pts.back() - pts[pts.size() - 2])))) + " deg");
  }
  if (pts.size() < 2 || norm(pts.back() - pb.goal.p) > 1e-6) {
    res.status = Status::kNoPath;
    res.reason = "stopped before the goal";
    res.stats.iterations = steps;
    return done(res);
  }

  res = finish(pb, pts, false, check, objective);
  res.stats.iterations = res.stats.iterations_compliant = steps;
  res.stats.nodes = static_cast<int>(pts.size());
  res.stats.first_solution_iteration = steps;
  res.stats.edge_checks = checks;
  std::string reason;
  for (const std::string& n : notes) reason += (reason.empty() ? "" : "; ") + n;
  if (pb.colreg && !res.colreg_compliant) {
    const std::string safe = check.check_path(pts, false);
    if (!safe.empty()) {
      res.status = Status::kNoPath;
      res.reason = "apf-vo path unsafe: " + safe + (reason.empty() ? "" : " (" + reason + ")");
      res.path.clear();
      return done(res);
    }
    res.status = Status::kRelaxed;
    res.relaxed = true;
    // Which target the violation is for (the checker's verdict names the leg only).
    std::string whom;
    for (const Target& tg : pb.targets) {
      Problem one = pb;
      one.targets = {tg};
      if (!ValidityChecker(one, c).check_path(pts, true).empty()) whom += (whom.empty() ? " (target " : ", ") + std::to_string(tg.id);
    }
    if (!whom.empty()) whom += ")";
    reason = "not COLREG-compliant: " + check.check_path(pts, true) + whom + (reason.empty() ? "" : "; " + reason);
  } else if (!pb.colreg) {
    const std::string safe = check.check_path(pts, false);
    if (!safe.empty()) {
      res.status = Status::kNoPath;
      res.reason = "apf-vo path unsafe: " + safe;
      res.path.clear();
      return done(res);
    }
  }
  res.reason = reason;
  return done(res);
}

}  // namespace mpgc::opp
