#include "mpgc/guidance_control/autopilot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "mpgc/geo/angles.hpp"

namespace mpgc::guidance_control {

namespace {
void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}
bool finite_nonneg(double v) { return std::isfinite(v) && v >= 0.0; }
bool finite_pos(double v) { return std::isfinite(v) && v > 0.0; }
}  // namespace

void HeadingAutopilotParams::validate() const {
  require(finite_nonneg(kp), "HeadingAutopilotParams.kp must be finite and >= 0");
  require(finite_nonneg(ki), "HeadingAutopilotParams.ki must be finite and >= 0");
  require(finite_nonneg(kd), "HeadingAutopilotParams.kd must be finite and >= 0");
  require(finite_pos(max_rudder) && max_rudder <= 1.0, "HeadingAutopilotParams.max_rudder must be in (0, 1] rad");
  require(finite_pos(max_rudder_rate), "HeadingAutopilotParams.max_rudder_rate must be finite and > 0");
  require(finite_nonneg(integral_limit), "HeadingAutopilotParams.integral_limit must be finite and >= 0");
}

HeadingAutopilot::HeadingAutopilot(const HeadingAutopilotParams& p) : p_(p) { p_.validate(); }

void HeadingAutopilot::reset(double rudder) {
  integral_ = 0.0;
  last_ = std::isfinite(rudder) ? std::clamp(rudder, -p_.max_rudder, p_.max_rudder) : 0.0;
}

double HeadingAutopilot::update(double psi_d, double psi, double r, double dt) {
  if (!std::isfinite(psi_d) || !std::isfinite(psi) || !std::isfinite(r) || !std::isfinite(dt) || dt < 0.0)
    throw std::invalid_argument("HeadingAutopilot::update: non-finite input or negative dt");
  const double e = geo::angle_diff(psi_d, psi);
  const double i_next = std::clamp(integral_ + p_.ki * e * dt, -p_.integral_limit, p_.integral_limit);
  const double u = p_.kp * e + i_next - p_.kd * r;
  double out = std::clamp(u, -p_.max_rudder, p_.max_rudder);
  saturated_ = out != u;
  out = std::clamp(out, last_ - p_.max_rudder_rate * dt, last_ + p_.max_rudder_rate * dt);
  // Conditional integration: hold the integral when a limit holds the output back and the error
  // would push it further that way.
  const bool limited = std::abs(out - u) > 1e-12;
  if (!limited || (u - out) * e < 0.0) integral_ = i_next;
  last_ = out;
  return out;
}

void SpeedControllerParams::validate() const {
  require(map_speed.size() >= 2 && map_speed.size() == map_rpm.size(),
          "SpeedControllerParams.map_speed/map_rpm must have the same size >= 2");
  for (std::size_t i = 0; i < map_speed.size(); ++i) {
    require(std::isfinite(map_speed[i]) && std::isfinite(map_rpm[i]),
            "SpeedControllerParams.map_speed/map_rpm entry " + std::to_string(i) + " is not finite");
    if (i > 0) require(map_speed[i] > map_speed[i - 1], "SpeedControllerParams.map_speed must be strictly increasing");
  }
  require(finite_nonneg(kp), "SpeedControllerParams.kp must be finite and >= 0");
  require(finite_nonneg(ki), "SpeedControllerParams.ki must be finite and >= 0");
  require(finite_nonneg(integral_limit), "SpeedControllerParams.integral_limit must be finite and >= 0");
  require(finite_pos(integral_zone), "SpeedControllerParams.integral_zone must be finite and > 0");
  require(std::isfinite(min_rpm) && std::isfinite(max_rpm) && max_rpm > min_rpm,
          "SpeedControllerParams.max_rpm must be finite and > min_rpm");
  require(finite_pos(max_rpm_rate), "SpeedControllerParams.max_rpm_rate must be finite and > 0");
}

