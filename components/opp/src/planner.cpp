#include "mpgc/opp/planner.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpgc/opp/validity.hpp"

namespace mpgc::opp {

void Budget::validate() const {
  // About 100 bytes per node: 2e6 iterations bound the tree to ~200 MB.
  if (!(max_iterations >= 1 && max_iterations <= 2'000'000))
    throw std::invalid_argument("opp::Params.max_iterations must be in [1, 2e6]");
  if (!(std::isfinite(time_budget) && time_budget > 0))
    throw std::invalid_argument("opp::Params.time_budget must be finite and > 0");
}

const char* to_string(Status s) {
  switch (s) {
    case Status::kOk: return "ok";
    case Status::kRelaxed: return "relaxed";
    case Status::kNoPath: return "no_path";
    case Status::kInvalidInput: return "invalid_input";
  }
  return "?";
}

std::vector<Vec2> warm_tail(const std::vector<Vec2>& warm, Vec2 start) {
  if (warm.size() < 2) return {};
  size_t best_leg = 0;
  double bd = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < warm.size(); ++i) {
    const double d = point_segment_dist2(start, warm[i], warm[i + 1]);
    if (d < bd) {
      bd = d;
      best_leg = i;
    }
  }
  return std::vector<Vec2>(warm.begin() + static_cast<long>(best_leg) + 1, warm.end());
}

Result finish(const Problem& pb, const std::vector<Vec2>& pts, bool relaxed, const ValidityChecker& check,
              const Objective& objective) {
  Result res;
  res.relaxed = relaxed;
  res.status = relaxed ? Status::kRelaxed : Status::kOk;
  res.colreg_compliant = check.check_path(pts, true).empty();
  res.cost = objective.path_cost(pts);
  double len = 0.0;
  res.path.push_back({pts[0], 0.0});
  for (size_t i = 1; i < pts.size(); ++i) {
    len += norm(pts[i] - pts[i - 1]);
    res.path.push_back({pts[i], len / pb.speed});
  }
  return res;
}

}  // namespace mpgc::opp
