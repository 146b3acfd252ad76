// The fixed obstacles a run is judged against: the scenario's own chart files and shapes, loaded
// by the evaluation itself rather than taken from what the obstacle_manager under test published
// (issue 17), so an obstacle it drops or moves is still measured. Circles stay exact circles (the
// obstacle_manager sends them as circumscribed polygons); other shapes and chart features go
// through the chart loader with the run's draught. No DDS, no clock.
#pragma once

#include <string>

#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace mpgc::scenario_runner {

// Throws (ChartError, std::invalid_argument) naming the file or shape that cannot be read.
// `shared_dir`: relative chart paths are tried against it too ($MPGC_SHARED_DATA).
FixedObstacles scenario_obstacles(const Scenario& s, const std::string& shared_dir);

}  // namespace mpgc::scenario_runner
