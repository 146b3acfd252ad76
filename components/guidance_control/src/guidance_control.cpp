#include "mpgc/guidance_control/guidance_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mpgc::guidance_control {

namespace {
std::string seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f s", s);
  return buf;
}
}  // namespace

const char* to_string(Mode m) {
  switch (m) {
    case Mode::Idle: return "idle";
    case Mode::Following: return "following";
    case Mode::Arrived: return "arrived";
    case Mode::SafeMode: return "safe_mode";
  }
  return "?";
}

std::string check_nav(const NavInput& n) {
  if (!std::isfinite(n.x) || !std::isfinite(n.y)) return "non-finite position";
  if (!std::isfinite(n.heading)) return "non-finite heading";
  if (!std::isfinite(n.u)) return "non-finite surge speed";
  if (!std::isfinite(n.r)) return "non-finite yaw rate";
  if (std::abs(n.x) > 1e7 || std::abs(n.y) > 1e7) return "position more than 1e7 m from the origin";
  if (std::abs(n.u) > 50.0) return "surge speed beyond 50 m/s";
  if (std::abs(n.r) > 1.0) return "yaw rate beyond 1 rad/s";
  return {};
}

void GuidanceControlParams::validate() const {
  follower.validate();
  heading.validate();
  speed.validate();
  // The rudder and rpm limits are the ship's: checked as the one description checks them.
  actuator_limits().validate("guidance_control actuator limits");
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!pos(plan_max_age)) throw std::invalid_argument("GuidanceControlParams.plan_max_age must be finite and > 0 s");
  if (!pos(nav_timeout)) throw std::invalid_argument("GuidanceControlParams.nav_timeout must be finite and > 0 s");
  nav::JumpGateParams{jumps.max_speed, jumps.margin, nav_timeout}.validate();
  if (!pos(safe_speed)) throw std::invalid_argument("GuidanceControlParams.safe_speed must be finite and > 0 m/s");
  if (!std::isfinite(arrival_speed) || arrival_speed < 0.0)
    throw std::invalid_argument("GuidanceControlParams.arrival_speed must be finite and >= 0 m/s");
  if (!pos(max_dt)) throw std::invalid_argument("GuidanceControlParams.max_dt must be finite and > 0 s");
}

namespace {
const GuidanceControlParams& validated(const GuidanceControlParams& p) {
  p.validate();
  return p;
}
}  // namespace

GuidanceController::GuidanceController(const GuidanceControlParams& p)
    : p_(validated(p)),
      follower_(p.follower),
      heading_(p.heading),
      speed_(p.speed),
      jumps_(nav::JumpGateParams{p.jumps.max_speed, p.jumps.margin, p.nav_timeout}) {}

std::string GuidanceController::on_plan(const PlanInput& plan, double t) {
  if (!std::isfinite(t)) return "non-finite receive time";
  // A refused plan leaves the ship on the last valid one, but says so (degraded) until a valid one.
  auto refuse = [&](const std::string& why) {
    issue_ = "plan " + std::to_string(plan.plan_id) + " rejected: " + why;
    return why;
  };
  if (plan.kind == PlanKind::Ok || plan.kind == PlanKind::Relaxed) {
    const std::string why = check_path(plan.waypoints);
    if (!why.empty()) return refuse(why);
  }
  if (std::isfinite(plan.stamp) && t - plan.stamp > p_.plan_max_age)
    return refuse("plan is " + seconds(t - plan.stamp) + " old (plan_max_age " + seconds(p_.plan_max_age) + ")");
  if (!std::isfinite(plan.effective)) return refuse("non-finite effective time");
  if (plan.effective - t > p_.plan_max_age)
    return refuse("takes effect in " + seconds(plan.effective - t) + ", beyond plan_max_age " + seconds(p_.plan_max_age));
  if (plan.effective > t) {  // computed for a later time: the current plan is followed until then
    held_ = plan;
    held_t_ = t;
    return {};
  }
  pending_ = plan;
  pending_t_ = t;
  held_.reset();  // older than this one: it must not replace it later
  return {};
}

std::string GuidanceController::on_nav(const NavInput& nav, double t) {
  if (!std::isfinite(t)) return "non-finite receive time";
  std::string why = check_nav(nav);
  if (!why.empty()) return why;
  if (jumps_.check(nav.x, nav.y, std::llround(t * 1e9), &why) != nav::JumpGate::Verdict::kTaken) return why;
  nav_ = nav;
  nav_t_ = t;
  return {};
}

void GuidanceController::enter_safe(const std::string& why) {
  mode_ = Mode::SafeMode;
  detail_ = why;
  hold_set_ = false;
}

void GuidanceController::join(const PlanInput& plan, double t_recv, const NavInput& nav) {
  if (plan.kind == PlanKind::NoPath || plan.kind == PlanKind::InvalidInput) {
    issue_ = std::string("planner reports ") + (plan.kind == PlanKind::NoPath ? "no path" : "invalid input") +
             (plan.reason.empty() ? "" : ": " + plan.reason);
    switch (mode_) {
      case Mode::Following:
      case Mode::Arrived: break;  // the last valid plan is kept while it is young enough (step)
      case Mode::SafeMode:
        detail_ = issue_;  // already holding a heading: keep it
        plan_id_ = plan.plan_id;
        break;
      case Mode::Idle:  // nothing valid to follow
        plan_id_ = plan.plan_id;
        follower_.clear();
        have_plan_time_ = false;
        enter_safe(issue_);
        break;
    }
    return;
  }
  follower_.set_path(plan.waypoints, nav.x, nav.y);  // validated in on_plan
  mode_ = Mode::Following;
  plan_id_ = plan.plan_id;
  detail_ = "following plan " + std::to_string(plan.plan_id) + (plan.kind == PlanKind::Relaxed ? " (COLREG relaxed)" : "");
  // Its age counts from when it was computed (the targets' predictions it cleared), else receipt.
  plan_t_ = std::isfinite(plan.stamp) ? std::min(plan.stamp, t_recv) : t_recv;
  have_plan_time_ = true;
  hold_set_ = false;
  issue_.clear();
}

