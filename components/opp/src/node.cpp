#include "mpgc/opp/node.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <future>
#include <limits>
#include <optional>

#include "mpgc/geo/angles.hpp"
#include "mpgc/opp/registry.hpp"
#include "mpgc/opp/validity.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::opp {

void declare(rt::ParamSet& ps, NodeParams& p, std::vector<std::unique_ptr<Planner>>& planners) {
  ConstraintParams& c = p.constraints;
  ObjectiveParams& o = p.objective;
  ps.add("plan.planner", &p.planner, "rrtstar", "the planner (registry.hpp)", planner_names());
  ps.add("replan.period", &p.replan.period, 15.0, "s", 0.1, 3600.0, "fixed re-planning period (seed 000: 15 s)");
  ps.add("replan.track_threshold", &p.replan.track_threshold, 300.0, "m", 1.0, 1e5,
         "re-plan at once when a target's predicted position moved this far from the last plan's prediction");
  ps.add("replan.track_horizon", &p.replan.track_horizon, 300.0, "s", 0.0, 3600.0, "prediction horizon of that comparison");
  ps.add("replan.min_interval", &p.replan.min_interval, 2.0, "s", 0.0, 600.0, "event-triggered plans no closer than this");
  ps.add("replan.check_period", &p.check_period, 0.5, "s", 0.01, 60.0, "how often the conditions are checked");
  ps.add("plan.time_budget", &p.budget.time_budget, 0.5, "s", 0.001, 60.0, "wall-time budget of one plan");
  ps.add("plan.max_iterations", &p.budget.max_iterations, 20000, "-", 1, 2000000, "iterations per plan");
  ps.add("plan.seed", &p.seed, 1, "-", 0, 2147483647, "base seed (plan k uses seed + k)");
  ps.add("plan.max_turn", &c.max_turn, geo::deg2rad(60.0), "rad", 0.01, 3.15, "turning-angle limit (eq. 2)");
  ps.add("plan.safety_distance", &c.safety_distance, 1000.0, "m", 0.0, 1e5, "d_safety when the goal does not set one (eq. 4)");
  ps.add("plan.colreg_distance", &c.colreg_distance, 3000.0, "m", 0.0, 1e6, "d_COLREG (§5), at least d_safety");
  ps.add("plan.theta_overtaking", &c.colreg.overtaking_course_angle, geo::deg2rad(22.5), "rad", 0.01, 1.5,
         "theta_o of eq. 16: overtaking when the two velocities are within it of each other");
  ps.add("plan.theta_head_on", &c.colreg.head_on_course_angle, geo::deg2rad(22.5), "rad", 0.01, 1.5,
         "theta_h of §5.5: head-on when one velocity is within it of the other's reciprocal");
  ps.add("plan.port_tolerance", &c.colreg.port_tolerance, geo::deg2rad(5.0), "rad", 0.0, 1.5,
         "a pinned head-on / give-way leg may point this far to port of the course at the encounter's start");
  ps.add("plan.apparent_turn", &c.colreg.apparent_turn, geo::deg2rad(30.0), "rad", 0.0, 3.1,
         "rule 8(b): while closing a pinned give-way / head-on / overtaking target, hold the pinned course or alter "
         "by at least this (0: any alteration)");
  ps.add("plan.head_on_turn", &c.colreg.head_on_turn, geo::deg2rad(10.0), "rad", 0.0, 1.5,
         "rule 14(a): within d_COLREG of a pinned head-on target, a leg that would pass it within plan.encounter_cpa x "
         "d_safety is altered to starboard by at least this");
  ps.add("plan.apparent_slowdown", &c.colreg.apparent_slowdown, 0.5, "-", 0.0, 0.99,
         "rule 8(b): a leg this much slower than the speed an encounter began at is a readily apparent action (0: never)");
  ps.add("plan.apparent_turn_margin", &c.colreg.apparent_turn_margin, geo::deg2rad(2.0), "rad", 0.0, 1.5,
         "a readily apparent leg turns this far beyond plan.apparent_turn (the course sailed approaches a leg's only "
         "asymptotically, and the evaluation measures the course sailed)");
  ps.add("plan.apparent_slowdown_margin", &c.colreg.apparent_slowdown_margin, 0.05, "-", 0.0, 0.5,
         "... and a slow one is this much slower than plan.apparent_slowdown asks");
  ps.add("plan.escape_start", &c.escape_start, true,
         "start within d_safety (target moved in): still plan; the first leg may not get closer (else INVALID_INPUT)");
  ps.add("plan.gamma_s", &o.gamma_s, 500.0, "m/rad^2", 0.0, 1e9, "weight of the steering cost (eq. 6)");
  ps.add("plan.gamma_f", &o.gamma_f, 1e5, "m^2", 0.0, 1e12, "weight of the fixed-obstacle margin cost (eq. 7)");
  ps.add("plan.gamma_m", &o.gamma_m, 1e5, "m^2", 0.0, 1e12, "weight of the target margin cost (eq. 8)");
  ps.add("plan.gamma_l", &o.gamma_l, 1.0, "-", 0.0, 1e6, "weight of the path length (eq. 9)");
  ps.add("plan.bounds_margin", &p.bounds_margin, 3000.0, "m", 0.0, 1e6, "sampling box margin around start and goal");
  ps.add("plan.arrival_radius", &p.arrival_radius, 100.0, "m", 0.0, 1e5, "stop planning this close to the goal");
  ps.add("plan.default_speed", &p.default_speed, 5.0, "m/s", 0.1, 50.0, "planned speed when no other is known");
  ps.add("plan.max_state_age", &p.max_state_age, 5.0, "s", 0.1, 600.0, "older own states are not planned from");
  nav::declare_params(ps, &p.jumps);
  ps.add("plan.max_obstacle_age", &p.max_obstacle_age, 10.0, "s", 0.1, 600.0,
         "moving obstacles older than this (obstacle_manager publishes every 0.5 s) are not extrapolated: no plan "
         "until fresh ones come (guidance keeps the last plan, then slows to steerage speed)");
  ps.add("plan.target_sigmas", &p.target_sigmas, 2.0, "-", 0.0, 10.0,
         "a target is kept d_safety + this many position sigmas away (obstacles/moving position_std, which grows "
         "while the target is not measured)");
  ps.add("plan.rule17c_range", &p.rule17c_range, 5.0, "-", 0.1, 1e6,
         "x d_safety: rule 17(c) (no turn to port for a crossing ship on the port side that the own ship stands on "
         "for) binds within this range, where the own ship may act for that ship (beyond the evaluation's stage 3, "
         "4 r_min_cpa); farther off a turn made for another ship is not action for it");
  ps.add("plan.rule17c_lead", &p.rule17c_lead, 0.4, "-", 0.0, 10.0,
         "x d_safety: a port leg is judged for rule 17(c) as begun this far earlier on the course held; at least the "
         "guidance's circle of acceptance, where it turns for the next leg (0.25 d_safety in the paper suite, 800 m / "
         "3200 m; up to 0.33 in the DNV suite, 305 m / 926 m)");
  ps.add("plan.tracking_margin", &p.tracking_margin, 0.02, "-", 0.0, 1.0,
         "x d_safety kept beyond d_safety from every target: a plan that grazes d_safety is lost by the ship "
         "following it (cross-track error of metres), so the margin is planned, not left to chance");
  ps.add("plan.require_chart", &p.require_chart, true,
         "no plan until obstacles/fixed gave the charted region (false: open water everywhere while none came)");
  ps.add("plan.warm_start", &p.warm_start, true, "re-use the previous path of the same goal");
  ps.add("plan.pin_encounters", &p.pin_encounters, true,
         "fix each target's COLREG obligation when the risk of collision appears (encounters.hpp); false: per leg (§5)");
  ps.add("plan.encounter_cpa", &p.encounter_cpa, 2.0, "-", 0.0, 10.0,
         "risk of collision: CPA inside this many d_safety (about the NTNU evaluator's r_pref / r_min_cpa, 1.9)");
  ps.add("plan.encounter_tcpa", &p.encounter_tcpa, 0.0, "s", 0.0, 86400.0,
         "a risk of collision within this time pins the encounter (0: the straight-line time to the goal)");
  ps.add("plan.speed_steps", &p.speed_steps, 3, "-", 0, 20,
         "no COLREG-compliant path at the planned speed: try this many lower speeds, evenly down to "
         "plan.min_speed_fraction (seed 000 §2: reduce speed when steering alone is not sufficient); 0: never");
  ps.add("plan.speed_detour", &p.speed_detour, 1.3, "-", 1.0, 100.0,
         "a compliant plan longer than this x the straight line to the goal is compared with slower ones by "
         "arrival time");
  ps.add("plan.min_speed_fraction", &p.min_speed_fraction, 0.25, "-", 0.05, 1.0,
         "the lowest speed tried, and the emergency leg's, as a fraction of the planned speed");
  ps.add("plan.emergency", &p.emergency, true,
         "no path at any speed: publish the emergency leg (rule 17(b): starboard first, reduced speed) as RELAXED");
  ps.add("plan.stand_on_time", &p.stand_on_time, 3.0, "-", 0.0, 100.0,
         "... and until the CPA is nearer than the time to sail this many d_safety at the planned speed (the "
         "evaluation: 4 r_min_cpa; a TCPA estimate is less sure than a range, so the margin is wider)");
  ps.add("plan.stand_on_steady", &p.stand_on_steady, 60.0, "s", 0.0, 3600.0,
         "a stand-on hold's end re-estimated within this of the previous plan's is kept (noisy TCPA of a slow "
         "overtaker); 0: re-estimated every plan");
  ps.add("plan.stand_on_range", &p.stand_on_range, 3.5, "-", 0.0, 100.0,
         "rule 17(a): hold course and speed for a target the own ship stands on for until it is this many d_safety "
         "away (the evaluation lets a stand-on ship act from 4 r_min_cpa); 0: no hold");
  ps.add("encounter.abaft_beam", &p.sector_abaft_beam, geo::deg2rad(22.5), "rad", 0.01, 1.5,
         "rule 13 sector of pinned and reported encounters: overtaking from more than this abaft the beam");
  ps.add("encounter.head_on", &p.sector_head_on, geo::deg2rad(22.5), "rad", 0.01, 1.5,
         "rule 14 sector of pinned and reported encounters: each ship within this of the other's bow");
  ps.add("memory.file", &p.memory_file, "",
         "file that keeps the goal, plan id, warm-start path and pinned COLREG obligations across a restart "
         "(read at start, rewritten after every plan; \"\" = start blind)");
  ps.add("plan.latency_per_iteration", &p.latency_per_iteration, 0.0, "s", 0.0, 1.0,
         "on simulated time, a plan takes effect iterations x this after the state it was planned from (guidance "
         "follows the previous plan meanwhile, seed 000 §6); 25e-6 is the paper's 0.5 s for 20000 iterations; "
         "0 = at once");
  planners.clear();
  for (const std::string& name : planner_names()) {
    planners.push_back(make_planner(name));
    planners.back()->declare(ps);
  }
}

