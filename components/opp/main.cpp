// mpgc_opp: own state + goal + fixed and moving obstacles -> plan/path and plan/encounters.
// Seed 000 §6: plans at a fixed rate and at once on a new goal or a changed target track; the
// planning runs inside a timer callback on the component clock (in lockstep the simulator waits
// for it). COLREG-compliant first, relaxed and flagged otherwise, explicit status when no path.
#include <cmath>
#include <memory>
#include <optional>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/obstacle_manager/msg_convert.hpp"
#include "mpgc/opp/chart_obstacles.hpp"
#include "mpgc/opp/encounters.hpp"
#include "mpgc/opp/memory.hpp"
#include "mpgc/opp/planner.hpp"
#include "mpgc/opp/replan.hpp"
#include "mpgc/opp/validate.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace msg = mpgc::msg;
namespace opp = mpgc::opp;
namespace om = mpgc::obstacle_manager;

namespace {

struct NodeParams {
  opp::Params planner;
  opp::ReplanParams replan;
  int seed = 1;                  // [-] base seed; plan k uses seed + k
  double check_period = 0.5;     // [s] how often the re-planning conditions are checked
  double bounds_margin = 3000;   // [m] sampling box around start and goal
  double arrival_radius = 100;   // [m] no more plans once the own ship is this close to the goal
  double default_speed = 5;      // [m/s] when neither the goal nor the own state gives a speed
  double max_state_age = 5;      // [s] own state older than this is not planned from
  mpgc::nav::JumpGateParams jumps;  // own position jumps are not planned from (timeout: max_state_age)
  double max_obstacle_age = 10;  // [s] moving obstacles older than this are not planned with
  bool warm_start = true;        // seed the tree with the previous path of the same goal
  bool pin_encounters = true;    // hold each leg to the obligation fixed at the encounter's start
  double encounter_cpa = 2.0;    // [-] x d_safety: a CPA inside it is a risk of collision
  double encounter_tcpa = 0;     // [s] risk of collision within this TCPA pins an encounter (0: the
                                 //     plan's horizon, the straight-line time to the goal)
  std::string memory_file;       // what a restart must remember (memory.hpp); "" = nothing kept
  double latency_per_iteration = 0;  // [s] simulated time one iteration takes (late plans); 0 = at once
};

void declare(mpgc::rt::ParamSet& ps, NodeParams& p) {
  opp::Params& q = p.planner;
  ps.add("replan.period", &p.replan.period, 15.0, "s", 0.1, 3600.0, "fixed re-planning period (seed 000: 15 s)");
  ps.add("replan.track_threshold", &p.replan.track_threshold, 300.0, "m", 1.0, 1e5,
         "re-plan at once when a target's predicted position moved this far from the last plan's prediction");
  ps.add("replan.track_horizon", &p.replan.track_horizon, 300.0, "s", 0.0, 3600.0, "prediction horizon of that comparison");
  ps.add("replan.min_interval", &p.replan.min_interval, 2.0, "s", 0.0, 600.0, "event-triggered plans no closer than this");
  ps.add("replan.check_period", &p.check_period, 0.5, "s", 0.01, 60.0, "how often the conditions are checked");
  ps.add("plan.time_budget", &q.time_budget, 0.5, "s", 0.001, 60.0, "wall-time budget of one plan");
  ps.add("plan.max_iterations", &q.max_iterations, 20000, "-", 1, 2000000, "RRT* iterations per plan");
  ps.add("plan.compliant_share", &q.compliant_share, 0.5, "-", 0.01, 1.0,
         "budget share after which a compliant pass without any solution is relaxed");
  ps.add("plan.restart_after", &q.restart_after, 1000, "-", 0, 10000000,
         "iterations without improvement before a fresh tree is grown (0 = never)");
  ps.add("plan.seed", &p.seed, 1, "-", 0, 2147483647, "base seed (plan k uses seed + k)");
  ps.add("plan.step", &q.step, 500.0, "m", 1.0, 1e5, "RRT* steer step");
  ps.add("plan.goal_bias", &q.goal_bias, 0.05, "-", 0.0, 1.0, "probability of sampling the goal");
  ps.add("plan.rewire_factor", &q.rewire_factor, 1.1, "-", 1.0, 10.0, "scales the k-nearest neighbourhood");
  ps.add("plan.max_turn", &q.max_turn, mpgc::geo::deg2rad(60.0), "rad", 0.01, 3.15, "turning-angle limit (eq. 2)");
  ps.add("plan.safety_distance", &q.safety_distance, 1000.0, "m", 0.0, 1e5,
         "d_safety when the goal does not set one (eq. 4)");
  ps.add("plan.colreg_distance", &q.colreg_distance, 3000.0, "m", 0.0, 1e6, "d_COLREG (§5), at least d_safety");
  ps.add("plan.theta_overtaking", &q.colreg.theta_overtaking, mpgc::geo::deg2rad(22.5), "rad", 0.01, 1.5, "theta_o (eq. 16)");
  ps.add("plan.theta_head_on", &q.colreg.theta_head_on, mpgc::geo::deg2rad(22.5), "rad", 0.01, 1.5, "theta_h (§5.5)");
  ps.add("plan.gamma_s", &q.gamma_s, 500.0, "m/rad^2", 0.0, 1e9, "weight of the steering cost (eq. 6)");
  ps.add("plan.gamma_f", &q.gamma_f, 1e5, "m^2", 0.0, 1e12, "weight of the fixed-obstacle margin cost (eq. 7)");
  ps.add("plan.gamma_m", &q.gamma_m, 1e5, "m^2", 0.0, 1e12, "weight of the target margin cost (eq. 8)");
  ps.add("plan.gamma_l", &q.gamma_l, 1.0, "-", 0.0, 1e6, "weight of the path length (eq. 9)");
  ps.add("plan.escape_start", &q.escape_start, true,
         "start within d_safety (target moved in): still plan; the first leg may not get closer (else INVALID_INPUT)");
  ps.add("plan.bounds_margin", &p.bounds_margin, 3000.0, "m", 0.0, 1e6, "sampling box margin around start and goal");
  ps.add("plan.arrival_radius", &p.arrival_radius, 100.0, "m", 0.0, 1e5, "stop planning this close to the goal");
  ps.add("plan.default_speed", &p.default_speed, 5.0, "m/s", 0.1, 50.0, "planned speed when no other is known");
  ps.add("plan.max_state_age", &p.max_state_age, 5.0, "s", 0.1, 600.0, "older own states are not planned from");
  mpgc::nav::declare_params(ps, &p.jumps);
  ps.add("plan.max_obstacle_age", &p.max_obstacle_age, 10.0, "s", 0.1, 600.0,
         "moving obstacles older than this (obstacle_manager publishes every 0.5 s) are not extrapolated: no plan "
         "until fresh ones come (guidance keeps the last plan, then slows to steerage speed)");
  ps.add("plan.warm_start", &p.warm_start, true, "re-use the previous path of the same goal");
  ps.add("plan.pin_encounters", &p.pin_encounters, true,
         "fix each target's COLREG obligation when the risk of collision appears (encounters.hpp); false: per leg (§5)");
  ps.add("plan.encounter_cpa", &p.encounter_cpa, 2.0, "-", 0.0, 10.0,
         "risk of collision: CPA inside this many d_safety (about the NTNU evaluator's r_pref / r_min_cpa, 1.9)");
  ps.add("plan.encounter_tcpa", &p.encounter_tcpa, 0.0, "s", 0.0, 86400.0,
         "a risk of collision within this time pins the encounter (0: the straight-line time to the goal)");
  ps.add("memory.file", &p.memory_file, "",
         "file that keeps the goal, plan id, warm-start path and pinned COLREG obligations across a restart "
         "(read at start, rewritten after every plan; \"\" = start blind)");
  ps.add("plan.latency_per_iteration", &p.latency_per_iteration, 0.0, "s", 0.0, 1.0,
         "on simulated time, a plan takes effect iterations x this after the state it was planned from (guidance "
         "follows the previous plan meanwhile, seed 000 §6); 25e-6 is the paper's 0.5 s for 20000 iterations; "
         "0 = at once");
  ps.add("plan.port_tolerance", &q.colreg.port_tolerance, mpgc::geo::deg2rad(5.0), "rad", 0.0, 1.5,
         "a pinned head-on / give-way leg may point this far to port of the course at the encounter's start");
}

msg::PlanStatus to_msg(opp::Status s) {
  switch (s) {
    case opp::Status::kOk: return msg::PlanStatus::PLAN_OK;
    case opp::Status::kRelaxed: return msg::PlanStatus::PLAN_RELAXED;
    case opp::Status::kNoPath: return msg::PlanStatus::PLAN_NO_PATH;
    case opp::Status::kInvalidInput: return msg::PlanStatus::PLAN_INVALID_INPUT;
  }
  return msg::PlanStatus::PLAN_NO_PATH;
}

msg::EncounterType to_msg(mpgc::colreg::EncounterType t) {
  using E = mpgc::colreg::EncounterType;
  switch (t) {
    case E::kNone: return msg::EncounterType::ENCOUNTER_NONE;
    case E::kHeadOn: return msg::EncounterType::ENCOUNTER_HEAD_ON;
    case E::kCrossingGiveWay: return msg::EncounterType::ENCOUNTER_CROSSING_GIVE_WAY;
    case E::kCrossingStandOn: return msg::EncounterType::ENCOUNTER_CROSSING_STAND_ON;
    case E::kOvertaking: return msg::EncounterType::ENCOUNTER_OVERTAKING;
    case E::kOvertaken: return msg::EncounterType::ENCOUNTER_OVERTAKEN;
  }
  return msg::EncounterType::ENCOUNTER_NONE;
}

msg::OwnRole to_msg(mpgc::colreg::Role r) {
  using R = mpgc::colreg::Role;
  switch (r) {
    case R::kNone: return msg::OwnRole::ROLE_NONE;
    case R::kGiveWay: return msg::OwnRole::ROLE_GIVE_WAY;
    case R::kStandOn: return msg::OwnRole::ROLE_STAND_ON;
    case R::kBothGiveWay: return msg::OwnRole::ROLE_BOTH_GIVE_WAY;
  }
  return msg::OwnRole::ROLE_NONE;
}

}  // namespace

