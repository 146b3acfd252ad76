// The simulated world: own ship (any ShipModel), target ships and sensors, stepped at a fixed
// step. Time and seeds are inputs; nothing here reads a clock or talks DDS. The YAML format is
// documented in components/ship_simulator/README.md.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/sensors.hpp"
#include "mpgc/ship_simulator/ship_model.hpp"
#include "mpgc/ship_simulator/targets.hpp"

namespace mpgc::ship_simulator {

struct WorldConfig {
  geo::LatLon origin{0.0, 0.0};  // [rad] origin of the local NED frame
  uint64_t seed = 1;             // base seed; sensors without their own seed derive from it
  ModelChoice model;             // own-ship model
  ShipState own_start;           // [SI] start state (rpm filled from speed when own_rpm < 0)
  double own_rpm = -1.0;         // [1/min] start propeller speed; < 0: the straight-run rpm
  uint32_t own_mmsi = 0;
  Environment environment;
  std::vector<TargetConfig> targets;
  NavSensorConfig nav;
  AisConfig ais;
  RadarConfig radar;
  double radar_antenna_x = 0.0;  // [m] antenna forward of midship (body axes)

  // Parses the world YAML text; every error names the key (and file/origin).
  static WorldConfig from_yaml(const std::string& text, const std::string& origin = "<string>");
  static WorldConfig from_file(const std::string& path);
  // The target with this MMSI; throws std::out_of_range when there is none.
  const TargetConfig& target(uint32_t mmsi) const;
};

struct TruthShip {
  uint32_t id, mmsi;
  double x, y, heading, cog, sog, u, v, r, length, beam;
};

struct RadarScanOut {
  double antenna_x, antenna_y, max_range;
  std::vector<RadarContactOut> contacts;
};

// What the sensors produced at the current time.
struct SensorOutputs {
  std::optional<NavMeasurement> nav;
  std::vector<AisMeasurement> ais;
  std::optional<RadarScanOut> radar;
};

class World {
 public:
  World(WorldConfig cfg, int64_t step_ns);
  // Advances one step with the command held over it.
  void step(const ShipCommand& cmd);
  // Samples due at the current time (call once per step, also at time 0).
  SensorOutputs sense();

  int64_t time_ns() const { return static_cast<int64_t>(step_) * step_ns_; }
  uint64_t step_index() const { return step_; }
  int64_t step_ns() const { return step_ns_; }
  const ShipModel& own() const { return *own_; }
  ShipModel& own() { return *own_; }
  TruthShip own_truth() const;
  std::vector<TruthShip> target_truth() const;
  const std::vector<TargetShip>& targets() const { return targets_; }
  const geo::LocalNed& frame() const { return frame_; }
  const WorldConfig& config() const { return cfg_; }
  ShipCommand initial_command() const { return {0.0, own_->state().rpm}; }

 private:
  Kinematics own_kinematics() const;
  WorldConfig cfg_;
  int64_t step_ns_;
  uint64_t step_ = 0;
  std::unique_ptr<ShipModel> own_;
  std::vector<TargetShip> targets_;
  bool any_colreg_ = false;  // some target has a rule-following helmsman
  geo::LocalNed frame_;
  NavSensor nav_;
  RadarSensor radar_;
  std::vector<AisTransmitter> ais_;
  int64_t next_nav_ns_ = 0, next_radar_ns_ = 0;
};

}  // namespace mpgc::ship_simulator
