// Reader for traffic situations in the DNV ship-traffic-generator JSON format
// (../shared/data/encounters/dnv/): the own ship and target ships with WGS84 positions, SOG in
// knots and heading in degrees, plus the desired encounter types of the matching input file.
#pragma once

#include <string>
#include <vector>

#include "mpgc/colreg/colreg.hpp"

namespace mpgc::sa {

struct DnvShip {
  std::string name;
  double lat = 0.0;      // [rad]
  double lon = 0.0;      // [rad]
  double heading = 0.0;  // [rad] initial.heading; the generator sails every ship on its heading
  double sog = 0.0;      // [m/s]
  double length = 0.0;   // [m] NaN if absent
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

// Reads a generated situation. Throws std::runtime_error naming the file and the bad key.
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
