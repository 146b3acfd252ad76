// The guidance-and-control supervisor: plans in, own state in, rudder and rpm out at a fixed rate.
// It keeps following the last valid plan while the planner computes the next one, joins a new plan
// from where the ship is (at the plan's effective time: a late plan replaces the old one only when
// it takes effect), rejects bad plans without dropping the good one, and has a defined safe
// behaviour for every missing input (README "Modes"):
//
//   * no valid plan (the planner reports no path / invalid input, or sends bad plans): keep
//     following the last valid plan while it is younger than plan_max_age (its clearance was
//     computed against target predictions that age), reported as degraded; then safe mode.
//   * no plan at all for plan_max_age (none since the start, or the last one aged out): safe mode.
//   * safe mode: hold the heading the ship had when it was entered (no turn into the unknown) and
//     slow to `safe_speed` (steerage is kept). It ends when the next valid plan is joined.
//   * own state missing or older than nav_timeout: nothing to steer by, so the rudder goes
//     amidships and the rpm is reduced to the feed-forward of safe_speed (never raised), reported
//     as safe mode; the next fresh state ends it.
//   * own position jumping farther than the ship can go (nav/jump_gate.hpp): refused, so the ship
//     is steered by the last good state and after nav_timeout is in safe mode as above; a new place
//     is taken once the old state is stale and a second state agrees with it.
//
//   GuidanceController gc(params);                   // validates every field
//   gc.on_plan(plan, t); gc.on_nav(nav, t);          // "" or why the input was refused
//   Command cmd = gc.step(t);                        // every control period
//
// No DDS, no clock, no global state: every call takes the time t [s] on the run's clock.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mpgc/guidance_control/autopilot.hpp"
#include "mpgc/guidance_control/path_follower.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/ship/actuator_limits.hpp"

namespace mpgc::guidance_control {

enum class Mode { Idle, Following, Arrived, SafeMode };
const char* to_string(Mode m);

enum class PlanKind { Ok, Relaxed, NoPath, InvalidInput };

struct PlanInput {
  uint32_t plan_id = 0;             // [-]
  PlanKind kind = PlanKind::Ok;
  std::string reason;               // planner's reason for NoPath / InvalidInput
  double stamp = 0.0;               // [s] time of the plan on the run's clock; NaN when unknown
  double effective = 0.0;           // [s] when the plan takes effect (the previous one is followed until
                                    //     then); 0 or <= the receive time: at once
  std::vector<PathPoint> waypoints;
};

struct NavInput {
  double x = 0.0;        // [m] north
  double y = 0.0;        // [m] east
  double heading = 0.0;  // [rad]
  double u = 0.0;        // [m/s] surge speed
  double r = 0.0;        // [rad/s] yaw rate
};
// Empty when usable, else the reason (non-finite field, |x|,|y| > 1e7 m, |u| > 50 m/s, |r| > 1 rad/s).
std::string check_nav(const NavInput& n);

struct GuidanceControlParams {
  PathFollowerParams follower;
  HeadingAutopilotParams heading;
  SpeedControllerParams speed;
  double plan_max_age = 60.0;  // [s] a plan older than this (from its stamp) is not followed: safe mode
                               //     (4 re-planning periods of 15 s)
  double nav_timeout = 5.0;    // [s] own state older than this -> safe mode, rudder amidships
  // A position jump no ship can make is refused while the last state is younger than nav_timeout
  // (nav/jump_gate.hpp; its own timeout is not used): the ship is steered by the last good state,
  // then safe mode.
  nav::JumpGateParams jumps;
  double safe_speed = 3.0;     // [m/s] speed in safe mode (KVLCC2 keeps steerage at about 6 kn)
  double arrival_speed = 0.0;  // [m/s] speed once the last waypoint is reached
  double max_dt = 1.0;         // [s] longest time step the integrators take (pauses are clipped)
  // The actuator limits these parameters describe (heading.max_rudder/_rate, speed.min/max_rpm).
  ship::ActuatorLimits actuator_limits() const {
    return {heading.max_rudder, heading.max_rudder_rate, speed.min_rpm, speed.max_rpm};
  }
  void validate() const;       // throws std::invalid_argument naming the bad field
};

struct Status {
  Mode mode = Mode::Idle;
  bool degraded = false;  // an input is missing or bad (always in SafeMode; also while following
                          // the last valid plan because the planner has none)
  std::string detail;
  uint32_t plan_id = 0;
  uint32_t active_waypoint = 0;
  double cross_track_error = 0.0;  // [m]
  double along_track = 0.0;        // [m]
  double desired_heading = 0.0;    // [rad]
  double desired_speed = 0.0;      // [m/s]
};

struct Command {
  double rudder = 0.0;         // [rad] within +-max_rudder
  double propeller_rpm = 0.0;  // [1/min] within [min_rpm, max_rpm]
  bool rudder_saturated = false;  // the controller asked for more than max_rudder (clipped)
  bool rpm_saturated = false;     // the controller asked for an rpm outside the range (clipped)
  Status status;
};

class GuidanceController {
 public:
  explicit GuidanceController(const GuidanceControlParams& p);

