#include "mpgc/scenario_runner/evaluation.hpp"

#include "mpgc/geom/fixed_obstacle_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace mpgc::scenario_runner {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxSamples = 50'000'000;  // far beyond any run; guards against garbage sizes

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument("RunRecord: " + what); }

bool finite(const ShipState& s) {
  return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.heading) && std::isfinite(s.cog) &&
         std::isfinite(s.sog);
}

void check_track(const ShipTrack& tr, const std::string& name, std::size_t n) {
  if (!(std::isfinite(tr.length) && tr.length > 0.0)) bad(name + ".length must be finite and > 0");
  if (tr.states.size() != n)
    bad(name + ".states has " + std::to_string(tr.states.size()) + " samples, t has " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (!finite(tr.states[i])) bad(name + ".states[" + std::to_string(i) + "] is not finite");
}

// --- geometry -----------------------------------------------------------------------------------

using geom::Vec2;

// The scenario's own fixed obstacles in the common fixed-obstacle map (each polygon its own
// even-odd feature, circles of radius 0 as its points), and the circles of radius > 0 measured
// directly. Exact: 0 inside land or on a segment that touches it.
class ObstacleIndex {
 public:
  explicit ObstacleIndex(const FixedObstacles& o) {
    std::vector<geom::Polygon> rings;
    for (std::size_t k = 0; k < o.polygons.size(); ++k) {
      std::vector<Vec2> ring = o.polygons[k].vertices;
      if (ring.size() > 3 && ring.front() == ring.back()) ring.pop_back();  // the closing vertex is optional
      rings.push_back({static_cast<std::uint32_t>(k + 1), std::move(ring)});
    }
    std::vector<Vec2> points;
    for (const auto& c : o.circles) (c.radius > 0.0 ? discs_.push_back(c) : points.push_back(c.centre));
    map_ = geom::FixedObstacleMap(std::move(points), std::move(rings));
  }

  // Least distance from the segment [a, b] (a point when a == b) to any obstacle.
  double distance(Vec2 a, Vec2 b) const {
    double best = a == b ? map_.clearance(a) : map_.segment_clearance(a, b);
    for (const auto& c : discs_) best = std::min(best, std::max(0.0, geom::point_segment_distance(c.centre, a, b) - c.radius));
    return best;
  }

 private:
  geom::FixedObstacleMap map_;
  std::vector<Circle> discs_;
};

// Walks the own ship's samples in order: the distance at each sample and the least distance on
// the segment sailed from the previous one.
class ObstacleWalker {
 public:
  explicit ObstacleWalker(const ObstacleIndex& index) : index_(index) {}
  std::pair<double, double> step(Vec2 p) {
    const double at_p = index_.distance(p, p);
    const double seg = have_ ? index_.distance(last_, p) : at_p;
    have_ = true, last_ = p;
    return {at_p, seg};
  }

 private:
  const ObstacleIndex& index_;
  bool have_ = false;
  Vec2 last_;
};

Vec2 pos(const ShipState& s) { return {s.x, s.y}; }

// Closest approach of a target to the own ship between two samples, both moving linearly (exact
// for straight segments): the relative position goes from r to r + dv over a unit interval; tau is
// the fraction of the interval where it happens.
geom::Approach approach(const ShipState& o0, const ShipState& o1, const ShipState& t0, const ShipState& t1) {
  const Vec2 r = pos(t0) - pos(o0);
  return geom::closest_approach(r, (pos(t1) - pos(o1)) - r, 1.0);
}

// Course over ground, or heading when (nearly) stopped, where the course is meaningless.
double course(const ShipState& s) { return s.sog > 0.1 ? s.cog : s.heading; }

colreg::ShipKinematics kin(const ShipState& s) {
  return colreg::ShipKinematics::from_course(s.x, s.y, s.cog, s.sog, s.heading);
}

// Linear-interpolated percentile (q in [0, 1]) of a sorted, non-empty vector.
double percentile(const std::vector<double>& sorted, double q) {
  const double pos_ = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos_));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos_ - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

// Time within [t0, t1] where a linearly interpolated distance d0 -> d1 is below `limit`.
double time_below(double t0, double t1, double d0, double d1, double limit) {
  const bool b0 = d0 < limit, b1 = d1 < limit;
  if (b0 && b1) return t1 - t0;
  if (!b0 && !b1) return 0.0;
  const double f = (limit - d0) / (d1 - d0);  // crossing fraction; d0 != d1 here
  return b0 ? f * (t1 - t0) : (1.0 - f) * (t1 - t0);
}

Verdict verdict(bool ok) { return ok ? Verdict::kPass : Verdict::kFail; }

}  // namespace

// --- names ----------------------------------------------------------------------------------------

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::kNotApplicable: return "n/a";
    case Verdict::kPass: return "pass";
    case Verdict::kFail: return "fail";
  }
  return "?";
}
const char* to_string(Side s) {
  switch (s) {
    case Side::kNone: return "none";
    case Side::kPort: return "port";
    case Side::kStarboard: return "starboard";
  }
  return "?";
}
std::vector<std::uint32_t> Metrics::near_miss_targets() const {
  std::vector<std::uint32_t> ids;
  for (const TargetDistance& td : min_distance_targets)
    if (td.near_miss) ids.push_back(td.target_id);
  return ids;
}
std::vector<std::uint32_t> Metrics::likely_collision_targets() const {
  std::vector<std::uint32_t> ids;
  for (const TargetDistance& td : min_distance_targets)
    if (td.likely_collision) ids.push_back(td.target_id);
  return ids;
}

