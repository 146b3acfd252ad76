// Scenario files (scenarios/*.yaml): what the closed-loop runner sails and how it is judged.
// Format reference: scenarios/README.md. Loading checks every field and names the file, line and
// key of any problem. No DDS, no clock.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/dnv/situation.hpp"

namespace mpgc::scenario_runner {

// A fault injected during a run (scenario key `faults:`, scenarios/README.md "Faults").
struct Fault {
  enum class Kind {
    kKill,          // SIGKILL the component's process (the launcher restarts it)
    kStop,          // SIGSTOP it for duration_s, then SIGCONT (a hung process)
    kSilence,       // every writer of `topic` drops its samples for duration_s
    kAisOutage,     // target `mmsi`'s AIS reports stop for duration_s
    kGnssDropout,   // no own-ship navigation output for duration_s
    kPositionJump,  // the reported own-ship position is off by (dx, dy) for duration_s
  };
  Kind kind = Kind::kKill;
  double at_s = 0.0;        // [s] simulated time it begins
  double duration_s = 0.0;  // [s] simulated (kStop of the ship_simulator: wall, its clock stops)
  std::string component;    // kKill, kStop
  std::string topic;        // kSilence
  std::uint32_t mmsi = 0;   // kAisOutage
  double dx = 0.0, dy = 0.0;  // [m] kPositionJump
  std::string describe() const;  // e.g. "kill opp", "silence sensors/ais for 60 s"
};
const char* to_string(Fault::Kind k);  // "kill", "stop", "silence", "ais_outage", ...

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
  // The evaluation's minimum acceptable CPA r_min_cpa (evaluation.min_cpa_m): every distance of the
  // evaluation is scaled with it (EvaluationParams::scaled_to). 0: the default, 10 own-ship lengths.
  double evaluation_min_cpa = 0.0;  // [m]
  PassCriteria criteria;
  // Per-component parameter overrides: component -> (name -> value).
  std::map<std::string, std::map<std::string, std::string>> params;
  std::vector<Fault> faults;     // in the order of at_s
};

// The evaluation's parameters for an own ship of `own_length` [m]: scaled to the length, or so
// that r_min_cpa = evaluation_min_cpa when the scenario gives one.
EvaluationParams evaluation_params(const Scenario& s, double own_length);

// Reads a scenario file: YAML (format above), or a DNV ship-traffic-generator situation (*.json,
// converted by dnv_scenario). Throws std::runtime_error "<file>:<line>: <key>: <problem>" (YAML)
// or "<file>: <field>: <problem>" (JSON). A YAML file with `from: FILE` is that scenario (YAML or
// JSON; relative to the file's folder, $MPGC_SHARED_DATA expanded) with its own name,
// description, faults, criteria, time limit and parameters on top.
Scenario load_scenario(const std::string& path);
Scenario parse_scenario(const std::string& yaml, const std::string& origin);

// DNV ship-traffic-generator situations (../shared/data/encounters/dnv/, scenarios/README.md
// "DNV situations"): the generated JSON becomes a scenario. The own ship starts at its first
// waypoint (the origin) on its initial heading at the first leg's SOG and must reach its last
// waypoint; targets follow their waypoints; the parameters the file does not give are the
// documented choices below. `desired` is the desiredEncounterType of each target (from the input
// file; empty entries or a short list: no requirement for those targets).
struct DnvChoices {
  double safety_distance = 926.0;        // [m] 0.5 NM, but at most min_range_share x the nearest target's start range
  double min_range_share = 0.8;          // [-]
  double colreg_distance = 5556.0;       // [m] d_COLREG, 3 NM
  double time_factor = 1.5;              // [-] time limit = route length / SOG x this, rounded up to 100 s
  double arrival_lengths = 2.0;          // [-] arrival radius in own-ship lengths
  double lookahead_lengths = 2.5;        // [-] LOS lookahead and circle of acceptance in own-ship lengths
  double safety_tolerance = 0.05;        // [-] pass: min distance >= d_safety x (1 - this)
  double max_safety_violation_s = 60.0;  // [s] pass: time allowed below d_safety
};
Scenario dnv_scenario(const std::string& path, const DnvChoices& choices = {});
// The conversion alone (no file access except the Nomoto table for the heading-controller gains).
Scenario dnv_scenario(const dnv::Situation& situation, const std::vector<std::string>& desired,
                      const DnvChoices& choices = {});

// Replaces every `<key>_lpp: v` by `<key>_m: v * lpp`, recursively (maps and sequences).
YAML::Node lpp_to_metres(const YAML::Node& n, double lpp);
// Multiplies every number of an obstacle_manager shapes string by `scale`.
std::string scale_shapes(const std::string& shapes, double scale);

}  // namespace mpgc::scenario_runner
