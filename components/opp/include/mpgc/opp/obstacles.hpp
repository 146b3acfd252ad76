// Fixed obstacles as the planner sees them: one narrow interface injected into the planner
// (Autoware/OMPL style), so the planner is testable without a chart and the obstacle manager's
// library plugs in through an adapter (chart_obstacles.hpp, also for a bare point set F of seed 000
// §4.2: one spatial index for fixed obstacles). Implementations here: none and analytic discs
// (benchmark worlds).
#pragma once

#include <cstdint>
#include <vector>

#include "mpgc/opp/geometry.hpp"

namespace mpgc::opp {

class FixedObstacles {
 public:
  virtual ~FixedObstacles() = default;
  // [m] distance from p to the nearest obstacle (+inf when there is none): eq. 4 and eq. 7.
  virtual double nearest(Vec2 p) const = 0;
  // True when every point of segment [a, b] is at least d from every obstacle (exact, eq. 4
  // along the whole edge, not only at its ends).
  virtual bool segment_clear(Vec2 a, Vec2 b, double d) const = 0;
};

class NoFixedObstacles final : public FixedObstacles {
 public:
  double nearest(Vec2) const override;
  bool segment_clear(Vec2, Vec2, double) const override { return true; }
};

struct Disc {
  Vec2 c;         // [m] centre
  double r = 0;   // [m] radius
};

// Solid discs: distance is measured to the disc boundary (0 inside).
class DiscObstacles final : public FixedObstacles {
 public:
  explicit DiscObstacles(std::vector<Disc> discs);  // throws std::invalid_argument on NaN / r < 0
  double nearest(Vec2 p) const override;
  bool segment_clear(Vec2 a, Vec2 b, double d) const override;
  const std::vector<Disc>& discs() const { return discs_; }

 private:
  std::vector<Disc> discs_;
};

}  // namespace mpgc::opp
