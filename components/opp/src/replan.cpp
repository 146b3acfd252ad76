#include "mpgc/opp/replan.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mpgc::opp {

void ReplanParams::validate() const {
  auto bad = [](const char* f, const char* why) { throw std::invalid_argument(std::string("opp::ReplanParams.") + f + " " + why); };
  if (!(std::isfinite(period) && period > 0)) bad("period", "must be finite and > 0");
  if (!(std::isfinite(track_threshold) && track_threshold > 0)) bad("track_threshold", "must be finite and > 0");
  if (!(std::isfinite(track_horizon) && track_horizon >= 0)) bad("track_horizon", "must be finite and >= 0");
  if (!(std::isfinite(min_interval) && min_interval >= 0)) bad("min_interval", "must be finite and >= 0");
}

ReplanPolicy::ReplanPolicy(ReplanParams p) : p_(p) { p_.validate(); }

std::string ReplanPolicy::due(double t, uint32_t goal_id, const std::vector<Target>& targets) const {
  if (!any_) return "first plan";
  if (goal_id != goal_id_) return "new goal " + std::to_string(goal_id);
  if (t - t_last_ >= p_.period) return "period";
  if (t - t_last_ < p_.min_interval) return "";
  if (!ok_) return "retry after a failed plan";
  const double dt = t - t_last_;
  for (const Target& n : targets) {
    const Target* o = nullptr;
    for (const Target& x : targets_)
      if (x.id == n.id) o = &x;
    if (!o) return "new target " + std::to_string(n.id);
    // eq. 3 predictions of the last plan vs now, at three horizons.
    for (double h : {0.0, 0.5 * p_.track_horizon, p_.track_horizon}) {
      const Vec2 old_p = o->p + (dt + h) * o->v;
      const Vec2 new_p = n.p + h * n.v;
      const double dev = norm(new_p - old_p);
      if (dev > p_.track_threshold) {
        std::ostringstream os;
        os << "target " << n.id << " track changed by " << static_cast<int>(dev) << " m at +" << h << " s";
        return os.str();
      }
    }
  }
  return "";
}

void ReplanPolicy::planned(double t, uint32_t goal_id, const std::vector<Target>& targets, bool ok) {
  any_ = true;
  ok_ = ok;
  t_last_ = t;
  goal_id_ = goal_id;
  targets_ = targets;
}

}  // namespace mpgc::opp
