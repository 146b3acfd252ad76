// The planner speaks the project's one 2-D vocabulary (common/include/mpgc/geom/vec2.hpp): NED
// points and velocities and the exact distances behind every edge check (seed 000 eq. 3-4).
#pragma once

#include "mpgc/geom/vec2.hpp"

namespace mpgc::opp {
using geom::cross;
using geom::dot;
using geom::finite;
using geom::norm;
using geom::norm2;
using geom::point_segment_dist2;
using geom::Vec2;
}  // namespace mpgc::opp
