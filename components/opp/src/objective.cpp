#include "mpgc/opp/objective.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpgc::opp {

Objective::Objective(const Problem& pb, const ObjectiveParams& w) : pb_(pb), w_(w) {
  fixed_ = pb.fixed ? pb.fixed : &none_;
}

double Objective::moving_term(Vec2 p, double t) const {
  if (w_.gamma_m == 0.0 || pb_.targets.empty()) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (const Target& tg : pb_.targets) best = std::min(best, norm2(p - (tg.p + t * tg.v)));
  return w_.gamma_m / std::max(std::sqrt(best), w_.min_margin);
}

double Objective::steer_term(Vec2 dir, Vec2 seg, double len, bool at_root) const {
  if (w_.gamma_s == 0.0 || at_root) return 0.0;
  const double c = std::clamp(dot(dir, seg) / len, -1.0, 1.0);
  const double th = std::acos(c);
  return w_.gamma_s * th * th;
}

CostTerms Objective::path_cost(const std::vector<Vec2>& path) const {
  CostTerms c;
  if (path.empty()) return c;
  Vec2 dir{std::cos(pb_.heading), std::sin(pb_.heading)};
  double len_acc = 0.0;
  c.fixed += fixed_term(path[0]);
  c.moving += moving_term(path[0], 0.0);
  for (size_t i = 1; i < path.size(); ++i) {
    const Vec2 seg = path[i] - path[i - 1];
    const double len = norm(seg);
    c.smooth += steer_term(dir, seg, len, i == 1);
    len_acc += len;
    c.length += w_.gamma_l * len;
    c.fixed += fixed_term(path[i]);
    c.moving += moving_term(path[i], len_acc / pb_.speed);
    if (len > 0) dir = (1.0 / len) * seg;
  }
  c.total = c.smooth + c.fixed + c.moving + c.length;
  return c;
}

}  // namespace mpgc::opp
