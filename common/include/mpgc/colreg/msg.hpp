// The COLREG vocabulary on the bus: colreg::EncounterType and colreg::Role as the tracks.idl enums
// (EncounterType, OwnRole). One conversion for every component that publishes encounters
// (situational_awareness's sa/encounters, opp's plan/encounters); needs mpgc_msgs.
#pragma once

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/msg/tracks.hpp"

namespace mpgc::colreg {

inline msg::EncounterType to_msg(EncounterType t) {
  switch (t) {
    case EncounterType::kHeadOn: return msg::EncounterType::ENCOUNTER_HEAD_ON;
    case EncounterType::kCrossingGiveWay: return msg::EncounterType::ENCOUNTER_CROSSING_GIVE_WAY;
    case EncounterType::kCrossingStandOn: return msg::EncounterType::ENCOUNTER_CROSSING_STAND_ON;
    case EncounterType::kOvertaking: return msg::EncounterType::ENCOUNTER_OVERTAKING;
    case EncounterType::kOvertaken: return msg::EncounterType::ENCOUNTER_OVERTAKEN;
    case EncounterType::kNone: break;
  }
  return msg::EncounterType::ENCOUNTER_NONE;
}

inline msg::OwnRole to_msg(Role r) {
  switch (r) {
    case Role::kGiveWay: return msg::OwnRole::ROLE_GIVE_WAY;
    case Role::kStandOn: return msg::OwnRole::ROLE_STAND_ON;
    case Role::kBothGiveWay: return msg::OwnRole::ROLE_BOTH_GIVE_WAY;
    case Role::kNone: break;
  }
  return msg::OwnRole::ROLE_NONE;
}

}  // namespace mpgc::colreg