// --- validation -----------------------------------------------------------------------------------

void RunRecord::validate() const {
  const std::size_t n = t.size();
  if (n == 0) bad("t is empty");
  if (n > kMaxSamples) bad("t has " + std::to_string(n) + " samples (more than " + std::to_string(kMaxSamples) + ")");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t[i])) bad("t[" + std::to_string(i) + "] is not finite");
    if (i > 0 && !(t[i] > t[i - 1])) bad("t[" + std::to_string(i) + "] is not after t[" + std::to_string(i - 1) + "]");
  }
  check_track(own, "own", n);
  std::set<std::uint32_t> ids;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    const std::string name = "targets[" + std::to_string(k) + "] (id " + std::to_string(targets[k].id) + ")";
    check_track(targets[k], name, n);
    if (!ids.insert(targets[k].id).second) bad(name + ": duplicate target id");
  }
  for (std::size_t k = 0; k < plans.size(); ++k) {
    const PlanRecord& p = plans[k];
    const std::string name = "plans[" + std::to_string(k) + "] (plan_id " + std::to_string(p.plan_id) + ")";
    if (!std::isfinite(p.t)) bad(name + ".t is not finite");
    if (k > 0 && p.t < plans[k - 1].t) bad(name + ".t is before the previous plan's");
    if (!(std::isfinite(p.planning_time) && p.planning_time >= 0.0)) bad(name + ".planning_time must be finite and >= 0");
    if (p.status != PlanStatus::kNoPath && p.waypoints.empty()) bad(name + " has no waypoints");
    for (std::size_t i = 0; i < p.waypoints.size(); ++i) {
      const auto& w = p.waypoints[i];
      if (!std::isfinite(w.x) || !std::isfinite(w.y) || std::isnan(w.t))
        bad(name + ".waypoints[" + std::to_string(i) + "] is not finite");
    }
  }
  for (std::size_t k = 0; k < guidance.size(); ++k)
    if (!std::isfinite(guidance[k].t) || (k > 0 && guidance[k].t < guidance[k - 1].t))
      bad("guidance[" + std::to_string(k) + "].t is not finite or out of order");
  for (std::size_t k = 0; k < obstacles.polygons.size(); ++k) {
    const auto& v = obstacles.polygons[k].vertices;
    if (v.size() < 3) bad("obstacles.polygons[" + std::to_string(k) + "] has fewer than 3 vertices");
    for (const auto& q : v)
      if (!std::isfinite(q.x) || !std::isfinite(q.y)) bad("obstacles.polygons[" + std::to_string(k) + "] has a non-finite vertex");
  }
  for (std::size_t k = 0; k < obstacles.circles.size(); ++k) {
    const auto& c = obstacles.circles[k];
    if (!std::isfinite(c.centre.x) || !std::isfinite(c.centre.y) || !(std::isfinite(c.radius) && c.radius >= 0.0))
      bad("obstacles.circles[" + std::to_string(k) + "] is not finite or has a negative radius");
  }
  if (!(std::isfinite(safety_distance) && safety_distance > 0.0)) bad("safety_distance must be finite and > 0");
  if (!std::isfinite(goal.x) || !std::isfinite(goal.y)) bad("goal is not finite");
  if (!(std::isfinite(goal.radius) && goal.radius > 0.0)) bad("goal.radius must be finite and > 0");
}

EvaluationParams EvaluationParams::scaled_to(double length, double reference_length) {
  if (!(std::isfinite(length) && length > 0.0))
    throw std::invalid_argument("EvaluationParams::scaled_to: length must be finite and > 0");
  if (!(std::isfinite(reference_length) && reference_length > 0.0))
    throw std::invalid_argument("EvaluationParams::scaled_to: reference_length must be finite and > 0");
  EvaluationParams p;
  const double s = length / reference_length;
  p.reference_length = reference_length;
  p.scale = s;
  for (double* d : {&p.r_colregs_2_max, &p.r_colregs_3_max, &p.r_colregs_4_max, &p.r_pref, &p.r_min_cpa, &p.r_nm,
                    &p.r_col_cpa})
    *d *= s;
  p.epsilon_d_course /= s;  // same speeds, s times the turning radius: s times slower turns
  p.colreg = default_colreg(p.r_colregs_2_max, p.r_pref);
  return p;
}

