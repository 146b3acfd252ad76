// Conversions between the obstacle messages and the query library, for the DDS side only (a
// component main that links mpgc_msgs). The planner's main can do:
//
//   c.subscribe<msg::FixedObstacles>(topics::kFixedObstacles, dds::QosProfile::latched(),
//       [&](const msg::FixedObstacles& m) { map = std::make_shared<const FixedObstacleMap>(
//           mpgc::obstacle_manager::map_from_msg(m)); });
#pragma once

#include <vector>

#include "mpgc/msg/obstacles.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace mpgc::obstacle_manager {

inline std::vector<geom::Vec2> points_from_msg(const std::vector<msg::PointNE>& v) {
  std::vector<geom::Vec2> out;
  out.reserve(v.size());
  for (const auto& p : v) out.push_back({p.x, p.y});
  return out;
}

inline std::vector<msg::PointNE> points_to_msg(const std::vector<geom::Vec2>& v) {
  std::vector<msg::PointNE> out;
  out.reserve(v.size());
  for (const auto& p : v) out.push_back({p.x, p.y});
  return out;
}

// Throws std::invalid_argument (from FixedObstacleMap) naming a non-finite point or short ring.
inline FixedObstacleMap map_from_msg(const msg::FixedObstacles& m) {
  std::vector<Polygon> polys;
  polys.reserve(m.polygons.size());
  for (const auto& g : m.polygons) polys.push_back({g.feature_id, points_from_msg(g.ring)});
  return FixedObstacleMap(points_from_msg(m.points), std::move(polys));
}

}  // namespace mpgc::obstacle_manager