std::vector<Target> targets_at(const std::vector<TrackReport>& tracks, double dt, double sigmas) {
  std::vector<Target> out;
  out.reserve(tracks.size());
  for (const TrackReport& t : tracks) {
    Target g{t.id, {t.p.x + t.v.x * dt, t.p.y + t.v.y * dt}, t.v, {}, 0.0};
    if (std::isfinite(t.position_std) && t.position_std > 0.0) g.margin = sigmas * t.position_std;
    out.push_back(g);
  }
  return out;
}

Setup build_setup(const NodeParams& p, const OwnReport& own, const GoalSpec& goal, std::vector<Target> targets,
                  const ChartView& chart, uint32_t plan_index) {
  Setup s;
  Problem& pb = s.problem;
  // The own ship at the planning time, dead-reckoned over the report's age.
  const double sog = std::isfinite(own.sog) ? own.sog : 0.0;
  const double cog = std::isfinite(own.cog) ? own.cog : own.heading;
  const double age = std::max(0.0, own.age);
  pb.start = {own.p.x + sog * std::cos(cog) * age, own.p.y + sog * std::sin(cog) * age};
  pb.heading = own.heading;
  pb.speed = goal.cruise_speed > 0 ? goal.cruise_speed : (sog > 0.5 ? sog : p.default_speed);
  pb.goal.p = goal.p;
  pb.goal.heading = goal.heading;
  pb.goal.heading_tolerance = std::isfinite(goal.heading) ? goal.heading_tolerance : geo::kPi;
  s.arrived = norm(pb.goal.p - pb.start) < p.arrival_radius;
  const double m = p.bounds_margin;
  pb.bounds = {std::min(pb.start.x, pb.goal.p.x) - m, std::min(pb.start.y, pb.goal.p.y) - m,
               std::max(pb.start.x, pb.goal.p.x) + m, std::max(pb.start.y, pb.goal.p.y) + m};
  pb.fixed = chart.obstacles;
  pb.charted = chart.region;
  if (chart.region) pb.bounds = pb.bounds.intersect(*chart.region);  // nothing to sample beyond it
  pb.targets = std::move(targets);
  pb.colreg = goal.colreg;
  s.constraints = p.constraints;
  if (goal.safety_distance > 0) s.constraints.safety_distance = goal.safety_distance;
  s.constraints.colreg_distance = std::max(s.constraints.colreg_distance, s.constraints.safety_distance);
  for (Target& t : pb.targets) t.margin += p.tracking_margin * s.constraints.safety_distance;
  s.constraints.colreg.port_turn_range = p.rule17c_range * s.constraints.safety_distance;
  s.constraints.colreg.risk_cpa = p.encounter_cpa * s.constraints.safety_distance;
  s.constraints.colreg.port_turn_lead = p.rule17c_lead * s.constraints.safety_distance;
  s.constraints.colreg.act_range = s.constraints.colreg_distance;
  s.budget = p.budget;
  s.budget.seed = static_cast<uint64_t>(p.seed) + plan_index;
  s.own = colreg::ShipKinematics::from_course(pb.start.x, pb.start.y, cog, sog, own.heading);
  return s;
}

