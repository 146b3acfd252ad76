// Every topic of the system with its type and QoS profile, in one place (design.md data flow).
#pragma once

namespace mpgc::topics {

// name                                      type                 QoS profile
inline constexpr const char* kClock = "clock";                  // Clock             command (reliable, keep-last 16)
inline constexpr const char* kStepAck = "clock/ack";            // StepAck           command
inline constexpr const char* kHealth = "health";                // ComponentHealth   latched (keyed by component)
inline constexpr const char* kOwnState = "nav/own_state";       // NavState          state (deadline 3 periods)
inline constexpr const char* kTruth = "sim/truth";              // GroundTruth       state
inline constexpr const char* kAis = "sensors/ais";              // AisReport         command (every report matters)
inline constexpr const char* kRadar = "sensors/radar";          // RadarScan         state
inline constexpr const char* kTracks = "sa/tracks";             // TrackList         state
inline constexpr const char* kEncounters = "sa/encounters";     // EncounterList     state
inline constexpr const char* kFixedObstacles = "obstacles/fixed";   // FixedObstacles  latched
inline constexpr const char* kMovingObstacles = "obstacles/moving"; // MovingObstacles state
inline constexpr const char* kGoal = "mission/goal";            // MissionGoal       latched
inline constexpr const char* kPath = "plan/path";               // Path              latched
inline constexpr const char* kPlanEncounters = "plan/encounters";   // EncounterList   latched
inline constexpr const char* kPlanMemory = "plan/memory";       // PlannerMemory     latched (opp reads it back on restart)
inline constexpr const char* kActuators = "control/actuators";  // ActuatorCommand   command
inline constexpr const char* kGuidanceStatus = "guidance/status";   // GuidanceStatus  state
inline constexpr const char* kFaults = "sim/faults";            // FaultCommand      command (simulated runs only)

}  // namespace mpgc::topics
