// The planning component's logic without DDS or a clock (mpgc_opp's main.cpp is wiring around
// it): its named parameters, the problem it builds from what it last heard (dead reckoning of the
// own ship over the report's age, targets extrapolated by eq. 3, the goal's speed and d_safety,
// the sampling box), the encounter memory's parameters, and the encounters it reports.
//
//   opp::NodeParams p;  opp::declare(ps, p);  ps.validate_and_apply();
//   std::vector<opp::Target> tg = opp::targets_at(tracks, age);
//   opp::Setup s = opp::build_setup(p, own, goal, tg, plan_index);
//   if (!s.arrived) r = planner.solve(s.request(warm), hooks);
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/opp/encounters.hpp"
#include "mpgc/opp/planner.hpp"
#include "mpgc/opp/replan.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::opp {

struct NodeParams {
  std::string planner = "rrtstar";  // plan.planner: which planner of the registry plans
  ConstraintParams constraints;     // plan.safety_distance (unless the goal sets it), max_turn, ...
  ObjectiveParams objective;        // plan.gamma_*
  Budget budget;                    // plan.max_iterations, plan.time_budget (seed: plan.seed + k)
  ReplanParams replan;
  int seed = 1;                  // [-] base seed; plan k uses seed + k
  double check_period = 0.5;     // [s] how often the re-planning conditions are checked
  double bounds_margin = 3000;   // [m] sampling box around start and goal
  double arrival_radius = 100;   // [m] no more plans once the own ship is this close to the goal
  double default_speed = 5;      // [m/s] when neither the goal nor the own state gives a speed
  double max_state_age = 5;      // [s] own state older than this is not planned from
  nav::JumpGateParams jumps;     // own position jumps are not planned from (timeout: max_state_age)
  double max_obstacle_age = 10;  // [s] moving obstacles older than this are not planned with
  double target_sigmas = 2;      // [-] a target is kept d_safety + this x its position sigma away
  double rule17c_range = 5.0;    // [-] x d_safety: colreg.port_turn_range (17(c) within it)
  double rule17c_lead = 0.4;     // [-] x d_safety: colreg.port_turn_lead
  double tracking_margin = 0.02; // [-] x d_safety, kept beyond d_safety from every target: the ship
                                 //     follows a plan to within metres, not exactly
  bool require_chart = true;     // no plan before obstacles/fixed said which region is known
  bool warm_start = true;        // seed the search with the previous path of the same goal
  bool pin_encounters = true;    // hold each leg to the obligation fixed at the encounter's start
  double encounter_cpa = 2.0;    // [-] x d_safety: a CPA inside it is a risk of collision
  double encounter_tcpa = 0;     // [s] risk of collision within this TCPA pins an encounter (0: the
                                 //     plan's horizon, the straight-line time to the goal)
  int speed_steps = 3;           // [-] lower speeds tried when no compliant path exists (0: none)
  double min_speed_fraction = 0.25;  // [-] the lowest of them, of the planned speed
  double speed_detour = 1.3;     // [-] ... also when the compliant plan is longer than this x the straight line
  bool emergency = true;         // no path at any speed: the emergency leg (emergency_path)
  double stand_on_time = 3.0;    // [-] ... and until the CPA is nearer than sailing this many d_safety takes
  double stand_on_steady = 60;   // [s] a new estimate of a hold's end this close to the last keeps it
  double stand_on_range = 3.5;   // [-] x d_safety: a stand-on ship keeps course and speed until a
                                 //     target it stands on for is this close (rule 17(a)); 0: no hold
  // Rule 13-15 sectors of the pinned and reported encounters (common colreg, not the planner's eq. 16 angle).
  double sector_abaft_beam = 0.39269908169872414;  // [rad] overtaking: more than this abaft the beam
  double sector_head_on = 0.39269908169872414;     // [rad] head-on: within this of each bow
  std::string memory_file;       // what a restart must remember (memory.hpp); "" = nothing kept
  double latency_per_iteration = 0;  // [s] simulated time one iteration takes (late plans); 0 = at once
};