std::string chart_wait(const NodeParams& p, const Setup& s, bool have_chart) {
  if (!have_chart) return p.require_chart ? "no chart yet (obstacles/fixed)" : "";
  return beyond_chart(s.problem, s.constraints.safety_distance);
}

EncounterMemoryParams encounter_params(const NodeParams& p, const Setup& s) {
  EncounterMemoryParams ep;
  ep.cpa_risk = p.encounter_cpa * s.constraints.safety_distance;
  // The plan checks COLREG along the whole path: a risk anywhere within its horizon matters.
  ep.tcpa_max = p.encounter_tcpa > 0 ? p.encounter_tcpa : norm(s.problem.goal.p - s.problem.start) / s.problem.speed;
  ep.release_range = s.constraints.colreg_distance;
  ep.abaft_beam = p.sector_abaft_beam;
  ep.head_on_sector = p.sector_head_on;
  // An alteration has begun once the own course leaves the band a pinned leg may hold.
  ep.acted_turn = std::max(s.constraints.colreg.port_tolerance, geo::deg2rad(1.0));
  // Made once the course or the speed sailed is altered as much as rule 8(b) asks (the legs aim
  // beyond it by the apparent margins, so that it is reached).
  ep.apparent_turn = s.constraints.colreg.apparent_turn;
  ep.apparent_slowdown = s.constraints.colreg.apparent_slowdown;
  ep.port_turn_range = s.constraints.colreg.port_turn_range;
  return ep;
}

