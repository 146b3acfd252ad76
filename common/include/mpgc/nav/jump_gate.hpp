// A position jump no ship can make, refused wherever a position enters: the ship bridge's
// navigation fusion (GNSS fixes) and every component that steers or plans by nav/own_state.
// A fix farther from the last one taken than max_speed over the time between them, plus margin
// (GNSS noise), is refused while that last fix is fresh. Once it is stale the new place is taken
// when a later fix agrees with it: a real relocation after an outage is not refused for ever, and
// a single wild fix is never taken.
#pragma once

#include <cmath>

#include <cstdint>
#include <optional>
#include <string>

#include "mpgc/runtime/params.hpp"

namespace mpgc::nav {

// [s] age at now_ns of something last heard at t_ns; +inf when never heard (t_ns < 0).
inline double age_of(int64_t t_ns, int64_t now_ns) {
  return t_ns < 0 ? INFINITY : static_cast<double>(now_ns - t_ns) * 1e-9;
}

struct JumpGateParams {
  double max_speed = 25.0;  // [m/s] fastest the ship can go
  double margin = 30.0;     // [m] noise allowance on top of max_speed * dt
  double timeout = 3.0;     // [s] the last fix taken is fresh this long
  void validate() const;    // throws std::invalid_argument naming the parameter
};

// Declares nav.max_speed and nav.jump_margin, the names every component gives them; the timeout is
// the component's own staleness limit.
void declare_params(rt::ParamSet& ps, JumpGateParams* p);

class JumpGate {
 public:
  enum class Verdict { kTaken, kJump, kUnconfirmed };
  explicit JumpGate(JumpGateParams p);
  // Whether the position (x, y) [m] at t_ns is taken; `why` says why not.
  Verdict check(double x, double y, int64_t t_ns, std::string* why = nullptr);
  // The position is lost (no fix): the next one is taken as it is.
  void forget() { last_t_ = -1; }
  // A jump was refused and no later fix has confirmed the new place yet.
  bool jumped() const { return pending_; }

 private:
  struct Fix {
    double x, y;
    int64_t t;
  };
  double reach(int64_t since, int64_t now) const;  // [m] farthest the ship can have gone
  JumpGateParams p_;
  double last_x_ = 0, last_y_ = 0;
  int64_t last_t_ = -1;
  bool pending_ = false;
  std::optional<Fix> candidate_;
};

}  // namespace mpgc::nav
