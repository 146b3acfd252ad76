// Every topic of the system, its type and QoS profile, in one place (design.md data flow).
#pragma once

#include <string_view>

namespace mpgc::topics {

inline constexpr const char* kClock = "clock";  // reliable, keep-last 16
inline constexpr const char* kStepAck = "clock/ack";
inline constexpr const char* kHealth = "health";  // keyed by component
inline constexpr const char* kOwnState = "nav/own_state";  // deadline 3 periods
inline constexpr const char* kTruth = "sim/truth";
inline constexpr const char* kAis = "sensors/ais";  // every report matters
inline constexpr const char* kRadar = "sensors/radar";
inline constexpr const char* kTracks = "sa/tracks";
inline constexpr const char* kEncounters = "sa/encounters";
inline constexpr const char* kFixedObstacles = "obstacles/fixed";
inline constexpr const char* kMovingObstacles = "obstacles/moving";
inline constexpr const char* kGoal = "mission/goal";
inline constexpr const char* kPath = "plan/path";
inline constexpr const char* kPlanEncounters = "plan/encounters";
inline constexpr const char* kPlanMemory = "plan/memory";  // opp reads it back on restart
inline constexpr const char* kActuators = "control/actuators";
inline constexpr const char* kGuidanceStatus = "guidance/status";
inline constexpr const char* kFaults = "sim/faults";  // simulated runs only

// Every topic with its type and QoS profile, for code that handles every topic alike (the
// recorder, replay): a topic added here is recorded without other changes. `type` is the IDL
// name (mpgc/msg/all.hpp finds it), `qos` a dds::QosProfile::by_name name.
struct Info {
  const char* name;
  const char* type;
  const char* qos;
};
inline constexpr Info kAll[] = {
    {kClock, "mpgc::msg::Clock", "command"},
    {kStepAck, "mpgc::msg::StepAck", "command"},
    {kHealth, "mpgc::msg::ComponentHealth", "latched"},
    {kOwnState, "mpgc::msg::NavState", "state"},
    {kTruth, "mpgc::msg::GroundTruth", "state"},
    {kAis, "mpgc::msg::AisReport", "command"},
    {kRadar, "mpgc::msg::RadarScan", "state"},
    {kTracks, "mpgc::msg::TrackList", "state"},
    {kEncounters, "mpgc::msg::EncounterList", "state"},
    {kFixedObstacles, "mpgc::msg::FixedObstacles", "latched"},
    {kMovingObstacles, "mpgc::msg::MovingObstacles", "state"},
    {kGoal, "mpgc::msg::MissionGoal", "latched"},
    {kPath, "mpgc::msg::Path", "latched"},
    {kPlanEncounters, "mpgc::msg::EncounterList", "latched"},
    {kPlanMemory, "mpgc::msg::PlannerMemory", "latched"},
    {kActuators, "mpgc::msg::ActuatorCommand", "command"},
    {kGuidanceStatus, "mpgc::msg::GuidanceStatus", "state"},
    {kFaults, "mpgc::msg::FaultCommand", "command"},
};

// The entry of a topic by name, or nullptr when topics.hpp has none.
inline const Info* find(std::string_view name) {
  for (const auto& t : kAll)
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace mpgc::topics
