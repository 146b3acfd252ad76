// What opp must remember across a restart: the goal and plan it had, the path it was improving
// (warm start) and the COLREG obligations it had pinned. A planner restarted without them would
// re-judge every encounter from the ship's present, manoeuvred course (a give-way turn already
// under way could then read as a head-on to port) and start its plan ids again.
//
// Kept in a file, not only on the bus: Cyclone DDS 0.10 has no durability service, so a
// transient-local sample lives as long as its writer; a restarted process cannot read back what
// its dead predecessor published. The file is written after every plan (atomically, by rename).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/opp/encounters.hpp"
#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

struct PlannerMemory {
  uint32_t goal_id = 0;        // [-] goal of the last plan
  uint32_t plan_id = 0;        // [-] last plan id published
  uint32_t warm_goal = 0;      // [-] goal the warm-start path belongs to
  std::vector<Vec2> last_path; // [m] the last path found (warm start)
  std::vector<PinnedRecord> pinned;
};

// YAML text, doubles with 17 significant digits so that a restore is exact.
std::string to_yaml(const PlannerMemory& m);
// Throws std::invalid_argument naming `origin` and the field on malformed or non-finite content.
PlannerMemory memory_from_yaml(const std::string& text, const std::string& origin);

// Writes `path` atomically (temporary file + rename); throws std::runtime_error naming the file.
void save_memory(const std::string& path, const PlannerMemory& m);
// The memory in `path`, or nullopt when there is no such file; throws like memory_from_yaml.
std::optional<PlannerMemory> load_memory(const std::string& path);

}  // namespace mpgc::opp
