#include "mpgc/opp/obstacles.hpp"

#include <limits>
#include <stdexcept>
#include <string>

namespace mpgc::opp {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double NoFixedObstacles::nearest(Vec2) const { return kInf; }

DiscObstacles::DiscObstacles(std::vector<Disc> discs) : discs_(std::move(discs)) {
  for (size_t i = 0; i < discs_.size(); ++i) {
    if (!finite(discs_[i].c) || !std::isfinite(discs_[i].r) || discs_[i].r < 0.0)
      throw std::invalid_argument("DiscObstacles: disc " + std::to_string(i) + " has a non-finite centre or bad radius");
  }
}

double DiscObstacles::nearest(Vec2 p) const {
  double best = kInf;
  for (const auto& d : discs_) best = std::min(best, std::max(0.0, norm(p - d.c) - d.r));
  return best;
}

bool DiscObstacles::segment_clear(Vec2 a, Vec2 b, double d) const {
  for (const auto& c : discs_) {
    const double rr = c.r + d;
    if (point_segment_dist2(c.c, a, b) < rr * rr) return false;
  }
  return true;
}

}  // namespace mpgc::opp
