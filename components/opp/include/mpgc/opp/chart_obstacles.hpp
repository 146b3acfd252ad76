// Adapter: the obstacle manager's FixedObstacleMap (kd-tree over the points plus exact clearance
// to the land polygons) as the planner's FixedObstacles.
#pragma once

#include <memory>

#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"
#include "mpgc/opp/obstacles.hpp"

namespace mpgc::opp {

class ChartObstacles final : public FixedObstacles {
 public:
  explicit ChartObstacles(std::shared_ptr<const obstacle_manager::FixedObstacleMap> map) : map_(std::move(map)) {}
  // Exact distance to points and polygon edges, 0 inside land.
  double nearest(Vec2 p) const override { return map_->clearance(p); }
  bool segment_clear(Vec2 a, Vec2 b, double d) const override {
    const double c = map_->segment_clearance(a, b);
    return c >= d && c > 0.0;  // 0 = crosses or touches land, blocked even when d = 0
  }
  const obstacle_manager::FixedObstacleMap& map() const { return *map_; }

 private:
  std::shared_ptr<const obstacle_manager::FixedObstacleMap> map_;
};

}  // namespace mpgc::opp
