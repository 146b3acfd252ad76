// The obstacle manager builds the fixed-obstacle map the whole system queries (common's
// geom::FixedObstacleMap: kd-tree over points, exact clearance to land polygons); these are its
// names for it here.
#pragma once

#include "mpgc/geom/fixed_obstacle_map.hpp"

namespace mpgc::obstacle_manager {
using geom::BoxNE;
using geom::FixedObstacleMap;
using geom::Polygon;
}  // namespace mpgc::obstacle_manager