StandOnHold stand_on_hold(const NodeParams& p, const Setup& s, const std::optional<StandOnHold>& previous) {
  StandOnHold h;
  const Problem& pb = s.problem;
  if (!pb.colreg || !(p.stand_on_range > 0.0) || s.own.speed() < 0.5) return h;
  const EncounterMemoryParams ep = encounter_params(p, s);
  const colreg::ColregParams cp = ep.assessment();
  const double acted = ep.acted_turn;  // [rad] a target's course change that shows it acted
  const double reach = p.stand_on_range * s.constraints.safety_distance;
  const bool again = previous && previous->time > 0.0 && std::isfinite(previous->course);
  h.course = again ? previous->course : s.own.course();
  const Vec2 v = s.own.speed() * Vec2{std::cos(h.course), std::sin(h.course)};
  double t_hold = std::numeric_limits<double>::infinity();
  for (const Target& t : pb.targets) {
    if (is_duty(t.pinned.obligation)) {
      h.why_not = "giving way to target " + std::to_string(t.id) + " (rule 16 first)";
      continue;
    }
    colreg::Assessment a;
    try {
      a = colreg::assess(s.own, {t.p.x, t.p.y, t.v.x, t.v.y}, cp);
    } catch (const std::exception&) {
      continue;  // non-finite: report_encounters names it
    }
    const bool pinned_so = t.pinned.obligation == Obligation::kCrossingStandOn || t.pinned.obligation == Obligation::kOvertaken;
    if (pinned_so && !a.risk) {
      // The give-way ship has acted: keep course and speed until it is past (17(a)(i) lasts while
      // the other keeps out of the way; the memory releases the target once passed and clear).
      // No risk because the own ship has altered for others while the other held on is no such
      // case: nothing to hold for (DNV 40 held a 28 deg diversion 1000 s for a ship 3.5 km off
      // that never turned, and did not reach the goal).
      const double its_turn = std::remainder(std::atan2(t.v.y, t.v.x) - t.pinned.target_course, 2.0 * geo::kPi);
      if (!(norm(t.v) > 0.5 && std::fabs(its_turn) > acted)) continue;
      if (a.cpa.tcpa > 0.0 && a.cpa.tcpa < t_hold) {
        t_hold = a.cpa.tcpa;
        h.target = t.id;
      }
      continue;
    }
    if (!a.risk || (a.type != colreg::EncounterType::kCrossingStandOn && a.type != colreg::EncounterType::kOvertaken))
      continue;
    // First time the range |r0 + (v - w) t| falls to `reach`.
    const Vec2 r0 = pb.start - t.p, vr = v - t.v;
    const double A = dot(vr, vr), B = dot(r0, vr), C = dot(r0, r0) - reach * reach;
    double t_in = 0.0;
    if (C > 0.0) {
      const double disc = B * B - A * C;
      if (!(A > 0.0) || disc < 0.0) continue;  // never that close on present courses
      t_in = (-B - std::sqrt(disc)) / A;
      if (t_in < 0.0) continue;
    }
    // ... and, as the evaluation's stage 3, until the CPA is nearer than the time the own ship
    // takes to sail that range at the planned speed (an overtaking ship closing slowly from astern
    // leaves time; the present speed may be low while the ship works up to it).
    if (A > 0.0) t_in = std::max(t_in, -B / A - p.stand_on_time * s.constraints.safety_distance / pb.speed);
    if (t_in < t_hold) {
      t_hold = t_in;
      h.target = t.id;
    }
  }
  if (!std::isfinite(t_hold) || !h.why_not.empty()) return StandOnHold{0, 0, {}, 0, h.why_not};
  if (again && previous->target == h.target && std::fabs(t_hold - previous->time) < p.stand_on_steady)
    t_hold = previous->time;
  if (t_hold < 1.0) return {};  // may act now (17(a)(ii))
  const Vec2 end = pb.start + t_hold * v;
  auto refuse = [&](const std::string& why) {
    return StandOnHold{0, 0, {}, h.target, "stand-on for target " + std::to_string(h.target) + ": " + why};
  };
  if (norm(end - pb.start) >= norm(pb.goal.p - pb.start)) return {};  // the goal comes first
  if (pb.charted && !pb.charted->contains_by(end, s.constraints.safety_distance))
    return refuse("holding course leaves the charted region");
  const ValidityChecker vc(pb, s.constraints);
  const double len = norm(end - pb.start);
  if (!vc.fixed_clear(pb.start, end, vc.fixed_distance(true)))
    return refuse("holding course passes within d_safety of a fixed obstacle");
  // The stand-on targets themselves stay beyond `reach`; the others must be cleared (no COLREG:
  // no duty is pinned, and the per-leg model would judge the very situation being held in).
  Problem along = pb;
  along.speed = s.own.speed();
  const ValidityChecker vm(along, s.constraints);
  if (vm.moving(pb.start, 0.0, end, len, ColregLevel::kNone, s.constraints.escape_start) != ValidityChecker::kValid)
    return refuse("holding course passes within d_safety of a target");
  h.time = t_hold;
  h.end = end;
  return h;
}

