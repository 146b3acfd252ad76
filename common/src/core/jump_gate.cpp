#include "mpgc/nav/jump_gate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mpgc::nav {
namespace {

std::string fmt1(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

}  // namespace

void JumpGateParams::validate() const {
  if (!(std::isfinite(max_speed) && max_speed > 0)) throw std::invalid_argument("JumpGateParams.max_speed must be > 0 m/s");
  if (!(std::isfinite(margin) && margin >= 0)) throw std::invalid_argument("JumpGateParams.margin must be >= 0 m");
  if (!(std::isfinite(timeout) && timeout > 0)) throw std::invalid_argument("JumpGateParams.timeout must be > 0 s");
}

void declare_params(rt::ParamSet& ps, JumpGateParams* p) {
  const JumpGateParams d;
  ps.add("nav.max_speed", &p->max_speed, d.max_speed, "m/s", 0.1, 100.0,
         "fastest the ship can go: an own position jump beyond it is refused while the last one is fresh");
  ps.add("nav.jump_margin", &p->margin, d.margin, "m", 0.0, 1e4, "noise allowance of the position jump check");
}

JumpGate::JumpGate(JumpGateParams p) : p_(p) { p_.validate(); }

double JumpGate::reach(int64_t since, int64_t now) const {
  return p_.max_speed * std::max(age_of(since, now), 0.0) + p_.margin;
}

JumpGate::Verdict JumpGate::check(double x, double y, int64_t t, std::string* why) {
  if (last_t_ >= 0 && age_of(last_t_, t) <= p_.timeout) {
    const double d = std::hypot(x - last_x_, y - last_y_);
    if (d > reach(last_t_, t)) {
      pending_ = true;
      candidate_.reset();
      if (why) *why = "position jumped " + fmt1(d) + " m (at most " + fmt1(reach(last_t_, t)) + " m possible)";
      return Verdict::kJump;
    }
  } else if (pending_) {
    // The second fix must be a later one: what arrives together is not a confirmation.
    const bool agrees = candidate_ && t > candidate_->t && std::hypot(x - candidate_->x, y - candidate_->y) <= reach(candidate_->t, t);
    if (!agrees) {
      if (!candidate_ || t > candidate_->t) candidate_ = Fix{x, y, t};
      if (why) *why = "new position after a jump: waiting for a second fix that agrees";
      return Verdict::kUnconfirmed;
    }
    pending_ = false;
    candidate_.reset();
  }
  last_x_ = x, last_y_ = y, last_t_ = t;
  return Verdict::kTaken;
}

}  // namespace mpgc::nav