void EvaluationParams::validate() const {
  auto pos_ = [](double v, const char* name) {
    if (!(std::isfinite(v) && v > 0.0))
      throw std::invalid_argument(std::string("EvaluationParams.") + name + " must be finite and > 0");
  };
  pos_(reference_length, "reference_length");
  pos_(scale, "scale");
  pos_(r_colregs_2_max, "r_colregs_2_max");
  pos_(r_colregs_3_max, "r_colregs_3_max");
  pos_(r_colregs_4_max, "r_colregs_4_max");
  pos_(r_pref, "r_pref");
  pos_(r_min_cpa, "r_min_cpa");
  pos_(r_nm, "r_nm");
  pos_(r_col_cpa, "r_col_cpa");
  pos_(epsilon_d_course, "epsilon_d_course");
  pos_(delta_course_md, "delta_course_md");
  pos_(delta_speed_md, "delta_speed_md");
  pos_(delta_course_app, "delta_course_app");
  pos_(delta_speed_reduction_app, "delta_speed_reduction_app");
  pos_(theta_sm_lim, "theta_sm_lim");
  if (!(r_colregs_4_max <= r_colregs_3_max && r_colregs_3_max <= r_colregs_2_max))
    throw std::invalid_argument("EvaluationParams: stage ranges must satisfy r_colregs_4_max <= r_colregs_3_max <= r_colregs_2_max");
  if (!(r_col_cpa <= r_nm))
    throw std::invalid_argument("EvaluationParams: r_col_cpa must be <= r_nm (a likely collision is a near miss too)");
  colreg.validate();
}

void PassCriteria::validate() const {
  if (!(std::isfinite(safety_tolerance) && safety_tolerance >= 0.0 && safety_tolerance < 1.0))
    throw std::invalid_argument("PassCriteria.safety_tolerance must be in [0, 1)");
  if (!(std::isfinite(max_safety_violation_s) && max_safety_violation_s >= 0.0))
    throw std::invalid_argument("PassCriteria.max_safety_violation_s must be finite and >= 0");
  if (!(std::isfinite(min_ship_distance) && min_ship_distance >= 0.0))
    throw std::invalid_argument("PassCriteria.min_ship_distance must be finite and >= 0");
}

// --- geometry API -----------------------------------------------------------------------------------

double distance_to_polygon(Vec2 p, const Polygon& poly) {
  if (poly.vertices.size() < 3) throw std::invalid_argument("distance_to_polygon: fewer than 3 vertices");
  FixedObstacles one;
  one.polygons = {poly};
  return ObstacleIndex(one).distance(p, p);
}

double distance_to_obstacles(Vec2 p, const FixedObstacles& obs) {
  return ObstacleIndex(obs).distance(p, p);
}

std::size_t add_point_obstacles(FixedObstacles& obs, const std::vector<Vec2>& points, double tolerance) {
  std::vector<Vec2> keep;
  {
    FixedObstacles polygons;
    polygons.polygons = obs.polygons;
    const ObstacleIndex index(polygons);
    for (Vec2 p : points) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw std::invalid_argument("add_point_obstacles: point is not finite");
      if (index.distance(p, p) > tolerance) keep.push_back(p);
    }
  }
  for (Vec2 p : keep) obs.circles.push_back({p, 0.0});
  return keep.size();
}

double distance_to_path(Vec2 p, const std::vector<PlannedWaypoint>& wps) {
  if (wps.empty()) throw std::invalid_argument("distance_to_path: no waypoints");
  double best = geom::norm(p - Vec2{wps[0].x, wps[0].y});
  for (std::size_t i = 1; i < wps.size(); ++i)
    best = std::min(best, geom::point_segment_distance(p, {wps[i - 1].x, wps[i - 1].y}, {wps[i].x, wps[i].y}));
  return best;
}

std::vector<int> active_plan_index(const RunRecord& run) {
  std::vector<int> idx(run.t.size(), -1);
  int active = -1;
  std::size_t k = 0;
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    for (; k < run.plans.size() && run.plans[k].t <= run.t[i]; ++k)
      if (run.plans[k].status != PlanStatus::kNoPath) active = static_cast<int>(k);
    idx[i] = active;
  }
  return idx;
}

DistanceSeries distance_series(const RunRecord& run) {
  const std::size_t n = run.t.size();
  DistanceSeries d;
  d.closest.assign(n, kInf);
  d.target.resize(run.targets.size());
  for (std::size_t k = 0; k < run.targets.size(); ++k) {
    auto& v = d.target[k];
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      v[i] = geom::norm(pos(run.own.states[i]) - pos(run.targets[k].states[i]));
      d.closest[i] = std::min(d.closest[i], v[i]);
    }
  }
  if (!run.obstacles.empty()) {
    const ObstacleIndex index(run.obstacles);
    ObstacleWalker walk(index);
    d.fixed.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      d.fixed[i] = walk.step(pos(run.own.states[i])).first;
      d.closest[i] = std::min(d.closest[i], d.fixed[i]);
    }
  }
  return d;
}

// --- COLREG -----------------------------------------------------------------------------------------

