// mpgc_guidance_control: plan/path + nav/own_state -> control/actuators + guidance/status.
// Wiring only: messages are converted at the edge; the GuidanceController library decides.
#include <cmath>
#include <string>

#include "mpgc/dds/dds.hpp"
#include "mpgc/guidance_control/guidance_control.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/nav/jump_gate.hpp"
#include "mpgc/topics.hpp"
#include "mpgc/guidance_control/validate.hpp"

namespace gc = mpgc::guidance_control;
namespace msg = mpgc::msg;
using mpgc::dds::QosProfile;

namespace {

using mpgc::guidance_control::to_plan;

struct Params {
  gc::GuidanceControlParams gc;
  double rate = 2.0;  // [Hz] control cycle
  std::string speed_map;
  double nomoto_K = 0.0, nomoto_T = 0.0, omega_n = 0.0, zeta = 1.0, integral_ratio = 20.0;
};

void declare(mpgc::rt::ParamSet& ps, Params& p) {
  const gc::GuidanceControlParams d;
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
  ps.add("speed.map", &p.speed_map, gc::format_speed_map(d.speed), "speed:rpm pairs [m/s]:[1/min], calm-water feed-forward");
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
  mpgc::nav::declare_params(ps, &p.gc.jumps);
  ps.add("nav.timeout", &p.gc.nav_timeout, d.nav_timeout, "s", 0.1, 600.0,
         "own state older than this -> safe mode, rudder amidships, rpm reduced to safe_speed's");
  ps.add("safe_speed", &p.gc.safe_speed, d.safe_speed, "m/s", 0.1, 30.0, "speed in safe mode (heading held)");
  ps.add("arrival_speed", &p.gc.arrival_speed, d.arrival_speed, "m/s", 0.0, 30.0, "speed after the last waypoint");
}

msg::GuidanceMode to_msg(gc::Mode m) {
  switch (m) {
    case gc::Mode::Idle: return msg::GuidanceMode::GUIDANCE_IDLE;
    case gc::Mode::Following: return msg::GuidanceMode::GUIDANCE_FOLLOWING;
    case gc::Mode::Arrived: return msg::GuidanceMode::GUIDANCE_ARRIVED;
    case gc::Mode::SafeMode: return msg::GuidanceMode::GUIDANCE_SAFE_MODE;
  }
  return msg::GuidanceMode::GUIDANCE_SAFE_MODE;
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  mpgc::rt::ParamSet ps;
  declare(ps, p);
  return mpgc::rt::run_component("guidance_control", argc, argv, ps, [&](mpgc::rt::Component& c) {
    gc::parse_speed_map(p.speed_map, p.gc.speed);
    if (p.nomoto_K > 0.0)
      p.gc.heading = gc::tune_heading_pid({p.nomoto_K, p.nomoto_T}, p.omega_n, p.zeta, p.gc.heading, p.integral_ratio);
    c.log().info("heading PID kp={:.3f} ki={:.5f} kd={:.1f}; speed map {}", p.gc.heading.kp, p.gc.heading.ki,
                 p.gc.heading.kd, gc::format_speed_map(p.gc.speed));
    auto ctl = std::make_shared<gc::GuidanceController>(p.gc);  // validates every field
    auto t_now = [&c] { return static_cast<double>(c.now_ns()) * 1e-9; };

    auto& cmd_out = c.publisher<msg::ActuatorCommand>(mpgc::topics::kActuators, QosProfile::command());
    auto& status_out = c.publisher<msg::GuidanceStatus>(mpgc::topics::kGuidanceStatus, QosProfile::state());

    c.subscribe<msg::Path>(mpgc::topics::kPath, QosProfile::latched(), [&c, ctl, t_now](const msg::Path& m) {
      const std::string why = ctl->on_plan(to_plan(m), t_now());
      if (!why.empty()) {
        c.reject(mpgc::topics::kPath, "plan " + std::to_string(m.plan_id) + ": " + why + " (last good plan kept)");
        return;
      }
      if (const auto held = ctl->held_plan(); held && held->first == m.plan_id)
        c.log().info("plan {} held until it takes effect at t = {:.1f} s: status {}, {} waypoints {}", m.plan_id,
                     held->second, static_cast<int>(m.status), m.waypoints.size(), m.reason);
      else
        c.log().info("plan {} taken: status {}, {} waypoints {}", m.plan_id, static_cast<int>(m.status),
                     m.waypoints.size(), m.reason);
    });

    constexpr uint32_t kNeeded = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID;
    c.subscribe<msg::NavState>(mpgc::topics::kOwnState, QosProfile::state(), [&c, ctl, t_now](const msg::NavState& m) {
      if ((m.valid_mask & kNeeded) != kNeeded) {
        c.reject(mpgc::topics::kOwnState, "position, heading or velocity not valid (valid_mask " +
                                              std::to_string(m.valid_mask) + ")");
        return;
      }
      double r = m.r;
      if ((m.valid_mask & msg::NAV_RATE_VALID) == 0) {
        r = 0.0;  // no yaw rate: the PID loses its damping term, so count it
        c.count("nav.rate_missing");
      }
      const std::string why = ctl->on_nav({m.x, m.y, m.heading, m.u, r}, t_now());
      if (!why.empty()) c.reject(mpgc::topics::kOwnState, why);
    });

    auto last_mode = std::make_shared<gc::Mode>(gc::Mode::Idle);
    auto last_detail = std::make_shared<std::string>();
    c.every(1.0 / p.rate, [&c, &cmd_out, &status_out, ctl, t_now, last_mode, last_detail] {
      const gc::Command cmd = ctl->step(t_now());
      const gc::Status& st = cmd.status;
      // The controller asked beyond a limit and the order was clipped to it (counted per cycle).
      if (cmd.rudder_saturated) c.count("saturated.rudder");
      if (cmd.rpm_saturated) c.count("saturated.rpm");
      msg::ActuatorCommand a;
      a.header = c.header();
      a.rudder = cmd.rudder;
      a.propeller_rpm = cmd.propeller_rpm;
      cmd_out.write(a);
      msg::GuidanceStatus s;
      s.header = a.header;
      s.mode = to_msg(st.mode);
      s.detail = st.detail;
      s.plan_id = st.plan_id;
      s.active_waypoint = st.active_waypoint;
      s.cross_track_error = st.cross_track_error;
      s.along_track = st.along_track;
      s.desired_heading = st.desired_heading;
      s.desired_speed = st.desired_speed;
      status_out.write(s);
      if (st.mode != *last_mode || st.detail != *last_detail) {
        if (st.degraded) c.log().warn("mode {}: {}", gc::to_string(st.mode), st.detail);
        else c.log().info("mode {}: {}", gc::to_string(st.mode), st.detail);
        c.set_health(st.degraded ? msg::HealthState::HEALTH_DEGRADED : msg::HealthState::HEALTH_OK,
                     st.degraded ? st.detail : "");
        *last_mode = st.mode;
        *last_detail = st.detail;
      }
    });
  });
}
