// mpgc_guidance_control: plan/path + nav/own_state -> control/actuators + guidance/status.
// Wiring only: messages are converted at the edge; the GuidanceController library decides
// (its parameters and news: mpgc/guidance_control/node.hpp).
#include <memory>
#include <string>

#include "mpgc/dds/dds.hpp"
#include "mpgc/guidance_control/guidance_control.hpp"
#include "mpgc/guidance_control/node.hpp"
#include "mpgc/guidance_control/validate.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace gc = mpgc::guidance_control;
namespace msg = mpgc::msg;
using mpgc::dds::QosProfile;

namespace {

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
  gc::NodeParams p;
  mpgc::rt::ParamSet ps;
  gc::declare(ps, p);
  return mpgc::rt::run_component("guidance_control", argc, argv, ps, [&](mpgc::rt::Component& c) {
    const gc::GuidanceControlParams cp = gc::controller_params(p);
    c.log().info("heading PID kp={:.3f} ki={:.5f} kd={:.1f}; speed map {}", cp.heading.kp, cp.heading.ki,
                 cp.heading.kd, gc::format_speed_map(cp.speed));
    auto ctl = std::make_shared<gc::GuidanceController>(cp);  // validates every field
    auto t_now = [&c] { return static_cast<double>(c.now_ns()) * 1e-9; };

    auto& cmd_out = c.publisher<msg::ActuatorCommand>(mpgc::topics::kActuators, QosProfile::command());
    auto& status_out = c.publisher<msg::GuidanceStatus>(mpgc::topics::kGuidanceStatus, QosProfile::state());

    c.subscribe<msg::Path>(mpgc::topics::kPath, QosProfile::latched(), [&c, ctl, t_now](const msg::Path& m) {
      const std::string why = ctl->on_plan(gc::to_plan(m), t_now());
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

    c.subscribe<msg::NavState>(mpgc::topics::kOwnState, QosProfile::state(), [&c, ctl, t_now](const msg::NavState& m) {
      bool rate_missing = false;
      const gc::NavInput in = gc::to_nav(m, &rate_missing);
      if (rate_missing) c.count("nav.rate_missing");  // the PID loses its damping term
      const std::string why = ctl->on_nav(in, t_now());
      if (!why.empty()) c.reject(mpgc::topics::kOwnState, why);
    }, [](const msg::NavState& m) { return gc::check_nav(m); });

    auto news = std::make_shared<gc::ModeNews>();
    c.every(1.0 / p.rate, [&c, &cmd_out, &status_out, ctl, t_now, news] {
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
      if (news->changed(st)) {
        if (st.degraded) c.log().warn("mode {}: {}", gc::to_string(st.mode), st.detail);
        else c.log().info("mode {}: {}", gc::to_string(st.mode), st.detail);
        c.set_health(st.degraded ? msg::HealthState::HEALTH_DEGRADED : msg::HealthState::HEALTH_OK,
                     st.degraded ? st.detail : "");
      }
    });
  });
}
