// Reader for traffic situations in the DNV ship-traffic-generator JSON format
// (../shared/data/encounters/dnv/): the own ship and target ships with WGS84 positions, SOG in
// knots and heading in degrees, plus the desired encounter types of the matching input file.
// In common/ because two components read them: the scenario runner (DNV situations as scenarios)
// and situational_awareness's mpgc_classify. No DDS, no clock.
//
//   dnv::Situation s = dnv::read_situation(".../traffic_situation_07.json");
//   for (const dnv::TargetResult& r : dnv::assess(s, colreg::ColregParams{})) ...
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpgc/colreg/colreg.hpp"

namespace mpgc::dnv {

// One route point of a generated situation: waypoints[i].position and waypoints[i].leg.sog.
struct Waypoint {
  double lat = 0.0;  // [rad]
  double lon = 0.0;  // [rad]
  double sog = 0.0;  // [m/s] leg.sog (the leg from this waypoint on); NaN if the waypoint has no leg
};

struct Ship {
  std::string name;
  std::uint32_t mmsi = 0;  // [-] static.mmsi; 0 if absent
  double lat = 0.0;      // [rad]
  double lon = 0.0;      // [rad]
  double heading = 0.0;  // [rad] initial.heading; the generator sails every ship on its heading
  double sog = 0.0;      // [m/s]
  double length = 0.0;   // [m] static.dimensions.length; NaN if absent
  double width = 0.0;    // [m] static.dimensions.width; NaN if absent
  std::vector<Waypoint> waypoints;  // the route (generated files); empty in input files
};

struct Situation {
  std::string path;
  std::string title;
  Ship own;
  std::vector<Ship> targets;
  // desiredEncounterType per target from the input file ("head-on", "crossing-give-way", ...);
  // empty when no input file was found.
  std::vector<std::string> desired;
};

// Reads a generated situation. Throws std::runtime_error "<file>: <field>: <problem>" naming the
// file and the bad field (e.g. "targetShips[1].waypoints[0].position.lat") or, for a file that is
// not JSON at all, the parser's line and column.
Situation read_situation(const std::string& path);
// desiredEncounterType of every encounter of an input file (baseline_situations_input/*.json), or
// of the file itself when it carries "encounters". Throws std::runtime_error on malformed files.
std::vector<std::string> read_desired(const std::string& path);
// The input file for a generated one: .../baseline_situations_generated/traffic_situation_NN.json
// -> .../baseline_situations_input/baseline_situation_NN_*.json; empty if there is none.
std::string find_input(const std::string& generated_path);

struct TargetResult {
  colreg::ShipKinematics own, target;  // NED about the own ship's position
  colreg::Assessment assessment;
};
// Every target of the situation assessed from the own ship (GeographicLib local NED at the own
// ship; velocities from SOG along the heading).
std::vector<TargetResult> assess(const Situation& s, const colreg::ColregParams& p);

// A desiredEncounterType ("head-on", "crossing-give-way", ...) as the encounter type; kNone for
// anything else (the inverse of colreg::dnv_name).
colreg::EncounterType encounter_type(const std::string& name);

}  // namespace mpgc::dnv
