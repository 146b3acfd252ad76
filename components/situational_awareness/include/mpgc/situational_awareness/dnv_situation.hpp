// Reader for traffic situations in the DNV ship-traffic-generator JSON format
// (../shared/data/encounters/dnv/): the own ship and target ships with WGS84 positions, SOG in
// knots and heading in degrees, plus the desired encounter types of the matching input file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mpgc/colreg/colreg.hpp"

namespace mpgc::sa {

// One route point of a generated situation: waypoints[i].position and waypoints[i].leg.sog.
struct DnvWaypoint {
  double lat = 0.0;  // [rad]
  double lon = 0.0;  // [rad]
  double sog = 0.0;  // [m/s] leg.sog (the leg from this waypoint on); NaN if the waypoint has no leg
};

struct DnvShip {
  std::string name;
  std::uint32_t mmsi = 0;  // [-] static.mmsi; 0 if absent
  double lat = 0.0;      // [rad]
  double lon = 0.0;      // [rad]
  double heading = 0.0;  // [rad] initial.heading; the generator sails every ship on its heading
  double sog = 0.0;      // [m/s]
  double length = 0.0;   // [m] static.dimensions.length; NaN if absent
  double width = 0.0;    // [m] static.dimensions.width; NaN if absent
  std::vector<DnvWaypoint> waypoints;  // the route (generated files); empty in input files
};

struct DnvSituation {
  std::string path;
  std::string title;
  DnvShip own;
  std::vector<DnvShip> targets;
  // desiredEncounterType per target from the input file ("head-on", "crossing-give-way", ...);
  // empty when no input file was found.
  std::vector<std::string> desired;
};

// Reads a generated situation. Throws std::runtime_error "<file>: <field>: <problem>" naming the
// file and the bad field (e.g. "targetShips[1].waypoints[0].position.lat") or, for a file that is
// not JSON at all, the parser's line and column.
DnvSituation read_dnv_situation(const std::string& path);
// desiredEncounterType of every encounter of an input file (baseline_situations_input/*.json), or
// of the file itself when it carries "encounters". Throws std::runtime_error on malformed files.
std::vector<std::string> read_dnv_desired(const std::string& path);
// The input file for a generated one: .../baseline_situations_generated/traffic_situation_NN.json
// -> .../baseline_situations_input/baseline_situation_NN_*.json; empty if there is none.
std::string find_dnv_input(const std::string& generated_path);

struct DnvTargetResult {
  colreg::ShipKinematics own, target;  // NED about the own ship's position
  colreg::Assessment assessment;
};
// Every target of the situation assessed from the own ship (GeographicLib local NED at the own
// ship; velocities from SOG along the heading).
std::vector<DnvTargetResult> assess_dnv(const DnvSituation& s, const colreg::ColregParams& p);

// "head-on" etc. to the encounter type; kNone for anything else.
colreg::EncounterType from_dnv_name(const std::string& name);

}  // namespace mpgc::sa
