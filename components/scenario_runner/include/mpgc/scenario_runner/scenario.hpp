// Scenario files (scenarios/*.yaml): what the closed-loop runner sails and how it is judged.
// Format reference: scenarios/README.md. Loading checks every field and names the file, line and
// key of any problem. No DDS, no clock.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mpgc/scenario_runner/evaluation.hpp"

namespace mpgc::scenario_runner {

struct Scenario {
  std::string name;
  std::string description;
  std::string path;              // file it was read from
  double lpp = 320.0;            // [m] ship length: the unit of every *_lpp key and of the plots
  bool plot_in_lpp = true;       // plot axes in Lpp (else metres)
  YAML::Node world;              // ship_simulator world (all *_lpp keys already turned into *_m)
  double origin_lat_deg = 0.0;   // [deg] from world.origin
  double origin_lon_deg = 0.0;   // [deg]
  Goal goal;                     // [m] arrival point and radius
  double goal_heading = std::numeric_limits<double>::quiet_NaN();  // [rad] NaN: any
  double goal_heading_tolerance = 3.14159265358979323846;          // [rad]
  double cruise_speed = 0.0;     // [m/s] goal.speed_kn, else the own ship's start speed; 0: current speed
  double safety_distance = 0.0;  // [m] d_safety
  bool colreg = true;            // COLREG-compliant paths required first
  std::string chart_shapes;      // obstacle_manager chart.shapes (NED metres)
  std::vector<std::string> chart_files;
  double time_limit = 0.0;       // [s] simulated
  PassCriteria criteria;
  // Per-component parameter overrides: component -> (name -> value).
  std::map<std::string, std::map<std::string, std::string>> params;
};

// Reads a scenario YAML file. Throws std::runtime_error "<file>:<line>: <key>: <problem>".
Scenario load_scenario(const std::string& path);
Scenario parse_scenario(const std::string& yaml, const std::string& origin);

// Replaces every `<key>_lpp: v` by `<key>_m: v * lpp`, recursively (maps and sequences).
YAML::Node lpp_to_metres(const YAML::Node& n, double lpp);
// Multiplies every number of an obstacle_manager shapes string by `scale`.
std::string scale_shapes(const std::string& shapes, double scale);

}  // namespace mpgc::scenario_runner