Result solve_with_hold(Planner& planner, const Setup& s, const ObjectiveParams& objective, const StandOnHold& hold,
                       std::vector<Vec2> warm, const Hooks& hooks) {
  if (!(hold.time > 0.0)) return planner.solve(s.request(objective, std::move(warm)), hooks);
  Problem from = s.problem;
  from.start = hold.end;
  from.heading = hold.course;
  for (Target& t : from.targets) t.p = t.p + hold.time * t.v;  // eq. 3 at the hold's end
  const Bounds& b = s.problem.bounds;
  from.bounds = {std::min(b.min_x, hold.end.x), std::min(b.min_y, hold.end.y), std::max(b.max_x, hold.end.x),
                 std::max(b.max_y, hold.end.y)};
  if (from.charted) from.bounds = from.bounds.intersect(*from.charted);
  Result r = planner.solve(Request{from, s.constraints, objective, s.budget, warm}, hooks);
  if (r.status == Status::kNoPath || r.status == Status::kInvalidInput) {
    Result now = planner.solve(s.request(objective, std::move(warm)), hooks);
    now.reason = "stand-on hold for target " + std::to_string(hold.target) + " given up (" + r.reason + ")" +
                 (now.reason.empty() ? "" : "; " + now.reason);
    return now;
  }
  // The planner's path starts at the hold's end at t = 0: the hold leg goes first.
  for (Waypoint& w : r.path) w.t += hold.time;
  r.path.insert(r.path.begin(), Waypoint{s.problem.start, 0.0});
  const std::string held = "stand-on (rule 17(a)): course and speed held " + fmt(hold.time) + " s for target " +
                           std::to_string(hold.target);
  r.reason = r.reason.empty() ? held : held + "; " + r.reason;
  return r;
}

