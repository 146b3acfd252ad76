// The guidance component's configuration and health without DDS or a clock (mpgc_guidance_control's
// main.cpp is wiring around it): its named parameters, the controller's parameters they make (the
// speed map parsed, the heading PID placed from Nomoto K, T when heading.nomoto_K > 0), and when a
// change of mode or detail is news (logged, and health DEGRADED or OK).
//
//   gc::NodeParams p;  gc::declare(ps, p);  ps.validate_and_apply();
//   gc::GuidanceController ctl(gc::controller_params(p));
//   gc::ModeNews news;  if (news.changed(cmd.status)) log(...);
#pragma once

#include <string>

#include "mpgc/guidance_control/guidance_control.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::guidance_control {

struct NodeParams {
  GuidanceControlParams gc;
  double rate = 2.0;  // [Hz] control cycle
  std::string speed_map;  // speed:rpm pairs [m/s]:[1/min]
  // Pole placement of the heading PID (used when nomoto_K > 0).
  double nomoto_K = 0.0;   // [1/s]
  double nomoto_T = 0.0;   // [s]
  double omega_n = 0.0;    // [rad/s]
  double zeta = 1.0;       // [-]
  double integral_ratio = 20.0;  // [-] ki = omega_n kp / integral_ratio
};

// Declares every parameter of the component (defaults: GuidanceControlParams').
void declare(rt::ParamSet& ps, NodeParams& p);

// The controller's parameters: p.gc with the speed map parsed and, when nomoto_K > 0, the heading
// PID by pole placement. Throws std::invalid_argument on a bad speed map.
GuidanceControlParams controller_params(const NodeParams& p);

// A status whose mode or detail differs from the last one's is news.
class ModeNews {
 public:
  bool changed(const Status& s);

 private:
  Mode mode_ = Mode::Idle;
  std::string detail_;
};

}  // namespace mpgc::guidance_control