// Declares every parameter of the component, the planners' own included (each planner of the
// registry declares its parameters into `ps`; `planners` receives them, by name).
void declare(rt::ParamSet& ps, NodeParams& p, std::vector<std::unique_ptr<Planner>>& planners);

// The own ship as last reported, in the local frame.
struct OwnReport {
  Vec2 p;                  // [m]
  double heading = 0;      // [rad]
  double sog = 0;          // [m/s] NaN: unknown (taken as 0)
  double cog = 0;          // [rad] NaN: unknown (the heading)
  double age = 0;          // [s] at the planning time
};
struct GoalSpec {
  Vec2 p;                    // [m]
  double heading = 0;        // [rad] NaN: any
  double heading_tolerance = 0;  // [rad]
  double cruise_speed = 0;   // [m/s] 0: the own speed (or default_speed)
  double safety_distance = 0;  // [m] 0: plan.safety_distance
  bool colreg = true;
};
struct TrackReport {
  uint32_t id = 0;
  Vec2 p, v;                 // [m], [m/s] at the report's time
  double position_std = 0;   // [m] one sigma, grown by the obstacle manager while unmeasured
};

// Targets at the planning time: each report extrapolated over its age `dt` [s] (eq. 3), with a
// margin of `sigmas` x its position sigma (a non-finite or negative sigma counts as 0).
std::vector<Target> targets_at(const std::vector<TrackReport>& tracks, double dt, double sigmas);

struct Setup {
  Problem problem;
  ConstraintParams constraints;      // with the goal's d_safety
  Budget budget;                     // seed of this plan
  colreg::ShipKinematics own;        // the own ship at the planning time (course and speed over ground)
  bool arrived = false;              // within arrival_radius of the goal: no plan
  // Keeps a reference to `problem`: the Setup must outlive the request.
  Request request(const ObjectiveParams& objective, std::vector<Vec2> warm) const {
    return Request{problem, constraints, objective, budget, std::move(warm)};
  }
};

// The chart as last published: its obstacles and the region they are complete for.
struct ChartView {
  const FixedObstacles* obstacles = nullptr;  // nullptr: none received
  std::optional<Bounds> region;               // nullopt: complete everywhere (tests); a chart published
                                              // whole comes with an infinite region
};

// The problem of plan number `plan_index` (its seed is seed + plan_index) from the own ship, the
// goal and the targets at the planning time, on the chart (the sampling box kept inside its region).
Setup build_setup(const NodeParams& p, const OwnReport& own, const GoalSpec& goal, std::vector<Target> targets,
                  const ChartView& chart, uint32_t plan_index);

// Why the node waits instead of planning on this chart: none received while require_chart, or a
// goal the chart's region does not cover with d_safety to spare (the obstacle manager re-publishes
// the region when the goal changes). "" = plan.
std::string chart_wait(const NodeParams& p, const Setup& s, bool have_chart);

// When a risk of collision pins an encounter, for this setup (encounter_cpa x d_safety; TCPA
// within the plan's horizon; released beyond d_COLREG).
EncounterMemoryParams encounter_params(const NodeParams& p, const Setup& s);

// Rule 17(a)(i): where one ship is to keep out of the way, the other keeps her course and speed.
// While a target the own ship stands on for (crossing stand-on, overtaken) is a risk of collision,
// and either farther than stand_on_range x d_safety or farther in time to the CPA than sailing
// stand_on_time x d_safety takes at the planned speed, and no target is pinned with a duty of the
// own ship (rule 16 comes first), the plan's first leg holds the present course and speed until
// both are reached (the earliest over such targets); only from there may the ship act (17(a)(ii),
// (b)).
struct StandOnHold {
  double time = 0;      // [s] how long the course and speed are held (0: no hold)
  double course = 0;    // [rad] the course held
  Vec2 end;             // [m] where the hold ends
  uint32_t target = 0;  // the target that ends it first
  std::string why_not;  // a stand-on risk exists but is not held for, and why ("" otherwise)
};
// `previous`: the previous plan's hold, its time counted from this plan. Its course is kept while
// the hold lasts (re-taking the present course at every plan would let the track-keeping's small
// corrections add up to a turn), and so is its end while a new estimate lies within
// plan.stand_on_steady of it (the TCPA of a ship overtaking slowly is noisy: ends jumping by a
// minute from plan to plan made guidance cut short holds and turn early, DNV 05).
StandOnHold stand_on_hold(const NodeParams& p, const Setup& s, const std::optional<StandOnHold>& previous = std::nullopt);

