// Planners by name (plan.planner): every planner behind the interface is listed here once.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mpgc/opp/planner.hpp"

namespace mpgc::opp {

// The names make_planner accepts, the default ("rrtstar") first.
std::vector<std::string> planner_names();
// A new planner of that name; throws std::invalid_argument naming the known ones otherwise.
std::unique_ptr<Planner> make_planner(const std::string& name);

}  // namespace mpgc::opp
