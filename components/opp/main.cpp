// mpgc_opp: own state + goal + fixed and moving obstacles -> plan/path and plan/encounters.
// Seed 000 §6: plans at a fixed rate and at once on a new goal or a changed target track; the
// planning runs inside a timer callback on the component clock (in lockstep the simulator waits
// for it). COLREG-compliant first, relaxed and flagged otherwise, explicit status when no path.
#include <cmath>
#include <memory>
#include <optional>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/colreg/msg.hpp"
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
#include "mpgc/opp/node.hpp"
#include "mpgc/opp/replan.hpp"
#include "mpgc/opp/validate.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace msg = mpgc::msg;
namespace opp = mpgc::opp;
namespace om = mpgc::obstacle_manager;

namespace {

msg::PlanStatus to_msg(opp::Status s) {
  switch (s) {
    case opp::Status::kOk: return msg::PlanStatus::PLAN_OK;
    case opp::Status::kRelaxed: return msg::PlanStatus::PLAN_RELAXED;
    case opp::Status::kNoPath: return msg::PlanStatus::PLAN_NO_PATH;
    case opp::Status::kInvalidInput: return msg::PlanStatus::PLAN_INVALID_INPUT;
  }
  return msg::PlanStatus::PLAN_NO_PATH;
}

}  // namespace