// Plans `s` with `planner`; with a hold, the path is the hold leg and then the planner's path from
// its end (targets advanced by eq. 3, times shifted), the reason saying so. When nothing can be
// planned from the hold's end the ship acts now: the plain plan, its reason naming the hold given up.
Result solve_with_hold(Planner& planner, const Setup& s, const ObjectiveParams& objective,
                       const StandOnHold& hold, std::vector<Vec2> warm, const Hooks& hooks);

// Seed 000 §2: "the speed is reduced if the steering action alone is not sufficient". When the
// plan at the planned speed is not COLREG-compliant (relaxed, or no path), or compliant only by a
// detour longer than speed_detour x the straight line to the goal, or only with the planner's own
// margin given up (Result::margin_reduced), the same problem is planned at speed_steps lower speeds
// evenly down to min_speed_fraction of it, and the compliant plan that arrives first is taken (the
// time lost by going slower is its cost), one keeping the margin before one that gave it up. With none compliant, the
// planned speed's plan stands, unless it had no path at all and a lower speed has one. With no path at any speed
// and `emergency`, emergency_path.
// Time along the plan (Waypoint::t) of the last closest approach to a target that comes within
// range on it (0: none does): when the plan has passed every ship it meets.
double last_meeting(const Result& r, const std::vector<Target>& targets, double range);
// Arrival time of a plan made at a reduced speed (Waypoint::t at that speed), sailed so until
// last_meeting and at `cruise` after, if the rest at cruise keeps every target beyond `clear` +
// its margin (the risk CPA: a ship followed is not passed); else the plan's own arrival time.
double resumed_arrival(const Result& r, const std::vector<Target>& targets, double range, double clear,
                       double cruise);

struct NodePlan {
  Result result;
  std::vector<double> speeds;   // [m/s] per waypoint: the speed of the leg that ends there
  double speed_fraction = 1.0;  // [-] of the planned speed, after any stand-on hold
  bool emergency = false;
};
// A planner that keeps its plan (Planner::keeps_plan) and keeps `warm` at the planned speed is
// done; when the planned speed would try slower ones, it is first asked at warm's own speed
// (warm_fraction of the planned speed), and keeping it there is the plan, sailed at that speed
// (rule 8(b): the manoeuvre being made is carried on, not replaced by a new one at each re-plan).
NodePlan plan_node(Planner& planner, const NodeParams& p, const Setup& s, const ObjectiveParams& objective,
                   const StandOnHold& hold, const std::vector<Vec2>& warm, const Hooks& hooks,
                   double warm_fraction = 1.0);

// Rule 17(b) / 2(b), when nothing can be planned: one leg, for the time a leg of d_safety takes at
// min_speed_fraction of the planned speed, on the course among own course + {max_turn,
// max_turn/2, 0, -max_turn/2, -max_turn} (starboard first) and at min_speed_fraction or the
// planned speed (reduced first, rule 8(e)), that keeps clear of fixed obstacles (as far as the
// start is) and passes farthest from the targets (eq. 3) within that time; an earlier candidate
// is kept unless a later one passes 10 % farther. Its speed fraction goes to `speed_fraction`.
// Status kRelaxed, not compliant, the reason starting "emergency". Empty path when every course
// meets a fixed obstacle.
Result emergency_path(const NodeParams& p, const Setup& s, const std::string& why, double* speed_fraction = nullptr);

// One target as the planner reports it (plan/encounters): rule 13-15 assessment and bearing.
struct EncounterReport {
  uint32_t id = 0;
  colreg::Assessment assessment;
  double bearing = 0;  // [rad] true bearing from the own ship
};
// Every target that can be assessed; `rejected` receives why one could not (non-finite input).
std::vector<EncounterReport> report_encounters(const NodeParams& p, const Setup& s, std::vector<std::string>* rejected);

}  // namespace mpgc::opp