namespace {

// A course manoeuvre of the own ship: a change of at least delta_course_md within the detector's
// window (delta_course_md / epsilon_d_course) begins one, and it lasts while the course keeps
// changing that way by at least half as much per window; a turn the other way is a new one.
struct Episode {
  std::size_t from = 0;      // sample before the change (the window's first): the course held until then
  std::size_t detected = 0;  // sample at which the change reached delta_course_md
  std::size_t to = 0;        // last sample of the manoeuvre
  Side side = Side::kNone;
  double change = 0.0;       // [rad] largest course change from the course at `from`, up to `to`
};

std::vector<Episode> course_episodes(const RunRecord& run, const EvaluationParams& p) {
  const auto& t = run.t;
  const auto& own = run.own.states;
  const double window = p.manoeuvre_window();
  std::vector<Episode> out;
  bool in = false;
  std::size_t back = 0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    while (t[i] - t[back] > window) ++back;
    const double step = geo::angle_diff(course(own[i]), course(own[back]));
    const Side side = step > 0.0 ? Side::kStarboard : Side::kPort;
    if (std::fabs(step) >= p.delta_course_md && (!in || side != out.back().side)) {
      out.push_back({back, i, i, side});
      in = true;
    } else if (in && std::fabs(step) >= 0.5 * p.delta_course_md && side == out.back().side) {
      out.back().to = i;
    } else if (in && std::fabs(step) < 0.5 * p.delta_course_md) {
      in = false;
    }
  }
  for (Episode& ep : out) {
    const double chi = course(own[ep.from]);
    for (std::size_t i = ep.from; i <= ep.to; ++i) ep.change = std::max(ep.change, std::fabs(geo::angle_diff(course(own[i]), chi)));
  }
  return out;
}

// Which of the own ship's manoeuvres were made for this encounter, and what they amounted to. A
// manoeuvre is made for every encounter with a risk of collision when it began (closing, predicted
// CPA below r_pref from the states before the change), within [start, CPA]: a turn made for one
// ship is not judged for another that was no risk then (DNV 40, 46 were judged by such turns).
// The encounter's manoeuvre is the first of those that reached theta_sm_lim (smaller ones are
// wobbles, not an alteration to avoid collision); its course changes are measured from the course
// held before it, up to the CPA.
// A manoeuvre is made for a target when it was detected during the encounter, up to the closest
// approach, and began while that target was a risk of collision.
bool made_for(const Episode& ep, const std::vector<ShipState>& own, const std::vector<ShipState>& tg, std::size_t start,
              std::size_t kcpa, const EvaluationParams& p) {
  if (ep.detected < start || ep.detected > kcpa) return false;
  const colreg::Cpa c = colreg::cpa(kin(own[ep.from]), kin(tg[ep.from]));
  return c.tcpa > 0.0 && c.dcpa < p.colreg.cpa_risk;
}

void attribute(EncounterResult& e, const RunRecord& run, const ShipTrack& tgt, std::size_t start, std::size_t kcpa,
               const std::vector<Episode>& episodes, const EvaluationParams& p) {
  const auto& t = run.t;
  const auto& own = run.own.states;
  const auto& tg = tgt.states;
  for (const Episode& ep : episodes) {
    if (!made_for(ep, own, tg, start, kcpa, p)) continue;
    ++e.manoeuvres;
    if (ep.change < p.theta_sm_lim || !std::isnan(e.t_manoeuvre)) continue;
    const double chi = course(own[ep.from]);
    e.t_manoeuvre = t[ep.detected];
    e.manoeuvre_side = ep.side;
    for (std::size_t i = ep.from; i <= kcpa; ++i) {
      const double dchi = geo::angle_diff(course(own[i]), chi);
      e.max_starboard_change = std::max(e.max_starboard_change, dchi);
      e.max_port_change = std::max(e.max_port_change, -dchi);
    }
  }
}