Command GuidanceController::step(double t) {
  if (!std::isfinite(t)) throw std::invalid_argument("GuidanceController::step: non-finite time");
  double dt = 0.0;
  if (!started_) {
    started_ = true;
    start_t_ = t;
  } else {
    dt = std::clamp(t - last_t_, 0.0, p_.max_dt);
  }
  last_t_ = std::max(last_t_, t);

  // A held plan takes effect; it is newer than any pending one (on_plan drops held plans older
  // than a plan taking effect at once).
  if (held_ && t >= held_->effective) {
    pending_ = std::move(*held_);
    pending_t_ = held_t_;
    held_.reset();
  }

  Command cmd;
  Status& st = cmd.status;

  // No usable own state: nothing to steer by. Rudder amidships and reduce (never raise) the rpm to
  // the feed-forward of safe_speed; resume with the next fresh state.
  if (!nav_ || t - nav_t_ > p_.nav_timeout) {
    if (!nav_lost_) {  // worded once per outage: the detail (and so the log and health) stays put
      nav_lost_detail_ = nav_ ? "no own-ship state for more than " + seconds(p_.nav_timeout) + " (last at t = " +
                                    seconds(nav_t_) + ")"
                              : "no own-ship state yet";
    }
    nav_lost_ = true;
    double rpm = std::clamp(speed_.feedforward(p_.safe_speed), p_.speed.min_rpm, p_.speed.max_rpm);
    if (last_rpm_ >= 0.0) rpm = std::min(rpm, last_rpm_);
    heading_.reset(0.0);
    speed_.reset(rpm);
    st.mode = Mode::SafeMode;
    st.degraded = true;
    st.detail = nav_lost_detail_;
    st.plan_id = plan_id_;
    st.desired_speed = p_.safe_speed;
    cmd.rudder = 0.0;
    cmd.propeller_rpm = rpm;
    last_rpm_ = rpm;
    return cmd;
  }
  const NavInput nav = *nav_;
  if (nav_lost_) {
    nav_lost_ = false;
    hold_set_ = false;  // hold the heading the ship has now, not the one from before the outage
  }

  // A new plan is joined here, where the ship position is known.
  if (pending_) {
    const PlanInput plan = std::move(*pending_);
    pending_.reset();
    join(plan, pending_t_, nav);
  }

  // The plan followed ages out (its clearance was computed against predictions that age); before
  // any plan, the start is the reference. Arrived is exempt: the ship is slowing at the goal.
  if (mode_ == Mode::Following || mode_ == Mode::Idle) {
    const double age = t - (have_plan_time_ ? plan_t_ : start_t_);
    if (age > p_.plan_max_age) {
      const std::string why = have_plan_time_ ? "no valid plan for " + seconds(age) + " (plan " +
                                                    std::to_string(plan_id_) + " aged out)"
                                              : "no valid plan for " + seconds(age);
      follower_.clear();
      have_plan_time_ = false;
      enter_safe(issue_.empty() ? why : issue_ + "; " + why);
    }
  }

  double psi_d = 0.0, u_d = 0.0;
  switch (mode_) {
    case Mode::Idle:
      if (!hold_set_) {
        hold_heading_ = nav.heading;
        hold_speed_ = std::max(nav.u, 0.0);
        hold_set_ = true;
      }
      psi_d = hold_heading_;
      u_d = hold_speed_;
      break;
    case Mode::SafeMode:
      if (!hold_set_) {
        hold_heading_ = nav.heading;
        hold_set_ = true;
      }
      psi_d = hold_heading_;
      u_d = p_.safe_speed;
      break;
    case Mode::Following:
    case Mode::Arrived: {
      const GuidanceOutput g = follower_.update(nav.x, nav.y, nav.u, dt);
      if (g.arrived && mode_ == Mode::Following) {
        mode_ = Mode::Arrived;
        detail_ = "last waypoint of plan " + std::to_string(plan_id_) + " reached";
      }
      psi_d = g.desired_heading;
      u_d = g.arrived ? p_.arrival_speed : g.desired_speed;
      st.active_waypoint = static_cast<uint32_t>(g.active_waypoint);
      st.cross_track_error = g.cross_track_error;
      st.along_track = g.along_track;
      break;
    }
  }

  cmd.rudder = heading_.update(psi_d, nav.heading, nav.r, dt);
  cmd.propeller_rpm = speed_.update(u_d, nav.u, dt);
  cmd.rudder_saturated = heading_.saturated();
  cmd.rpm_saturated = speed_.saturated();
  last_rpm_ = cmd.propeller_rpm;
  st.mode = mode_;
  st.degraded = mode_ == Mode::SafeMode || !issue_.empty();
  st.detail = detail_;
  if (mode_ != Mode::SafeMode && !issue_.empty())
    st.detail += "; " + issue_ + (mode_ == Mode::Following ? ": kept until it is " + seconds(p_.plan_max_age) + " old" : "");
  st.plan_id = plan_id_;
  st.desired_heading = psi_d;
  st.desired_speed = u_d;
  return cmd;
}

}  // namespace mpgc::guidance_control