double last_meeting(const Result& r, const std::vector<Target>& targets, double range) {
  double last = 0.0;
  for (const Target& t : targets) {
    double best = std::numeric_limits<double>::infinity(), when = 0.0;
    for (std::size_t i = 1; i < r.path.size(); ++i) {
      const Waypoint &a = r.path[i - 1], &b = r.path[i];
      const double dt = b.t - a.t;
      if (!(dt > 0.0)) continue;
      const geom::Approach c = geom::closest_approach(a.p - (t.p + a.t * t.v), (1.0 / dt) * (b.p - a.p) - t.v, dt);
      if (c.dist2 < best) best = c.dist2, when = a.t + c.tau;
    }
    if (best < range * range) last = std::max(last, when);
  }
  return last;
}

double resumed_arrival(const Result& r, const std::vector<Target>& targets, double range, double clear,
                       double cruise) {
  if (r.path.size() < 2) return r.path.empty() ? 0.0 : r.path.back().t;
  const double slow = r.path.back().t, passed = std::min(last_meeting(r, targets, range), slow);
  // The rest of the path from where the plan is at `passed`, timed at the cruise speed.
  std::vector<Waypoint> rest;
  for (std::size_t i = 1; i < r.path.size(); ++i) {
    const Waypoint &a = r.path[i - 1], &b = r.path[i];
    if (b.t < passed) continue;
    if (rest.empty()) {
      const double f = b.t > a.t ? (passed - a.t) / (b.t - a.t) : 1.0;
      rest.push_back({a.p + f * (b.p - a.p), passed});
    }
    rest.push_back({b.p, rest.back().t + norm(b.p - rest.back().p) / cruise});
  }
  for (std::size_t i = 1; i < rest.size(); ++i) {
    const Waypoint &a = rest[i - 1], &b = rest[i];
    const double dt = b.t - a.t;
    if (!(dt > 0.0)) continue;
    for (const Target& t : targets) {
      const double c = clear + t.margin;
      if (geom::closest_approach(a.p - (t.p + a.t * t.v), (1.0 / dt) * (b.p - a.p) - t.v, dt).dist2 < c * c)
        return slow;  // resuming would run into a ship (one followed, not passed): slow the whole way
    }
  }
  return rest.empty() ? slow : rest.back().t;
}