// `act_from`: the time from which the own ship may act anyway because another stand-on encounter
// reached its stage 3 (evaluate_encounters): the hold ends there at the latest.
EncounterResult evaluate_one(const RunRecord& run, const ShipTrack& tgt, const std::vector<Episode>& episodes,
                             const EvaluationParams& p, double act_from = std::numeric_limits<double>::infinity()) {
  const auto& t = run.t;
  const auto& own = run.own.states;
  const auto& tg = tgt.states;
  const std::size_t n = t.size();
  EncounterResult e;
  e.target_id = tgt.id;

  std::vector<double> range(n);
  for (std::size_t i = 0; i < n; ++i) range[i] = geom::norm(pos(own[i]) - pos(tg[i]));

  // Closest approach over [a, b] (sample indices), refined between samples.
  auto closest = [&](std::size_t a, std::size_t b) {
    double best = range[a], tbest = t[a];
    for (std::size_t i = a; i < b; ++i) {
      const geom::Approach c = approach(own[i], own[i + 1], tg[i], tg[i + 1]);
      const double d = std::sqrt(c.dist2);
      if (d < best) best = d, tbest = t[i] + c.tau * (t[i + 1] - t[i]);
    }
    return std::pair<double, double>{best, tbest};
  };

  std::size_t start = n;
  for (std::size_t i = 0; i < n; ++i)
    if (range[i] < p.r_colregs_2_max) {
      start = i;
      break;
    }
  if (start == n) {  // never close: no encounter; report the closest approach anyway
    std::tie(e.cpa, e.t_cpa) = closest(0, n - 1);
    return e;
  }
  // The rules of Part B, Section II bind from when risk of collision exists (rules 7, 13-17): the
  // encounter is classified at the first sample within range that has it. A ship met while it
  // lay stopped, or while the own ship was still turning onto the leg that meets it, becomes an
  // encounter when the risk appears (Annapolis: the motor vessel left its berth at 455 s).
  for (std::size_t i = start; i < n; ++i)
    if (range[i] < p.r_colregs_2_max && colreg::assess(kin(own[i]), kin(tg[i]), p.colreg).type != colreg::EncounterType::kNone) {
      start = i;
      break;
    }
  e.encountered = true;
  e.t_start = t[start];
  e.range_start = range[start];
  const colreg::Assessment a = colreg::assess(kin(own[start]), kin(tg[start]), p.colreg);
  e.situation = a.type;
  e.role = a.role;
  e.beta_start = a.beta;
  e.alpha_start = a.alpha;
  e.dcpa_start = a.cpa.dcpa;

  // The encounter lasts until the range opens beyond the start range again after the closest
  // approach (or the run ends).
  std::size_t end = n - 1, kmin = start;
  for (std::size_t i = start; i < n; ++i) {
    if (range[i] < range[kmin]) kmin = i;
    if (i > kmin && range[i] >= p.r_colregs_2_max) {
      end = i;
      break;
    }
  }
  std::tie(e.cpa, e.t_cpa) = closest(start, end);
  std::size_t kcpa = kmin;  // sample nearest the refined CPA
  for (std::size_t i = start; i <= end; ++i)
    if (std::fabs(t[i] - e.t_cpa) < std::fabs(t[kcpa] - e.t_cpa)) kcpa = i;

  // Passing side: where the target was, seen from the own bow, at the closest approach.
  if (e.cpa > 1e-6) {
    const ShipState& o = own[kcpa];
    const double beta = geo::wrap_pi(geo::course_of(tg[kcpa].x - o.x, tg[kcpa].y - o.y) - o.heading);
    e.passing_side = beta > 0.0 ? Side::kStarboard : (beta < 0.0 ? Side::kPort : Side::kNone);
  }

  // Bow-crossing distance: the own ship's along-track position in the target's frame at the first
  // time it crosses the target's course line (lateral offset changes sign).
  for (std::size_t i = start; i < end && std::isnan(e.bow_crossing); ++i) {
    auto frame = [&](std::size_t j) {
      const double dx = own[j].x - tg[j].x, dy = own[j].y - tg[j].y, h = tg[j].heading;
      return std::pair<double, double>{std::cos(h) * dx + std::sin(h) * dy, -std::sin(h) * dx + std::cos(h) * dy};
    };
    const auto [al0, la0] = frame(i);
    const auto [al1, la1] = frame(i + 1);
    if (la0 != 0.0 && (la0 * la1 < 0.0 || la1 == 0.0)) {
      const double f = la0 / (la0 - la1);
      e.bow_crossing = al0 + f * (al1 - al0);
    }
  }

  // The own ship's manoeuvres judged for this encounter: only those made for it (attribute()).
  const double u0 = own[start].sog;
  for (std::size_t i = start; i <= kcpa; ++i)
    if (u0 > 0.1) e.max_speed_reduction = std::max(e.max_speed_reduction, (u0 - own[i].sog) / u0);
  const double chi0 = course(own[start]);
  attribute(e, run, tgt, start, kcpa, episodes, p);

  using colreg::EncounterType;
  if (e.situation == EncounterType::kHeadOn || e.situation == EncounterType::kCrossingGiveWay ||
      e.situation == EncounterType::kOvertaking)
    e.readily_apparent = verdict(std::max(e.max_starboard_change, e.max_port_change) >= p.delta_course_app ||
                                 e.max_speed_reduction >= p.delta_speed_reduction_app);
  switch (e.situation) {
    case EncounterType::kHeadOn:
      // Rule 14: alter course to starboard so that each passes on the port side of the other.
      e.turned_starboard = verdict(e.manoeuvre_side == Side::kStarboard && e.max_starboard_change >= p.theta_sm_lim);
      e.passed_port_to_port = verdict(e.passing_side == Side::kPort);
      break;
    case EncounterType::kCrossingGiveWay:
      // Rules 15/16: early substantial action, to starboard, and do not cross ahead.
      e.turned_starboard = verdict(e.manoeuvre_side == Side::kStarboard && e.max_starboard_change >= p.theta_sm_lim);
      e.not_crossed_ahead = verdict(!(e.bow_crossing > 0.0));
      break;
    case EncounterType::kOvertaking:
      // Rule 13: keep out of the way of the overtaken ship.
      e.kept_clear = verdict(e.cpa >= p.r_min_cpa);
      break;
    case EncounterType::kCrossingStandOn:
    case EncounterType::kOvertaken: {
      // Rule 17(a)(i): keep course and speed until the stand-on ship may act (stage 3): the
      // target within r_colregs_3_max and the CPA nearer in time than the own ship takes to sail
      // that range. A ship overtaking slowly from close astern is not yet a reason to act.
      auto may_act = [&](std::size_t i) {
        if (range[i] >= p.r_colregs_3_max) return false;
        return !(u0 > 0.1) || colreg::cpa(kin(own[i]), kin(tg[i])).tcpa < p.r_colregs_3_max / u0;
      };
      // Rule 17(c) binds the action taken under 17(a)(ii) "to avoid collision with" this ship, the
      // action it may take from stage 3: the first manoeuvre made for it detected there must not
      // alter course to port while the ship is "on her own port side". A turn made while it was
      // still beyond stage 3 (for another ship, 10 km off) is no action under 17(a)(ii) for it; a
      // turn while holding is judged by the hold; a port turn once it has crossed ahead to the
      // starboard bow turns away from it (DNV 48).
      if (e.situation == EncounterType::kCrossingStandOn) {
        bool to_port = false;
        for (const Episode& ep : episodes) {
          if (!made_for(ep, own, tg, start, kcpa, p) || ep.change < p.theta_sm_lim || !may_act(ep.detected)) continue;
          // "On her own port side" when she alters: where the course last was the one held (within
          // half delta_course_md, the detector's own "no change"), not at the detector's window
          // start, a whole window earlier (59 s at the DNV suite's scale: DNV 48's port turn began
          // with the crossing ship 6 deg on the starboard bow, 0.15 deg to port a window before).
          std::size_t began = ep.from;
          for (std::size_t i = ep.from; i <= ep.detected; ++i)
            if (std::fabs(geo::angle_diff(course(own[i]), course(own[ep.from]))) < 0.5 * p.delta_course_md) began = i;
          const Vec2 d = pos(tg[began]) - pos(own[began]);
          const bool on_port_side = geo::angle_diff(std::atan2(d.y, d.x), course(own[began])) < 0.0;
          double port = 0.0;
          for (std::size_t i = ep.from; i <= kcpa; ++i)
            port = std::max(port, -geo::angle_diff(course(own[i]), course(own[ep.from])));
          to_port = on_port_side && ep.side == Side::kPort && port >= p.theta_sm_lim;
          break;
        }
        e.not_turned_to_port = verdict(!to_port);
      }
      e.tcpa_start = colreg::cpa(kin(own[start]), kin(tg[start])).tcpa;
      if (may_act(start)) {  // may act from the start (17(a)(ii)): nothing to hold; judged as when
        e.kept_clear = verdict(e.cpa >= p.r_min_cpa);  // acting: a safe distance (8(d)), 17(c)
        e.t_hold_end = t[start];  // its hold ends at once: so does that of another it overlaps
        break;
      }
      bool held = true;
      std::size_t i = start;
      if (!(t[start] < act_from)) {  // acting for another stand-on target from the start
        e.conflicting_obligation = true;
        break;
      }
      // ... and until the CPA at the latest: past it the other no longer has to keep out of the way
      // (a give-way ship that acted may leave the range above stage 3 to the end).
      for (; i <= end && !may_act(i) && t[i] < act_from && t[i] < e.t_cpa; ++i) {
        if (std::fabs(geo::angle_diff(course(own[i]), chi0)) > p.delta_course_md) held = false;
        if (u0 > 0.1 && std::fabs(own[i].sog - u0) / u0 > p.delta_speed_md) held = false;
      }
      e.t_hold_end = t[std::min(i, end)];
      e.held_course_and_speed = verdict(held);
      break;
    }
    case EncounterType::kNone: break;
  }
  return e;
}