void parse_speed_map(const std::string& text, SpeedControllerParams& p) {
  std::vector<double> sp, rpm;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find(',', pos);
    if (end == std::string::npos) end = text.size();
    const std::string item = text.substr(pos, end - pos);
    pos = end + 1;
    if (item.find_first_not_of(" \t") == std::string::npos) {
      if (end == text.size()) break;
      throw std::invalid_argument("speed map: empty entry in '" + text + "'");
    }
    const std::size_t colon = item.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("speed map: entry '" + item + "' is not speed:rpm");
    try {
      std::size_t used1 = 0, used2 = 0;
      const std::string a = item.substr(0, colon), b = item.substr(colon + 1);
      const double v = std::stod(a, &used1), n = std::stod(b, &used2);
      if (a.find_first_not_of(" \t", used1) != std::string::npos || b.find_first_not_of(" \t", used2) != std::string::npos)
        throw std::invalid_argument("trailing text");
      sp.push_back(v);
      rpm.push_back(n);
    } catch (const std::exception&) {
      throw std::invalid_argument("speed map: entry '" + item + "' is not speed:rpm with two numbers");
    }
  }
  SpeedControllerParams q = p;
  q.map_speed = sp;
  q.map_rpm = rpm;
  q.validate();
  p = q;
}

std::string format_speed_map(const SpeedControllerParams& p) {
  std::string out;
  for (std::size_t i = 0; i < p.map_speed.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%s%g:%g", i ? ", " : "", p.map_speed[i], p.map_rpm[i]);
    out += buf;
  }
  return out;
}

SpeedController::SpeedController(const SpeedControllerParams& p) : p_(p) { p_.validate(); }

void SpeedController::reset(double rpm) {
  integral_ = 0.0;
  last_ = std::isfinite(rpm) ? std::clamp(rpm, p_.min_rpm, p_.max_rpm) : 0.0;
}

double SpeedController::feedforward(double speed) const {
  const auto& xs = p_.map_speed;
  const auto& ys = p_.map_rpm;
  std::size_t i = 1;
  while (i + 1 < xs.size() && speed > xs[i]) ++i;
  const double f = (speed - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return ys[i - 1] + f * (ys[i] - ys[i - 1]);
}

double SpeedController::update(double u_d, double u, double dt) {
  if (!std::isfinite(u_d) || !std::isfinite(u) || !std::isfinite(dt) || dt < 0.0)
    throw std::invalid_argument("SpeedController::update: non-finite input or negative dt");
  const double e = u_d - u;
  const double i_next = std::abs(e) < p_.integral_zone
                            ? std::clamp(integral_ + p_.ki * e * dt, -p_.integral_limit, p_.integral_limit)
                            : integral_;
  const double cmd = feedforward(u_d) + p_.kp * e + i_next;
  double out = std::clamp(cmd, p_.min_rpm, p_.max_rpm);
  saturated_ = out != cmd;
  out = std::clamp(out, last_ - p_.max_rpm_rate * dt, last_ + p_.max_rpm_rate * dt);
  const bool limited = std::abs(out - cmd) > 1e-9;
  if (!limited || (cmd - out) * e < 0.0) integral_ = i_next;
  last_ = out;
  return out;
}

HeadingAutopilotParams tune_heading_pid(const NomotoModel& m, double omega_n, double zeta,
                                        const HeadingAutopilotParams& base, double integral_ratio) {
  require(finite_pos(m.K), "tune_heading_pid: Nomoto K must be finite and > 0");
  require(finite_pos(m.T), "tune_heading_pid: Nomoto T must be finite and > 0");
  require(finite_pos(omega_n), "tune_heading_pid: omega_n must be finite and > 0");
  require(finite_pos(zeta), "tune_heading_pid: zeta must be finite and > 0");
  require(finite_pos(integral_ratio), "tune_heading_pid: integral_ratio must be finite and > 0");
  HeadingAutopilotParams p = base;
  p.kp = m.T * omega_n * omega_n / m.K;
  p.kd = (2.0 * zeta * omega_n * m.T - 1.0) / m.K;
  require(p.kd >= 0.0, "tune_heading_pid: kd < 0: omega_n is below 1/(2 zeta T) for this hull; raise omega_n");
  p.ki = omega_n * p.kp / integral_ratio;
  p.validate();
  return p;
}

}  // namespace mpgc::guidance_control