int main(int argc, char** argv) {
  NodeParams p;
  mpgc::rt::ParamSet ps;
  declare(ps, p);
  return mpgc::rt::run_component("opp", argc, argv, ps, [&p](mpgc::rt::Component& comp) {
    mpgc::rt::Component* c = &comp;  // callbacks outlive setup: capture by pointer / shared state
    if (p.planner.colreg_distance < p.planner.safety_distance) p.planner.colreg_distance = p.planner.safety_distance;
    p.planner.validate();

    struct State {
      std::optional<msg::NavState> own;
      std::optional<msg::MissionGoal> goal;
      std::optional<msg::MovingObstacles> moving;
      std::shared_ptr<opp::ChartObstacles> fixed;
      opp::ReplanPolicy policy;
      uint32_t plan_id = 0;
      uint32_t warm_goal = 0;
      std::vector<opp::Vec2> last_path;
      opp::EncounterMemory encounters;
      std::string stale;  // why no plan is made now ("" = inputs fresh)
      mpgc::rt::WallClock wall;  // planning time and budget are wall time, also on simulated time
      mpgc::nav::JumpGate jumps;
    };
    auto st = std::make_shared<State>(State{{}, {}, {}, {}, opp::ReplanPolicy(p.replan), 0, 0, {}, {}, {}, {},
                                            mpgc::nav::JumpGate({p.jumps.max_speed, p.jumps.margin, p.max_state_age})});

    auto* path_out = &c->publisher<msg::Path>(mpgc::topics::kPath, mpgc::dds::QosProfile::latched());
    auto* enc_out = &c->publisher<msg::EncounterList>(mpgc::topics::kPlanEncounters, mpgc::dds::QosProfile::latched());
    auto* memory_out = &c->publisher<msg::PlannerMemory>(mpgc::topics::kPlanMemory, mpgc::dds::QosProfile::latched());
    if (!p.memory_file.empty()) {
      try {
        if (const auto m = opp::load_memory(p.memory_file)) {
          st->encounters.restore(m->pinned);
          st->plan_id = m->plan_id;
          st->warm_goal = m->warm_goal;
          st->last_path = m->last_path;
          c->log().warn("restarted: memory of plan {} (goal {}) with {} pinned encounters restored from {}", m->plan_id,
                        m->goal_id, m->pinned.size(), p.memory_file);
          c->count("restored");
        }
      } catch (const std::exception& e) {
        c->reject("memory.file", e.what());  // start blind rather than from a memory that is not ours
      }
    }

    c->subscribe<msg::NavState>(mpgc::topics::kOwnState, mpgc::dds::QosProfile::state(),
                                [c, st](const msg::NavState& s) {
                                  std::string jump;
                                  if (st->jumps.check(s.x, s.y, s.header.stamp_ns, &jump) == mpgc::nav::JumpGate::Verdict::kTaken)
                                    st->own = s;
                                  else
                                    c->reject("nav.jump", jump);  // planned from the last good state until it is stale
                                }, opp::check_nav);
    c->subscribe<msg::MissionGoal>(mpgc::topics::kGoal, mpgc::dds::QosProfile::latched(),
                                   [st](const msg::MissionGoal& g) { st->goal = g; }, opp::check_goal);
    c->subscribe<msg::MovingObstacles>(mpgc::topics::kMovingObstacles, mpgc::dds::QosProfile::state(),
                                       [st](const msg::MovingObstacles& m) { st->moving = m; }, opp::check_moving);
    c->subscribe<msg::FixedObstacles>(
        mpgc::topics::kFixedObstacles, mpgc::dds::QosProfile::latched(), [c, st](const msg::FixedObstacles& m) {
          try {
            st->fixed = std::make_shared<opp::ChartObstacles>(
                std::make_shared<const om::FixedObstacleMap>(om::map_from_msg(m)));
            c->log().info("fixed obstacles v{}: {} points, {} polygons", m.version, m.points.size(), m.polygons.size());
          } catch (const std::exception& e) {
            c->reject(mpgc::topics::kFixedObstacles, e.what());
          }
        });

    c->every(p.check_period, [c, st, &p, path_out, enc_out, memory_out] {
      if (!st->own || !st->goal) return;
      const int64_t now_ns = c->now_ns();
      const double now = static_cast<double>(now_ns) * 1e-9;
      const msg::NavState& own = *st->own;
      const msg::MissionGoal& goal = *st->goal;
      const double own_age = mpgc::rt::seconds_between(now_ns, own.header.stamp_ns);
      // Stale inputs: no plan rather than one against a picture that no longer holds; guidance
      // keeps the last plan while it is fresh, then slows down (its README), and health says why.
      std::string stale;
      if (own_age > p.max_state_age) {
        c->count("skipped.stale_own_state");
        stale = "own-ship state " + std::to_string(static_cast<int>(own_age)) + " s old";
      } else if (st->moving && mpgc::rt::seconds_between(now_ns, st->moving->t_valid_ns) > p.max_obstacle_age) {
        c->count("skipped.stale_obstacles");
        stale = fmt::format("moving obstacles {:.0f} s old", mpgc::rt::seconds_between(now_ns, st->moving->t_valid_ns));
      }
      if (stale != st->stale) {
        st->stale = stale;
        if (!stale.empty()) c->log().warn("not planning: {}", stale);
        c->set_health(stale.empty() ? msg::HealthState::HEALTH_OK : msg::HealthState::HEALTH_DEGRADED,
                      stale.empty() ? "" : "not planning: " + stale);
      }
      if (!stale.empty()) return;
      // Targets at `now` by eq. 3.
      std::vector<opp::Target> targets;
      if (st->moving) {
        const double dt = mpgc::rt::seconds_between(now_ns, st->moving->t_valid_ns);
        for (const auto& o : st->moving->obstacles)
          targets.push_back({o.id, {o.x + o.vx * dt, o.y + o.vy * dt}, {o.vx, o.vy}});
      }
      const std::string why = st->policy.due(now, goal.goal_id, targets);
      if (why.empty()) return;
      // Own ship at `now` (dead-reckoned over the sample's age).
      const double sog = std::isfinite(own.sog) ? own.sog : 0.0;
      const double cog = std::isfinite(own.cog) ? own.cog : own.heading;
      opp::Problem pb;
      pb.start = {own.x + sog * std::cos(cog) * std::max(0.0, own_age), own.y + sog * std::sin(cog) * std::max(0.0, own_age)};
      pb.heading = own.heading;
      pb.speed = goal.cruise_speed > 0 ? goal.cruise_speed : (sog > 0.5 ? sog : p.default_speed);
      pb.goal.p = {goal.x, goal.y};
      pb.goal.heading = goal.heading;
      pb.goal.heading_tolerance = std::isfinite(goal.heading) ? goal.heading_tolerance : mpgc::geo::kPi;
      if (opp::norm(pb.goal.p - pb.start) < p.arrival_radius) {
        c->count("skipped.arrived");
        st->policy.planned(now, goal.goal_id, targets);
        return;
      }
      const double m = p.bounds_margin;
      pb.bounds = {std::min(pb.start.x, pb.goal.p.x) - m, std::min(pb.start.y, pb.goal.p.y) - m,
                   std::max(pb.start.x, pb.goal.p.x) + m, std::max(pb.start.y, pb.goal.p.y) + m};
      pb.fixed = st->fixed.get();
      pb.targets = targets;
      pb.colreg = goal.colreg;
      opp::Params prm = p.planner;
      if (goal.safety_distance > 0) prm.safety_distance = goal.safety_distance;
      prm.colreg_distance = std::max(prm.colreg_distance, prm.safety_distance);
      prm.seed = static_cast<uint64_t>(p.seed) + st->plan_id;
      const auto own_kin = mpgc::colreg::ShipKinematics::from_course(pb.start.x, pb.start.y, cog, sog, own.heading);
      if (pb.colreg && p.pin_encounters) {
        opp::EncounterMemoryParams ep;
        ep.cpa_risk = p.encounter_cpa * prm.safety_distance;
        // The plan checks COLREG along the whole path: a risk anywhere within its horizon matters.
        ep.tcpa_max = p.encounter_tcpa > 0 ? p.encounter_tcpa : opp::norm(pb.goal.p - pb.start) / pb.speed;
        ep.release_range = prm.colreg_distance;
        ep.theta_o = prm.colreg.theta_overtaking;
        ep.theta_h = prm.colreg.theta_head_on;
        try {
          const std::size_t before = st->encounters.size();
          st->encounters.update(ep, own_kin, pb.targets);
          if (st->encounters.size() != before)
            for (const auto& t : pb.targets)
              if (t.pinned.obligation != opp::Obligation::kNone)
                c->log().debug("target {}: {} pinned at course {:.1f} deg", t.id, opp::to_string(t.pinned.obligation),
                               mpgc::geo::rad2deg(t.pinned.course0));
        } catch (const std::exception& e) {
          c->reject("encounters", e.what());
        }
      }
      opp::Hooks hooks;
      auto wall = &st->wall;
      hooks.elapsed = [wall] { return wall->now_s(); };
      const bool warm = p.warm_start && st->warm_goal == goal.goal_id && !st->last_path.empty();
      const opp::Result r = opp::plan(pb, prm, hooks, warm ? st->last_path : std::vector<opp::Vec2>{});
      st->policy.planned(now, goal.goal_id, targets, !r.path.empty());

      msg::Path out;
      out.header = c->header();
      out.plan_id = ++st->plan_id;
      out.goal_id = goal.goal_id;
      out.t0_ns = now_ns;
      out.status = to_msg(r.status);
      out.reason = r.reason;
      out.colreg_compliant = r.colreg_compliant;
      out.relaxed = r.relaxed;
      for (const auto& w : r.path) out.waypoints.push_back({w.p.x, w.p.y, w.t, pb.speed});
      out.cost_total = r.cost.total;
      out.cost_length = r.cost.length;
      out.cost_fixed = r.cost.fixed;
      out.cost_moving = r.cost.moving;
      out.cost_smooth = r.cost.smooth;
      out.iterations = static_cast<uint32_t>(r.stats.iterations);
      out.planning_time = r.stats.planning_time;
      out.planner = "rrtstar-colreg";
      // A plan computed on simulated time takes as long as its iterations would (deterministic);
      // on the wall clock its lateness is real and it applies on arrival.
      if (c->clock().simulated() && p.latency_per_iteration > 0)
        out.effective_ns = now_ns + static_cast<int64_t>(std::llround(r.stats.iterations * p.latency_per_iteration * 1e9));
      path_out->write(out);
      if (!r.path.empty()) {
        st->last_path.clear();
        for (const auto& w : r.path) st->last_path.push_back(w.p);
        st->warm_goal = goal.goal_id;
      }
      c->count(std::string("plans.") + opp::to_string(r.status));
      c->log().info("plan {} ({}): {} cost {:.1f} ({} waypoints, {} iterations, {:.1f} ms{}){}{}", out.plan_id, why,
                    opp::to_string(r.status), r.cost.total, r.path.size(), r.stats.iterations,
                    1e3 * r.stats.planning_time, r.stats.warm_started ? ", warm" : "", r.reason.empty() ? "" : ": ",
                    r.reason);

      // Encounters from the planner's point of view (shared rule 13-15 geometry).
      msg::EncounterList enc;
      enc.header = out.header;
      mpgc::colreg::ColregParams cp;
      cp.theta_o = prm.colreg.theta_overtaking;
      cp.theta_h = prm.colreg.theta_head_on;
      cp.d_colreg = prm.colreg_distance;
      const auto& ok = own_kin;
      for (const auto& o : st->moving ? st->moving->obstacles : std::vector<msg::MovingObstacle>{}) {
        const opp::Target* t = nullptr;
        for (const auto& x : targets)
          if (x.id == o.id) t = &x;
        if (!t) continue;
        const mpgc::colreg::ShipKinematics tk{t->p.x, t->p.y, t->v.x, t->v.y};
        try {
          const auto a = mpgc::colreg::assess(ok, tk, cp);
          enc.encounters.push_back(
              {o.id, o.mmsi, to_msg(a.type), to_msg(a.role), a.cpa.dcpa, a.cpa.tcpa, a.cpa.range, mpgc::colreg::bearing(ok, tk)});
        } catch (const std::exception& e) {
          c->reject("plan/encounters", e.what());
        }
      }
      enc_out->write(enc);

      // What a restart must know (memory.hpp), on the bus for observers and in the memory file.
      opp::PlannerMemory mem{goal.goal_id, st->plan_id, st->warm_goal, st->last_path, st->encounters.records()};
      msg::PlannerMemory mm;
      mm.header = out.header;
      mm.goal_id = mem.goal_id;
      mm.plan_id = mem.plan_id;
      for (const auto& pin : mem.pinned)
        mm.pinned.push_back({pin.id, static_cast<uint32_t>(pin.e.obligation), pin.e.course0, pin.e.track_side,
                             pin.e.target_course, pin.range0});
      memory_out->write(mm);
      if (!p.memory_file.empty()) {
        try {
          opp::save_memory(p.memory_file, mem);
        } catch (const std::exception& e) {
          c->reject("memory.file", e.what());
        }
      }
    });
  });
}