void set_compliance(EncounterResult& e) {
  e.compliant = true;
  for (Verdict v : {e.turned_starboard, e.passed_port_to_port, e.not_crossed_ahead, e.kept_clear,
                    e.held_course_and_speed, e.not_turned_to_port, e.readily_apparent})
    if (v == Verdict::kFail) e.compliant = false;
}

std::string describe_failures(const EncounterResult& e) {
  std::ostringstream s;
  s << "target " << e.target_id << " (" << colreg::to_string(e.situation) << "):";
  auto add = [&](const char* name, Verdict v) {
    if (v == Verdict::kFail) s << " " << name;
  };
  add("did not turn to starboard;", e.turned_starboard);
  add("did not pass port to port;", e.passed_port_to_port);
  add("crossed ahead;", e.not_crossed_ahead);
  add("did not keep clear;", e.kept_clear);
  add("did not hold course and speed;", e.held_course_and_speed);
  add("turned to port for a ship on its port side (17(c));", e.not_turned_to_port);
  add("no readily apparent action (rule 8(b));", e.readily_apparent);
  std::string r = s.str();
  if (!r.empty() && r.back() == ';') r.pop_back();
  return r;
}

// Why the rule this encounter falls under could not be judged ("" when it was).
std::string unjudged(const EncounterResult& e, const EvaluationParams& p) {
  std::ostringstream s;
  s.precision(0);
  s << std::fixed;
  if (!e.encountered) {
    s << "never within r_colregs_2_max = " << p.r_colregs_2_max << " m";
  } else if (e.situation == colreg::EncounterType::kNone) {
    s << "no risk of collision within r_colregs_2_max at any time (predicted CPA " << e.dcpa_start
      << " m when the range first fell below it, r_pref " << p.r_pref << " m)";
  }
  return s.str();
}

}  // namespace