int main(int argc, char** argv) {
  opp::NodeParams p;
  std::vector<std::unique_ptr<opp::Planner>> planners;
  mpgc::rt::ParamSet ps;
  opp::declare(ps, p, planners);
  return mpgc::rt::run_component("opp", argc, argv, ps, [&p, &planners](mpgc::rt::Component& comp) {
    mpgc::rt::Component* c = &comp;  // callbacks outlive setup: capture by pointer / shared state
    if (p.constraints.colreg_distance < p.constraints.safety_distance)
      p.constraints.colreg_distance = p.constraints.safety_distance;
    p.constraints.validate();
    p.objective.validate();
    p.budget.validate();
    opp::Planner* planner = nullptr;
    for (auto& pl : planners)
      if (pl->name() == p.planner) planner = pl.get();

    struct State {
      std::optional<msg::NavState> own;
      std::optional<msg::MissionGoal> goal;
      std::optional<msg::MovingObstacles> moving;
      std::shared_ptr<opp::ChartObstacles> fixed;
      opp::Bounds region;      // what obstacles/fixed is complete for (valid with `fixed`)
      std::string chart_wait;  // why no plan is made on this chart ("" = none)
      opp::ReplanPolicy policy;
      uint32_t plan_id = 0;
      uint32_t warm_goal = 0;
      std::vector<opp::Vec2> last_path;
      opp::EncounterMemory encounters;
      std::string stale;  // why no plan is made now ("" = inputs fresh)
      mpgc::rt::WallClock wall;  // planning time and budget are wall time, also on simulated time
      mpgc::nav::JumpGate jumps;
      std::optional<opp::StandOnHold> held;  // rule 17(a): the last plan's stand-on hold
      double held_at = 0;                     // [s] when it was planned
      double last_fraction = 1.0;             // [-] last_path's speed, of the planned speed
    };
    auto st = std::make_shared<State>(State{{}, {}, {}, {}, {}, {}, opp::ReplanPolicy(p.replan), 0, 0, {}, {}, {}, {},
                                            mpgc::nav::JumpGate({p.jumps.max_speed, p.jumps.margin, p.max_state_age}), {}, 0});

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
                std::make_shared<const mpgc::geom::FixedObstacleMap>(om::map_from_msg(m)));
            st->region = opp::region_of(m);
            c->log().info("fixed obstacles v{}: {} points, {} polygons in [{:.0f}, {:.0f}] x [{:.0f}, {:.0f}] m", m.version,
                          m.points.size(), m.polygons.size(), m.region_min_x, m.region_max_x, m.region_min_y, m.region_max_y);
          } catch (const std::exception& e) {
            c->reject(mpgc::topics::kFixedObstacles, e.what());
          }
        },
        opp::check_fixed);

    c->every(p.check_period, [c, st, &p, planner, path_out, enc_out, memory_out] {
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
        c->set_problem("inputs", stale.empty() ? "" : "not planning: " + stale);
      }
      if (!stale.empty()) return;
      std::vector<opp::TrackReport> tracks;
      if (st->moving)
        for (const auto& o : st->moving->obstacles) tracks.push_back({o.id, {o.x, o.y}, {o.vx, o.vy}, o.position_std});
      const std::vector<opp::Target> targets = opp::targets_at(
          tracks, st->moving ? mpgc::rt::seconds_between(now_ns, st->moving->t_valid_ns) : 0.0, p.target_sigmas);
      const std::string why = st->policy.due(now, goal.goal_id, targets);
      if (why.empty()) return;
      opp::Setup setup = opp::build_setup(
          p, {{own.x, own.y}, own.heading, own.sog, own.cog, own_age},
          {{goal.x, goal.y}, goal.heading, goal.heading_tolerance, goal.cruise_speed, goal.safety_distance, goal.colreg},
          targets, st->fixed ? opp::ChartView{st->fixed.get(), st->region} : opp::ChartView{}, st->plan_id);
      const opp::Problem& pb = setup.problem;
      // Water beyond the charted region is unknown: wait (the plan stays due) until the obstacle
      // manager publishes a region that covers the goal; guidance keeps the last plan meanwhile.
      const std::string wait = opp::chart_wait(p, setup, st->fixed != nullptr);
      if (wait != st->chart_wait) {
        st->chart_wait = wait;
        if (!wait.empty()) c->log().warn("not planning: {}", wait);
        c->set_problem("chart", wait.empty() ? "" : "not planning: " + wait);
      }
      if (!wait.empty()) {
        c->count("skipped.chart");
        return;
      }
      if (setup.arrived) {
        c->count("skipped.arrived");
        st->policy.planned(now, goal.goal_id, targets);
        return;
      }
      if (pb.colreg && p.pin_encounters) {
        try {
          const std::size_t before = st->encounters.size();
          st->encounters.update(opp::encounter_params(p, setup), setup.own, setup.problem.targets);
          if (st->encounters.size() != before)
            for (const auto& t : pb.targets)
              if (t.pinned.obligation != opp::Obligation::kNone)
                c->log().debug("target {}: {} pinned at course {:.1f} deg", t.id, mpgc::colreg::to_string(t.pinned.obligation),
                               mpgc::geo::rad2deg(t.pinned.course0));
        } catch (const std::exception& e) {
          c->reject("encounters", e.what());
        }
      }
      opp::Hooks hooks;
      auto wall = &st->wall;
      hooks.elapsed = [wall] { return wall->now_s(); };
      const bool warm = p.warm_start && st->warm_goal == goal.goal_id && !st->last_path.empty();
      if (st->held) st->held->time -= now - st->held_at;  // counted from this plan
      const opp::StandOnHold hold = opp::stand_on_hold(p, setup, st->held);
      st->held.reset();
      if (hold.time > 0) {
        c->count("plans.stand_on_hold");
        st->held = hold;
        st->held_at = now;
      }
      if (!hold.why_not.empty()) c->log().debug("no stand-on hold: {}", hold.why_not);
      const opp::NodePlan np = opp::plan_node(*planner, p, setup, p.objective, hold,
                                              warm ? st->last_path : std::vector<opp::Vec2>{}, hooks,
                                              st->last_fraction);
      const opp::Result& r = np.result;
      if (np.speed_fraction < 1.0) c->count("plans.reduced_speed");
      if (np.emergency) c->count("plans.emergency");
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
      for (std::size_t i = 0; i < r.path.size(); ++i)
        out.waypoints.push_back({r.path[i].p.x, r.path[i].p.y, r.path[i].t, np.speeds[i]});
      out.cost_total = r.cost.total;
      out.cost_length = r.cost.length;
      out.cost_fixed = r.cost.fixed;
      out.cost_moving = r.cost.moving;
      out.cost_smooth = r.cost.smooth;
      out.iterations = static_cast<uint32_t>(r.stats.iterations);
      out.planning_time = r.stats.planning_time;
      out.planner = planner->name();
      // A plan computed on simulated time takes as long as its iterations would (deterministic);
      // on the wall clock its lateness is real and it applies on arrival.
      if (c->clock().simulated() && p.latency_per_iteration > 0)
        out.effective_ns = now_ns + static_cast<int64_t>(std::llround(r.stats.iterations * p.latency_per_iteration * 1e9));
      path_out->write(out);
      if (!r.path.empty()) {
        st->last_path.clear();
        for (const auto& w : r.path) st->last_path.push_back(w.p);
        st->last_fraction = np.speed_fraction;
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
      std::vector<std::string> rejected;
      for (const auto& e : opp::report_encounters(p, setup, &rejected)) {
        uint32_t mmsi = 0;
        for (const auto& o : st->moving->obstacles)
          if (o.id == e.id) mmsi = o.mmsi;
        const auto& a = e.assessment;
        enc.encounters.push_back({e.id, mmsi, to_msg(a.type), to_msg(a.role), a.cpa.dcpa, a.cpa.tcpa, a.cpa.range, e.bearing});
      }
      for (const auto& why_not : rejected) c->reject("plan/encounters", why_not);
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
