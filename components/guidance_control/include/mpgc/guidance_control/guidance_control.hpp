// The guidance-and-control supervisor: plans in, own state in, rudder and rpm out at a fixed rate.
// It keeps following the last valid plan while the planner computes the next one, joins a new plan
// from where the ship is, rejects bad plans without dropping the good one, and enters a defined
// safe mode when the planner reports no path or no valid plan has arrived for too long.
//
// Safe mode: hold the heading the ship had when safe mode was entered (no turn into the unknown) and
// slow down to `safe_speed` (steerage is kept). It ends when the next valid plan arrives.
// Without navigation data (none yet, or older than nav_timeout) the rudder goes midships and the
// rpm to the feed-forward of safe_speed, also reported as safe mode.
// No DDS, no clock: every call takes the time t [s] on the run's clock.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/guidance_control/autopilot.hpp"
#include "mpgc/guidance_control/path_follower.hpp"

namespace mpgc::guidance_control {

enum class Mode { Idle, Following, Arrived, SafeMode };
const char* to_string(Mode m);

enum class PlanKind { Ok, Relaxed, NoPath, InvalidInput };

struct PlanInput {
  uint32_t plan_id = 0;             // [-]
  PlanKind kind = PlanKind::Ok;
  std::string reason;               // planner's reason for NoPath / InvalidInput
  double stamp = 0.0;               // [s] time of the plan on the run's clock; NaN when unknown
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
  double plan_timeout = 60.0;  // [s] no valid plan for this long -> safe mode (4 re-planning periods of 15 s)
  double nav_timeout = 5.0;    // [s] own state older than this -> safe mode, rudder midships
  double safe_speed = 3.0;     // [m/s] speed in safe mode (KVLCC2 keeps steerage at about 6 kn)
  double arrival_speed = 0.0;  // [m/s] speed once the last waypoint is reached
  double max_dt = 1.0;         // [s] longest time step the integrators take (pauses are clipped)
  void validate() const;       // throws std::invalid_argument naming the bad field
};

struct Status {
  Mode mode = Mode::Idle;
  std::string detail;
  uint32_t plan_id = 0;
  uint32_t active_waypoint = 0;
  double cross_track_error = 0.0;  // [m]
  double along_track = 0.0;        // [m]
  double desired_heading = 0.0;    // [rad]
  double desired_speed = 0.0;      // [m/s]
};

struct Command {
  double rudder = 0.0;         // [rad]
  double propeller_rpm = 0.0;  // [1/min]
  Status status;
};

class GuidanceController {
 public:
  explicit GuidanceController(const GuidanceControlParams& p);

  // A plan from the planner, received at time t [s]. Returns an empty string when taken, else the
  // reason it was rejected (the last good plan is then kept). NoPath / InvalidInput plans are taken
  // (they are valid messages) and put the controller in safe mode.
  std::string on_plan(const PlanInput& plan, double t);
  // Own state at time t [s]. Returns an empty string when taken, else why it was rejected.
  std::string on_nav(const NavInput& nav, double t);
  // One control cycle at time t [s].
  Command step(double t);

  Mode mode() const { return mode_; }
  const GuidanceControlParams& params() const { return p_; }
  const PathFollower& follower() const { return follower_; }

 private:
  void enter_safe(const std::string& why);

  GuidanceControlParams p_;
  PathFollower follower_;
  HeadingAutopilot heading_;
  SpeedController speed_;

  Mode mode_ = Mode::Idle;
  std::string detail_ = "no plan yet";
  std::optional<PlanInput> pending_;  // taken, to be joined at the next step (needs the position)
  double pending_t_ = 0.0;            // [s] when the pending plan was received
  uint32_t plan_id_ = 0;
  double plan_t_ = 0.0;               // [s] when the plan being followed was received
  bool have_plan_time_ = false;
  double start_t_ = 0.0;              // [s] first step (staleness reference before any plan)
  bool started_ = false;

  std::optional<NavInput> nav_;
  double nav_t_ = 0.0;
  double last_t_ = 0.0;
  bool nav_lost_ = false;
  double hold_heading_ = 0.0;  // [rad] in Idle / SafeMode
  double hold_speed_ = 0.0;    // [m/s] in Idle
  bool hold_set_ = false;
};

}  // namespace mpgc::guidance_control