std::vector<EncounterResult> evaluate_encounters(const RunRecord& run, const EvaluationParams& p) {
  run.validate();
  p.validate();
  std::vector<EncounterResult> out;
  out.reserve(run.targets.size());
  const std::vector<Episode> episodes = course_episodes(run, p);
  for (const auto& tgt : run.targets) out.push_back(evaluate_one(run, tgt, episodes, p));
  // A stand-on ship that may act for one stand-on target (its stage 3 reached) cannot go on holding
  // course for another whose encounter overlaps: that one's hold ends there too.
  auto stands_on = [](const EncounterResult& e) { return e.role == colreg::Role::kStandOn && std::isfinite(e.t_hold_end); };
  std::vector<double> act_from(out.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t j = 0; j < out.size(); ++j)
      if (i != j && stands_on(out[i]) && stands_on(out[j]) && out[j].t_hold_end < out[i].t_hold_end &&
          out[j].t_cpa >= out[i].t_start)
        act_from[i] = std::min(act_from[i], out[j].t_hold_end);
  for (std::size_t i = 0; i < out.size(); ++i)
    if (std::isfinite(act_from[i])) out[i] = evaluate_one(run, run.targets[i], episodes, p, act_from[i]);
  // A ship that must give way to one target cannot stand on for another at the same time.
  for (auto& so : out) {
    if (so.conflicting_obligation) so.kept_clear = verdict(so.cpa >= p.r_min_cpa);  // acting for another stand-on
    if (so.held_course_and_speed == Verdict::kNotApplicable) continue;
    for (const auto& gw : out) {
      const bool gives_way = gw.role == colreg::Role::kGiveWay || gw.role == colreg::Role::kBothGiveWay;
      if (&gw != &so && gives_way && gw.t_start <= so.t_hold_end && gw.t_cpa >= so.t_start) {
        so.conflicting_obligation = true;
        so.held_course_and_speed = Verdict::kNotApplicable;
        so.kept_clear = verdict(so.cpa >= p.r_min_cpa);  // rule 8(d): still passed at a safe distance
      }
    }
  }
  for (auto& e : out) set_compliance(e);
  return out;
}

// --- everything ------------------------------------------------------------------------------------