NodePlan plan_node(Planner& planner, const NodeParams& p, const Setup& s, const ObjectiveParams& objective,
                   const StandOnHold& hold, const std::vector<Vec2>& warm, const Hooks& hooks,
                   double warm_fraction) {
  auto speeds_of = [&](const Result& r, double u) {
    std::vector<double> v(r.path.size(), u);
    if (hold.time > 0.0 && v.size() > 1) v[1] = s.own.speed();  // the hold leg keeps the speed
    return v;
  };
  auto length = [](const Result& r) {
    double l = 0.0;
    for (std::size_t i = 1; i < r.path.size(); ++i) l += norm(r.path[i].p - r.path[i - 1].p);
    return l;
  };
  NodePlan out;
  out.result = solve_with_hold(planner, s, objective, hold, warm, hooks);
  out.speeds = speeds_of(out.result, s.problem.speed);
  if (out.result.kept) return out;
  const double straight = norm(s.problem.goal.p - s.problem.start);
  // Slower speeds are tried when the plan is not compliant, or compliant only by a long detour
  // (loops where a ship would slow down), or only without the planner's own margin; among
  // compliant plans the earliest arrival wins (the lost time being the cost of going slower),
  // a plan keeping that margin before one that gave it up.
  const bool detour = out.result.status == Status::kOk && length(out.result) > p.speed_detour * straight;
  const bool want = s.problem.colreg && out.result.status != Status::kInvalidInput &&
                    (out.result.status != Status::kOk || detour || out.result.margin_reduced);
  auto fraction = [&](int k) { return 1.0 - k * (1.0 - p.min_speed_fraction) / p.speed_steps; };
  // The lower speeds are independent requests, each with its own seed-determined search: solved
  // at once on their own threads (a planner's solve is safe to run concurrently, planner.hpp),
  // each at most once, and judged in order of k below, so the plan is the same as one after the
  // other, in less wall time (issue 20: the speed tries were half of a lockstep run's planning).
  std::vector<std::future<Result>> tries(static_cast<std::size_t>(want ? p.speed_steps : 0));
  std::vector<std::optional<Result>> solved(tries.size());
  auto launch = [&](int k) {
    auto& t = tries[static_cast<std::size_t>(k - 1)];
    if (t.valid() || solved[static_cast<std::size_t>(k - 1)]) return;
    t = std::async(std::launch::async, [&, k] {
      Setup slow = s;
      slow.problem.speed = fraction(k) * s.problem.speed;
      return solve_with_hold(planner, slow, objective, hold, {}, hooks);
    });
  };
  auto tried = [&](int k) -> Result& {
    auto& r = solved[static_cast<std::size_t>(k - 1)];
    if (!r) r = tries[static_cast<std::size_t>(k - 1)].get();
    return *r;
  };
  // A slower plan being sailed and still valid at its speed is carried on when the planned speed
  // would need one too (else the ship resumes it); but a speed between, at which a plan is now
  // compliant with the margin and no detour, comes first, the fastest: the ship works back up as
  // the encounter allows (DNV 46 kept 0.7 NM from an overtaken ship at 25 % for 1000 s, then ran
  // out of time).
  if (want && planner.keeps_plan() && !warm.empty() && warm_fraction < 1.0) {
    int faster = 0;
    while (faster < p.speed_steps && fraction(faster + 1) > warm_fraction + 1e-9) launch(++faster);
    for (int k = 1; k <= faster; ++k) {
      const Result& r = tried(k);
      if (r.status != Status::kOk || r.margin_reduced || length(r) > p.speed_detour * straight) continue;
      out.result = r;
      out.result.reason = "speed raised to " + fmt(100.0 * fraction(k)) + " % from " + fmt(100.0 * warm_fraction) +
                          " %: " + r.reason;
      out.speeds = speeds_of(out.result, fraction(k) * s.problem.speed);
      out.speed_fraction = fraction(k);
      return out;
    }
    Setup slow = s;
    slow.problem.speed = warm_fraction * s.problem.speed;
    Result kept = solve_with_hold(planner, slow, objective, hold, warm, hooks);
    if (kept.kept) {
      out.result = std::move(kept);
      out.speeds = speeds_of(out.result, slow.problem.speed);
      out.speed_fraction = warm_fraction;
      out.result.reason = "at " + fmt(100.0 * warm_fraction) + " % speed: " + out.result.reason;
      return out;
    }
  }
  double best_time = out.result.status == Status::kOk ? length(out.result) / s.problem.speed
                                                      : std::numeric_limits<double>::infinity();
  // A slower plan is sailed slowly only until the targets it meets are passed: re-planned from
  // there at the planned speed (every replan tries it first). Its arrival is estimated so (seed
  // 000 §2 reduces speed for the encounter, not for the voyage); charged the whole way at the
  // reduced speed, letting a crossing ship pass ahead lost to holding a diversion alongside it
  // (DNV 30, 40, 46).
  auto arrival = [&](const Result& r) {
    // Resumed only where the rest at cruise is no new risk of collision (DNV 34 trailed an
    // overtaken ship at 25 % for 1200 s: each slow plan counted on passing it at cruise later).
    return resumed_arrival(r, s.problem.targets, s.constraints.colreg_distance, s.constraints.colreg.risk_cpa,
                           s.problem.speed);
  };
  for (int k = 1; k <= static_cast<int>(tries.size()); ++k) launch(k);
  for (int k = 1; k <= static_cast<int>(tries.size()); ++k) {
    const double f = fraction(k);
    Result& r = tried(k);
    const double time = r.status == Status::kOk ? arrival(r) : std::numeric_limits<double>::infinity();
    // A plan that keeps the planner's own margin beats one that gave it up, whatever the arrival.
    const bool wider = r.status == Status::kOk && !r.margin_reduced && out.result.margin_reduced;
    const bool narrower = r.margin_reduced && !out.result.margin_reduced && out.result.status == Status::kOk;
    const bool better =
        wider || (!narrower && (time < best_time || (out.result.status == Status::kNoPath && r.status == Status::kRelaxed)));
    if (!better) continue;
    best_time = time;
    r.reason = "speed reduced to " + fmt(100.0 * f) + " % (seed 000 §2: steering alone not sufficient" +
               (detour ? ", or only by a detour)" : ")") + (r.reason.empty() ? "" : "; " + r.reason);
    out.result = std::move(r);
    out.speeds = speeds_of(out.result, f * s.problem.speed);
    out.speed_fraction = f;
  }
  if (out.result.status == Status::kNoPath && p.emergency) {
    double f = p.min_speed_fraction;
    Result e = emergency_path(p, s, out.result.reason, &f);
    if (!e.path.empty()) {
      out.result = std::move(e);
      out.speeds.assign(out.result.path.size(), f * s.problem.speed);
      out.speed_fraction = f;
      out.emergency = true;
    }
  }
  return out;
}

