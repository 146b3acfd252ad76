// Encounter memory: which COLREG obligation the own ship has towards each target, fixed when the
// risk of collision first appears and kept until that target is passed (the situation of rules
// 13-15 is established once, at the start of an encounter, not re-judged from every new course).
// The planner holds each leg to the pinned obligation (colreg_check_pinned); without the memory
// it would re-derive the situation per leg (seed 000 §5) and a turn to port made early could
// turn a head-on into a crossing passed starboard to starboard.
//
//   opp::EncounterMemory mem;        // kept across plans
//   pb.targets = ...;
//   mem.update(params, own, pb.targets);   // fills Target::pinned, forgets targets no longer tracked
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/opp/problem.hpp"

namespace mpgc::opp {

struct EncounterMemoryParams {
  // Risk of collision on present courses (rules 7-8): the CPA passes inside cpa_risk within
  // tcpa_max. Only then is an obligation pinned.
  double cpa_risk = 1000.0;      // [m] the planner's d_safety
  double tcpa_max = 1800.0;      // [s] 30 min, the DNV generator's situation length
  double release_range = 3000.0; // [m] an opening target beyond it and beyond the range it was
                                 //     pinned at is done with (d_COLREG)
  // A target that changes course by more than this starts a new encounter (re-assessed): the
  // own ship's manoeuvres never re-open the situation, the target's do (unexpected behaviour).
  double new_course = 0.2617993877991494;  // [rad] 15 deg
  double abaft_beam = 0.39269908169872414;  // [rad] rule 13: overtaking from more than this abaft the beam
  double head_on_sector = 0.39269908169872414;  // [rad] rule 14: head-on when each is within this of the other's bow
  // The own course this far to starboard of course0 (either side when overtaking or overtaken)
  // marks a pinned encounter's alteration as begun (PinnedEncounter::acted).
  double acted_turn = 0.08726646259971647;  // [rad] 5 deg
  // ... and this far (colreg's apparent_turn) as made (PinnedEncounter::completed); 0: never.
  double apparent_turn = 0.5235987755982988;  // [rad] 30 deg
  // The same by speed (for a give-way, head-on or overtaking duty): the speed sailed this much below
  // the encounter's speed0 marks the action as begun (above the speed a turn alone loses), and
  // apparent_slowdown (colreg's) below it as made; 0: never. Without it a slow-down begun for a
  // ship was given up before it was apparent (DNV 41: 48 % for the 50 % rule 8(b) asks).
  double acted_slowdown = 0.2;     // [-]
  double apparent_slowdown = 0.5;  // [-]
  // Range within which a crossing stand-on target's rule 17(c) reference (PinnedEncounter::held_17c)
  // follows the own course (colreg's port_turn_range).
  double port_turn_range = 1e300;  // [m]
  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
  // The risk-of-collision assessment these parameters describe (any range: tcpa_max bounds it).
  colreg::ColregParams assessment() const;
};

// One pinned encounter as it is remembered across a restart (memory.hpp).
struct PinnedRecord {
  uint32_t id = 0;     // [-] target id
  PinnedEncounter e;
  double range0 = 0;   // [m] range when pinned
};

class EncounterMemory {
 public:
  // Own ship and targets at the same time (the plan's t = 0). Pins new encounters, releases
  // passed ones (and those whose target turned) and sets Target::pinned of every target. Bad parameters or non-finite input
  // throw std::invalid_argument (the memory is then unchanged).
  void update(const EncounterMemoryParams& p, const colreg::ShipKinematics& own, std::vector<Target>& targets);
  // The pinned obligation of a target id (kNone when there is none).
  PinnedEncounter find(uint32_t id) const;
  std::size_t size() const { return pinned_.size(); }
  // What a restarted planner needs to hold the same obligations (ordered by id).
  std::vector<PinnedRecord> records() const;
  // Replaces the memory; throws std::invalid_argument (memory unchanged) on a non-finite angle or
  // range, an unknown obligation or a duplicate id.
  void restore(const std::vector<PinnedRecord>& records);

 private:
  struct Entry {
    PinnedEncounter e;
    double range0;  // [m] range when pinned
  };
  std::map<uint32_t, Entry> pinned_;
};

}  // namespace mpgc::opp