Metrics evaluate(const RunRecord& run, const EvaluationParams& p, const PassCriteria& criteria) {
  criteria.validate();
  Metrics m;
  m.encounters = evaluate_encounters(run, p);  // validates run and p
  m.scale = p.scale;
  const auto& t = run.t;
  const auto& own = run.own.states;
  const std::size_t n = t.size();
  m.sim_s = t.back() - t.front();
  m.safety_distance = run.safety_distance;
  m.r_nm = p.r_nm;
  m.r_col_cpa = p.r_col_cpa;

  // Goal: first entry into the arrival circle, on the segment between samples.
  const Vec2 g{run.goal.x, run.goal.y};
  std::size_t last = n - 1;  // last sample that counts for path length and tracking
  if (geom::norm(pos(own[0]) - g) <= run.goal.radius) {
    m.goal_reached = true, m.t_goal = t[0], last = 0;
  } else {
    for (std::size_t i = 0; i + 1 < n && !m.goal_reached; ++i) {
      const Vec2 a = pos(own[i]), b = pos(own[i + 1]);
      if (geom::point_segment_distance(g, a, b) > run.goal.radius) continue;
      // Solve |a + u (b - a) - g| = r for the smaller root u in [0, 1].
      const Vec2 ab = b - a, ga = a - g;
      const double A = geom::norm2(ab), B = 2.0 * geom::dot(ga, ab),
                   C = geom::norm2(ga) - run.goal.radius * run.goal.radius;
      const double disc = std::max(0.0, B * B - 4.0 * A * C);
      const double u = A > 0.0 ? std::clamp((-B - std::sqrt(disc)) / (2.0 * A), 0.0, 1.0) : 0.0;
      m.goal_reached = true;
      m.t_goal = t[i] + u * (t[i + 1] - t[i]);
      last = i + 1;
    }
  }
  m.straight_line = geom::norm(pos(own[0]) - g);
  for (std::size_t i = 0; i < last; ++i) m.path_length += geom::norm(pos(own[i]) - pos(own[i + 1]));

  // Distances: exact minimum between samples; violation time from the sampled closest distance.
  m.min_distance = kInf;
  for (std::size_t k = 0; k < run.targets.size(); ++k) {
    const auto& tg = run.targets[k].states;
    TargetDistance td{run.targets[k].id, geom::norm(pos(own[0]) - pos(tg[0])), t[0]};
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const geom::Approach a = approach(own[i], own[i + 1], tg[i], tg[i + 1]);
      const double d = std::sqrt(a.dist2);
      if (d < td.min_distance) td.min_distance = d, td.t_min = t[i] + a.tau * (t[i + 1] - t[i]);
    }
    td.near_miss = td.min_distance < p.r_nm;
    td.likely_collision = td.min_distance < p.r_col_cpa;
    m.min_distance = std::min(m.min_distance, td.min_distance);
    m.min_distance_targets.push_back(td);
  }
  if (!run.obstacles.empty()) {
    const ObstacleIndex index(run.obstacles);
    ObstacleWalker walk(index);
    m.min_distance_fixed = kInf;
    for (std::size_t i = 0; i < n; ++i) m.min_distance_fixed = std::min(m.min_distance_fixed, walk.step(pos(own[i])).second);
    m.min_distance = std::min(m.min_distance, m.min_distance_fixed);
  }
  if (!std::isfinite(m.min_distance)) m.min_distance = kNaN;  // nothing to be close to
  const DistanceSeries ds = distance_series(run);
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (std::isfinite(ds.closest[i]))
      m.safety_violation_s += time_below(t[i], t[i + 1], ds.closest[i], ds.closest[i + 1], run.safety_distance);

  // Planning statistics.
  m.replans = static_cast<int>(run.plans.size());
  std::vector<double> ms;
  for (const auto& pl : run.plans) {
    ms.push_back(pl.planning_time * 1e3);
    if (pl.status == PlanStatus::kRelaxed) ++m.relaxed_plans;
    if (pl.status == PlanStatus::kNoPath) ++m.no_path_plans;
  }
  if (!ms.empty()) {
    std::sort(ms.begin(), ms.end());
    m.planning = {percentile(ms, 0.5), percentile(ms, 0.95), ms.back()};
  }

  // Tracking: distance to the path active at each sample, up to the goal arrival.
  const std::vector<int> active = active_plan_index(run);
  double sum2 = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i <= last; ++i) {
    if (active[i] < 0) continue;
    const double d = distance_to_path(pos(own[i]), run.plans[static_cast<std::size_t>(active[i])].waypoints);
    sum2 += d * d;
    ++count;
  }
  if (count > 0) m.tracking_rmse = std::sqrt(sum2 / static_cast<double>(count));

  // Pass criteria.
  auto fmt = [](double v) {
    std::ostringstream s;
    s.precision(1);
    s << std::fixed << v;
    return s.str();
  };
  if (criteria.goal_required && !m.goal_reached) {
    double closest = kInf;
    for (const auto& s : own) closest = std::min(closest, geom::norm(pos(s) - g));
    m.failures.push_back("goal not reached (closest " + fmt(closest) + " m, arrival radius " + fmt(run.goal.radius) + " m)");
  }
  const double limit = run.safety_distance * (1.0 - criteria.safety_tolerance);
  if (std::isfinite(m.min_distance) && m.min_distance < limit)
    m.failures.push_back("min distance " + fmt(m.min_distance) + " m < " + fmt(limit) + " m (d_safety " +
                         fmt(run.safety_distance) + " m, tolerance " + fmt(100.0 * criteria.safety_tolerance) + " %)");
  // A likely collision is always a failure of a run that must keep d_safety, and every run must
  // keep limit > 0: one closer than the limit fails already, this line says it was a collision.
  // Closer than r_col_cpa but not than the limit (a small d_safety) is reported, not failed: the
  // scenario's requirements do not ask for more.
  for (const TargetDistance& td : m.min_distance_targets)
    if (td.likely_collision && td.min_distance < limit)
      m.failures.push_back("target " + std::to_string(td.target_id) + ": likely collision (least distance " +
                           fmt(td.min_distance) + " m < r_col_cpa " + fmt(p.r_col_cpa) + " m)");
  if (criteria.min_ship_distance > 0.0)
    for (const TargetDistance& td : m.min_distance_targets)
      if (td.min_distance < criteria.min_ship_distance)
        m.failures.push_back("target " + std::to_string(td.target_id) + ": least distance " + fmt(td.min_distance) +
                             " m < the required " + fmt(criteria.min_ship_distance) + " m");
  if (m.safety_violation_s > criteria.max_safety_violation_s)
    m.failures.push_back("below d_safety for " + fmt(m.safety_violation_s) + " s (allowed " +
                         fmt(criteria.max_safety_violation_s) + " s)");
  if (criteria.all_encounters_compliant)
    for (const auto& e : m.encounters)
      if (!e.compliant) m.failures.push_back("COLREG: " + describe_failures(e));
  for (const auto& req : criteria.required) {
    const auto it = std::find_if(m.encounters.begin(), m.encounters.end(),
                                 [&](const EncounterResult& e) { return e.target_id == req.target_id; });
    if (it == m.encounters.end())
      throw std::invalid_argument("PassCriteria.required: no target with id " + std::to_string(req.target_id));
    if (req.check_situation && it->situation != req.situation)
      m.failures.push_back("target " + std::to_string(req.target_id) + ": situation " +
                           colreg::to_string(it->situation) + ", expected " + colreg::to_string(req.situation));
    // A verdict the scenario requires but that cannot be judged fails, with the reason.
    const std::string why = unjudged(*it, p);
    const std::string who = "target " + std::to_string(req.target_id) + ": ";
    if (!why.empty())
      m.failures.push_back(who + "COLREG verdict required (compliant: " + (req.compliant ? "true" : "false") +
                           ") but not judged: " + why);
    else if (req.compliant && !it->compliant && !criteria.all_encounters_compliant)
      m.failures.push_back("COLREG: " + describe_failures(*it));
    else if (!req.compliant && it->compliant)
      m.failures.push_back(who + "a COLREG violation is required (compliant: false, a run without COLREG), but every "
                           "verdict passed (" + colreg::to_string(it->situation) + ")");
  }
  m.faults = run.faults;
  for (const auto& f : run.faults) {
    if (!std::isfinite(f.t))
      m.failures.push_back("fault '" + f.what + "' planned at " + fmt(f.t_planned) + " s never happened (the run ended first)");
    else if (f.needs_recovery && !std::isfinite(f.t_recovered))
      m.failures.push_back("fault '" + f.what + "' at " + fmt(f.t) + " s: " + f.component + " never came back");
  }
  m.passed = m.failures.empty();
  return m;
}

}  // namespace mpgc::scenario_runner
