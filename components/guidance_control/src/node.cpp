#include "mpgc/guidance_control/node.hpp"

#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::guidance_control {

void declare(rt::ParamSet& ps, NodeParams& p) {
  const GuidanceControlParams d;
  auto& f = p.gc.follower;
  auto& h = p.gc.heading;
  auto& s = p.gc.speed;
  ps.add("rate", &p.rate, 2.0, "Hz", 0.1, 50.0, "control cycle: actuator commands and status per second");
  ps.add("los.lookahead", &f.lookahead, d.follower.lookahead, "m", 10.0, 1e5, "LOS lookahead distance (default 2.5 Lpp of KVLCC2)");
  ps.add("los.acceptance_radius", &f.acceptance_radius, d.follower.acceptance_radius, "m", 1.0, 1e5,
         "circle of acceptance around a waypoint (default 2.5 Lpp of KVLCC2)");
  ps.add("los.integral", &f.integral, d.follower.integral, "ILOS: integral action against current");
  ps.add("los.integral_gain", &f.integral_gain, d.follower.integral_gain, "-", 0.01, 0.99, "ILOS kappa");
  ps.add("los.integral_limit", &f.integral_limit, d.follower.integral_limit, "m", 0.0, 1e5, "bound of kappa * y_int");
  ps.add("los.integral_zone", &f.integral_zone, d.follower.integral_zone, "m", 1.0, 1e5,
         "ILOS integrates only while |cross-track| < this (> lookahead * current / speed)");
  ps.add("los.default_speed", &f.default_speed, d.follower.default_speed, "m/s", 0.1, 30.0,
         "speed where a waypoint carries none");
  ps.add("los.max_speed", &f.max_speed, d.follower.max_speed, "m/s", 0.1, 30.0, "planned speeds are clamped to this");
  ps.add("heading.kp", &h.kp, d.heading.kp, "rad/rad", 0.0, 100.0, "heading PID proportional gain");
  ps.add("heading.ki", &h.ki, d.heading.ki, "1/s", 0.0, 10.0, "heading PID integral gain");
  ps.add("heading.kd", &h.kd, d.heading.kd, "s", 0.0, 1e4, "heading PID gain on the measured yaw rate");
  // The actuator limits' defaults are the default ship's (mpgc/ship/actuator_limits.hpp), the ones the
  // simulator's KVLCC2 obeys; on another ship set them to its steering gear's and engine's.
  ps.add("heading.max_rudder", &h.max_rudder, d.heading.max_rudder, "rad", 0.01, 1.0,
         "rudder angle limit: the steering gear's (KVLCC2 35 deg); orders are clipped to it");
  ps.add("heading.max_rudder_rate", &h.max_rudder_rate, d.heading.max_rudder_rate, "rad/s", 0.001, 1.0,
         "rudder rate limit: the steering gear's (KVLCC2 2.32 deg/s)");
  ps.add("heading.integral_limit", &h.integral_limit, d.heading.integral_limit, "rad", 0.0, 1.0,
         "bound of the integral's rudder contribution");
  ps.add("heading.nomoto_K", &p.nomoto_K, 0.0, "1/s", 0.0, 10.0,
         "if > 0: compute kp, ki, kd by pole placement from Nomoto K, T, omega_n, zeta (README)");
  ps.add("heading.nomoto_T", &p.nomoto_T, 0.0, "s", 0.0, 1e4, "Nomoto time constant for pole placement");
  ps.add("heading.omega_n", &p.omega_n, 0.0, "rad/s", 0.0, 10.0, "closed-loop natural frequency for pole placement");
  ps.add("heading.zeta", &p.zeta, 1.0, "-", 0.1, 5.0, "closed-loop damping for pole placement");
  ps.add("heading.integral_ratio", &p.integral_ratio, 20.0, "-", 1.0, 1000.0,
         "pole placement: ki = omega_n kp / integral_ratio (Fossen: 10)");
  ps.add("speed.map", &p.speed_map, format_speed_map(d.speed), "speed:rpm pairs [m/s]:[1/min], calm-water feed-forward");
  ps.add("speed.kp", &s.kp, d.speed.kp, "rpm/(m/s)", 0.0, 1000.0, "speed PI proportional gain");
  ps.add("speed.ki", &s.ki, d.speed.ki, "rpm/m", 0.0, 100.0, "speed PI integral gain");
  ps.add("speed.integral_limit", &s.integral_limit, d.speed.integral_limit, "1/min", 0.0, 1000.0,
         "bound of the integral's contribution");
  ps.add("speed.integral_zone", &s.integral_zone, d.speed.integral_zone, "m/s", 0.001, 100.0,
         "speed PI integrates only while |speed error| < this");
  ps.add("speed.min_rpm", &s.min_rpm, d.speed.min_rpm, "1/min", -1000.0, 1000.0, "lowest rpm command (the engine's)");
  ps.add("speed.max_rpm", &s.max_rpm, d.speed.max_rpm, "1/min", 0.0, 1000.0, "highest rpm command (the engine's)");
  ps.add("speed.max_rpm_rate", &s.max_rpm_rate, d.speed.max_rpm_rate, "1/min/s", 0.01, 1000.0, "rpm slew limit");
  ps.add("plan.max_age", &p.gc.plan_max_age, d.plan_max_age, "s", 1.0, 86400.0,
         "the plan followed may be this old (from its stamp); then, without a newer valid one, safe mode");
  nav::declare_params(ps, &p.gc.jumps);
  ps.add("nav.timeout", &p.gc.nav_timeout, d.nav_timeout, "s", 0.1, 600.0,
         "own state older than this -> safe mode, rudder amidships, rpm reduced to safe_speed's");
  ps.add("safe_speed", &p.gc.safe_speed, d.safe_speed, "m/s", 0.1, 30.0, "speed in safe mode (heading held)");
  ps.add("arrival_speed", &p.gc.arrival_speed, d.arrival_speed, "m/s", 0.0, 30.0, "speed after the last waypoint");
}

GuidanceControlParams controller_params(const NodeParams& p) {
  GuidanceControlParams g = p.gc;
  parse_speed_map(p.speed_map, g.speed);
  if (p.nomoto_K > 0.0) g.heading = tune_heading_pid({p.nomoto_K, p.nomoto_T}, p.omega_n, p.zeta, g.heading, p.integral_ratio);
  return g;
}

bool ModeNews::changed(const Status& s) {
  if (s.mode == mode_ && s.detail == detail_) return false;
  mode_ = s.mode;
  detail_ = s.detail;
  return true;
}

}  // namespace mpgc::guidance_control
