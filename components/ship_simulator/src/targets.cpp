#include "mpgc/ship_simulator/targets.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_simulator {
namespace {
void finite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw std::invalid_argument("target: " + what + " must be finite");
}
void speed_ok(double v, const std::string& what) {
  if (!std::isfinite(v) || v < 0.0 || v > 30.0) throw std::invalid_argument("target: " + what + " must be in 0..30 m/s");
}
}  // namespace

void TargetConfig::validate() const {
  const std::string id = "target '" + name + "' ";
  if (mmsi < 100000000u || mmsi > 999999999u) throw std::invalid_argument(id + "mmsi must have 9 digits");
  finite(x0, name + ".x0");
  finite(y0, name + ".y0");
  finite(course0, name + ".course0");
  speed_ok(speed0, name + ".speed0");
  if (!legs.empty() && !waypoints.empty()) throw std::invalid_argument(id + "has both legs and waypoints");
  for (std::size_t i = 0; i < legs.size(); ++i) {
    finite(legs[i].course, name + ".legs[" + std::to_string(i) + "].course");
    speed_ok(legs[i].speed, name + ".legs[" + std::to_string(i) + "].speed");
    if (!std::isfinite(legs[i].duration) || legs[i].duration < 0.0 || (legs[i].duration == 0.0 && i + 1 < legs.size()))
      throw std::invalid_argument(id + "legs[" + std::to_string(i) + "].duration must be > 0 (0 only on the last leg)");
  }
  for (std::size_t i = 0; i < waypoints.size(); ++i) {
    finite(waypoints[i].x, name + ".waypoints[" + std::to_string(i) + "].x");
    finite(waypoints[i].y, name + ".waypoints[" + std::to_string(i) + "].y");
    speed_ok(waypoints[i].speed, name + ".waypoints[" + std::to_string(i) + "].speed");
  }
  for (std::size_t i = 0; i < manoeuvres.size(); ++i) {
    const auto& m = manoeuvres[i];
    const std::string w = name + ".manoeuvres[" + std::to_string(i) + "]";
    if (!std::isfinite(m.at) || m.at < 0.0) throw std::invalid_argument("target: " + w + ".at must be >= 0");
    finite(m.course, w + ".course");
    if (m.speed >= 0.0) speed_ok(m.speed, w + ".speed");
    if (!std::isfinite(m.speed)) throw std::invalid_argument("target: " + w + ".speed must be finite");
    if (!std::isfinite(m.duration) || m.duration < 0.0) throw std::invalid_argument("target: " + w + ".duration must be >= 0");
  }
  if (!(max_turn_rate > 0.0) || max_turn_rate > 0.2) throw std::invalid_argument(id + "max_turn_rate must be in (0, 0.2] rad/s");
  if (!(max_accel > 0.0) || max_accel > 5.0) throw std::invalid_argument(id + "max_accel must be in (0, 5] m/s^2");
  if (!(waypoint_radius > 0.0) || !std::isfinite(waypoint_radius)) throw std::invalid_argument(id + "waypoint_radius must be > 0");
  if (!(length > 0.0) || length > 500.0) throw std::invalid_argument(id + "length must be in (0, 500] m");
  if (!(beam > 0.0) || beam > 100.0) throw std::invalid_argument(id + "beam must be in (0, 100] m");
  if (nav_status > 15) throw std::invalid_argument(id + "nav_status must be 0..15");
  if (behaviour == TargetBehaviour::kColreg) {
    try {
      helmsman.validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(id + e.what());
    }
  }
}

TargetShip::TargetShip(TargetConfig cfg) : cfg_(std::move(cfg)) {
  cfg_.validate();
  s_.x = cfg_.x0;
  s_.y = cfg_.y0;
  s_.course = geo::wrap_pi(cfg_.course0);
  s_.speed = cfg_.speed0;
  route_course_ = s_.course;
  route_speed_ = s_.speed;
  if (cfg_.behaviour == TargetBehaviour::kColreg) helm_.emplace(cfg_.helmsman);
}

void TargetShip::ordered(double t, double* course, double* speed) {
  // Route first ...
  *course = s_.course;
  *speed = s_.speed;
  // A rule-following target's route without a leg or waypoint to steer by (none given, or past the
  // last waypoint) is the last course and speed the route ordered (at first the start course and
  // speed), not the current course: the one it returns to after giving way.
  if (helm_) {
    *course = route_course_;
    *speed = route_speed_;
  }
  if (!cfg_.legs.empty()) {
    double t0 = 0.0;
    std::size_t i = 0;
    while (i + 1 < cfg_.legs.size() && t >= t0 + cfg_.legs[i].duration) t0 += cfg_.legs[i++].duration;
    *course = cfg_.legs[i].course;
    *speed = cfg_.legs[i].speed;
  } else if (!cfg_.waypoints.empty()) {
    while (wp_ < cfg_.waypoints.size() &&
           std::hypot(cfg_.waypoints[wp_].x - s_.x, cfg_.waypoints[wp_].y - s_.y) < cfg_.waypoint_radius)
      ++wp_;
    if (wp_ < cfg_.waypoints.size()) {
      *course = geo::course_of(cfg_.waypoints[wp_].x - s_.x, cfg_.waypoints[wp_].y - s_.y);
      *speed = cfg_.waypoints[wp_].speed;
    }  // after the last waypoint: hold course and speed
  }
  route_course_ = *course;
  route_speed_ = *speed;
  // ... then the latest scripted manoeuvre active at t overrides it.
  for (const auto& m : cfg_.manoeuvres) {
    if (t >= m.at && (m.duration == 0.0 || t < m.at + m.duration)) {
      *course = m.course;
      if (m.speed >= 0.0) *speed = m.speed;
    }
  }
}

void TargetShip::step(double t, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(t)) throw std::invalid_argument("TargetShip::step: bad t or dt");
  double course = 0.0, speed = 0.0;
  ordered(t, &course, &speed);
  move(course, speed, dt);
}

void TargetShip::step(double t, double dt, const std::vector<SeenShip>& others) {
  if (!helm_) return step(t, dt);
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(t)) throw std::invalid_argument("TargetShip::step: bad t or dt");
  double course = 0.0, speed = 0.0;
  ordered(t, &course, &speed);
  // Targets do not drift: heading = course over ground.
  const auto me = colreg::ShipKinematics::from_course(s_.x, s_.y, s_.course, s_.speed, s_.course);
  const HelmOrder o = helm_->decide(me, course, speed, others);
  move(o.course, o.speed, dt);
}

void TargetShip::move(double course, double speed, double dt) {
  const double dpsi = std::clamp(geo::angle_diff(course, s_.course), -cfg_.max_turn_rate * dt, cfg_.max_turn_rate * dt);
  const double dv = std::clamp(speed - s_.speed, -cfg_.max_accel * dt, cfg_.max_accel * dt);
  // Move along the mean course and speed of the step (second order in dt).
  const double cm = s_.course + 0.5 * dpsi, vm = s_.speed + 0.5 * dv;
  s_.x += vm * dt * std::cos(cm);
  s_.y += vm * dt * std::sin(cm);
  s_.course = geo::wrap_pi(s_.course + dpsi);
  s_.speed += dv;
  s_.rot = dpsi / dt;
}

}  // namespace mpgc::ship_simulator
