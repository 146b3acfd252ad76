// Target ships: kinematic movers that follow a route (course/speed legs or waypoints) and
// scripted "unexpected" manoeuvres at given times (seed 000 §7); optionally with a rule-following
// helmsman (behaviour colreg, helmsman.hpp) that overrides the route while it gives way or stands on.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/ship_simulator/helmsman.hpp"

namespace mpgc::ship_simulator {

struct RouteLeg {
  double course = 0.0;    // [rad] course over ground, clockwise from north
  double speed = 0.0;     // [m/s]
  double duration = 0.0;  // [s] time on this leg; the last leg lasts forever (0 allowed there)
};

struct RouteWaypoint {
  double x = 0.0;      // [m] north
  double y = 0.0;      // [m] east
  double speed = 0.0;  // [m/s] speed towards this waypoint
};

// A scripted manoeuvre: from time `at` the target steers `course` at `speed`, for `duration`
// (0 = for the rest of the run), then returns to its route.
struct ScriptedManoeuvre {
  double at = 0.0;        // [s] simulation time it starts
  double course = 0.0;    // [rad]
  double speed = -1.0;    // [m/s]; negative keeps the current ordered speed
  double duration = 0.0;  // [s] 0 = permanent
};

enum class TargetBehaviour {
  kRoute,   // follows its route and scripted manoeuvres, whatever the other ships do
  kColreg,  // the same, but a Helmsman gives way or stands on by COLREG (helmsman.hpp)
};

struct TargetConfig {
  uint32_t mmsi = 0;                 // [-] 9 digits
  std::string name;
  double x0 = 0.0, y0 = 0.0;         // [m] start position
  double course0 = 0.0;              // [rad] start course
  double speed0 = 0.0;               // [m/s] start speed
  std::vector<RouteLeg> legs;        // either legs ...
  std::vector<RouteWaypoint> waypoints;  // ... or waypoints (then legs must be empty)
  std::vector<ScriptedManoeuvre> manoeuvres;
  double max_turn_rate = 0.0;        // [rad/s] (ROT limit of the course changes)
  double max_accel = 0.0;            // [m/s^2] speed change limit
  double waypoint_radius = 0.0;      // [m] acceptance radius of a waypoint
  double length = 0.0, beam = 0.0;   // [m]
  uint8_t nav_status = 0;            // [-] ITU-R M.1371 navigational status (1 anchored, 5 moored)
  TargetBehaviour behaviour = TargetBehaviour::kRoute;
  HelmsmanParams helmsman;           // used with behaviour kColreg only
  void validate() const;             // throws std::invalid_argument naming the field
};

struct TargetState {
  double x = 0.0, y = 0.0;  // [m]
  double course = 0.0;      // [rad] course over ground (= heading: targets do not drift)
  double speed = 0.0;       // [m/s]
  double rot = 0.0;         // [rad/s] rate of turn over the last step
};

class TargetShip {
 public:
  explicit TargetShip(TargetConfig cfg);
  // Advances from time t to t + dt: orders from the route/manoeuvres at t, then turns and
  // accelerates within the limits (explicit, exact for piecewise-constant rate).
  void step(double t, double dt);
  // The same with the other ships it sees at t (the own ship and the other targets): a colreg
  // target's helmsman may override the route's orders; a route target ignores `others`.
  void step(double t, double dt, const std::vector<SeenShip>& others);
  // The helmsman's mode (kRoute for a route target).
  HelmMode helm_mode() const { return helm_ ? helm_->mode() : HelmMode::kRoute; }
  const TargetState& state() const { return s_; }
  const TargetConfig& config() const { return cfg_; }
  // Course and speed the target is ordered to hold at time t (for tests).
  void ordered(double t, double* course, double* speed);

 private:
  TargetConfig cfg_;
  TargetState s_;
  std::size_t wp_ = 0;  // next waypoint
  std::optional<Helmsman> helm_;  // behaviour kColreg only
  double route_course_ = 0.0, route_speed_ = 0.0;  // [rad], [m/s] the route's last order (before manoeuvres)
  void move(double course, double speed, double dt);
};

}  // namespace mpgc::ship_simulator