Result emergency_path(const NodeParams& p, const Setup& s, const std::string& why, double* speed_fraction) {
  const Problem& pb = s.problem;
  const ValidityChecker vc(pb, s.constraints);
  // Every candidate is judged over the same time: that of the reduced-speed leg of d_safety.
  const double slow = p.min_speed_fraction * pb.speed, horizon = std::max(s.constraints.safety_distance, 10.0 * slow) / slow;
  const double course = s.own.speed() > 0.5 ? s.own.course() : pb.heading;
  const double turn = std::min(s.constraints.max_turn, geo::kPi / 2);
  Result best;
  double best_d = -1.0;
  for (const double a : {turn, turn / 2, 0.0, -turn / 2, -turn}) {
    // Rule 8(e): slacken speed first; the planned speed where that passes 10 % farther (being
    // overtaken from astern, slowing down brings the overtaking ships on sooner: DNV 54).
    for (const double f : {p.min_speed_fraction, 1.0}) {
      const Vec2 vel = f * pb.speed * Vec2{std::cos(course + a), std::sin(course + a)};
      const Vec2 end = pb.start + horizon * vel;
      if (!vc.fixed_clear(pb.start, end, vc.fixed_distance(true))) continue;
      double d = std::numeric_limits<double>::infinity();
      for (const Target& t : pb.targets)
        d = std::min(d, std::sqrt(geom::closest_approach(pb.start - t.p, vel - t.v, horizon).dist2));
      if (!(d > 1.1 * best_d)) continue;
      best_d = d;
      if (speed_fraction) *speed_fraction = f;
      best.path = {{pb.start, 0.0}, {end, horizon}};
      best.reason = "emergency (rule 17(b)): no path at any speed (" + why + "); " +
                    (a > 0 ? "turning to starboard " : (a < 0 ? "turning to port " : "holding course ")) +
                    fmt(geo::rad2deg(std::fabs(a))) + " deg at " + fmt(100.0 * f) + " % speed";
    }
  }
  best.status = best.path.empty() ? Status::kNoPath : Status::kRelaxed;
  best.relaxed = !best.path.empty();
  if (best.path.empty()) best.reason = why + "; no emergency leg clear of fixed obstacles either";
  return best;
}

std::vector<EncounterReport> report_encounters(const NodeParams& p, const Setup& s, std::vector<std::string>* rejected) {
  colreg::ColregParams cp;
  cp.abaft_beam = p.sector_abaft_beam;
  cp.head_on_sector = p.sector_head_on;
  cp.d_colreg = s.constraints.colreg_distance;
  std::vector<EncounterReport> out;
  for (const Target& t : s.problem.targets) {
    const colreg::ShipKinematics tk{t.p.x, t.p.y, t.v.x, t.v.y};
    try {
      out.push_back({t.id, colreg::assess(s.own, tk, cp), colreg::bearing(s.own, tk)});
    } catch (const std::exception& e) {
      if (rejected) rejected->push_back(e.what());
    }
  }
  return out;
}

}  // namespace mpgc::opp