  // A plan from the planner, received at time t [s]. Returns an empty string when taken, else the
  // reason it was rejected (the last good plan is then kept, the rejection reported as degraded).
  // NoPath / InvalidInput plans are taken (they are valid messages): the last valid plan is kept
  // while younger than plan_max_age, then safe mode. A plan with effective > t is held until the
  // step at which t reaches it (a newer held plan replaces an older one; one taking effect at once
  // drops an older held one: plans apply in the order they came).
  std::string on_plan(const PlanInput& plan, double t);
  // Own state at time t [s]. Returns an empty string when taken, else why it was rejected.
  std::string on_nav(const NavInput& nav, double t);
  // One control cycle at time t [s].
  Command step(double t);

  Mode mode() const { return mode_; }
  const GuidanceControlParams& params() const { return p_; }
  const PathFollower& follower() const { return follower_; }
  // The plan held until its effective time, if any: id and effective time [s].
  std::optional<std::pair<uint32_t, double>> held_plan() const {
    if (!held_) return std::nullopt;
    return std::make_pair(held_->plan_id, held_->effective);
  }

 private:
  void enter_safe(const std::string& why);
  void join(const PlanInput& plan, double t_recv, const NavInput& nav);

  GuidanceControlParams p_;
  PathFollower follower_;
  HeadingAutopilot heading_;
  SpeedController speed_;

  Mode mode_ = Mode::Idle;
  std::string detail_ = "no plan yet";
  std::optional<PlanInput> pending_;  // taken, to be joined at the next step (needs the position)
  double pending_t_ = 0.0;            // [s] when the pending plan was received
  std::optional<PlanInput> held_;     // taken, waiting for its effective time
  double held_t_ = 0.0;               // [s] when the held plan was received
  uint32_t plan_id_ = 0;
  double plan_t_ = 0.0;               // [s] age reference of the plan followed (its stamp, else its receipt)
  bool have_plan_time_ = false;
  std::string issue_;                 // why the planner has no valid plan for us ("" while it has)
  double start_t_ = 0.0;              // [s] first step (staleness reference before any plan)
  bool started_ = false;

  std::optional<NavInput> nav_;
  nav::JumpGate jumps_;
  double nav_t_ = 0.0;
  double last_t_ = 0.0;
  bool nav_lost_ = false;
  std::string nav_lost_detail_;
  double hold_heading_ = 0.0;  // [rad] in Idle / SafeMode
  double hold_speed_ = 0.0;    // [m/s] in Idle
  bool hold_set_ = false;
  double last_rpm_ = -1.0;     // [1/min] last rpm command (< 0: none yet)
};

}  // namespace mpgc::guidance_control
