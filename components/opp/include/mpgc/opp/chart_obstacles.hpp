// Adapter: the obstacle manager's FixedObstacleMap (kd-tree over the points plus exact clearance
// to the land polygons) as the planner's FixedObstacles.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "mpgc/geom/fixed_obstacle_map.hpp"
#include "mpgc/opp/obstacles.hpp"

namespace mpgc::opp {

class ChartObstacles final : public FixedObstacles {
 public:
  explicit ChartObstacles(std::shared_ptr<const geom::FixedObstacleMap> map) : map_(std::move(map)) {}
  // Exact distance to points and polygon edges, 0 inside land.
  double nearest(Vec2 p) const override { return map_->clearance(p); }
  bool segment_clear(Vec2 a, Vec2 b, double d) const override {
    // The search stops at the first obstacle closer than d. At d = 0 a leg that crosses or
    // touches land (clearance 0) is blocked too.
    if (d > 0.0) return map_->segment_clear(a, b, d);
    return !map_->segment_touches(a, b);
  }
  const geom::FixedObstacleMap& map() const { return *map_; }

 private:
  std::shared_ptr<const geom::FixedObstacleMap> map_;
};

// A point set F (densified shore lines, point features, seed 000 §4.2) in the obstacle manager's
// index. Throws std::invalid_argument naming a non-finite point.
inline std::shared_ptr<ChartObstacles> point_obstacles(std::vector<Vec2> points) {
  return std::make_shared<ChartObstacles>(
      std::make_shared<const geom::FixedObstacleMap>(std::move(points), std::vector<geom::Polygon>{}));
}

}  // namespace mpgc::opp
