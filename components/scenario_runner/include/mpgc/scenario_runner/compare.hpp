// Planners side by side (./mpgc compare, issue 18 part 3): the same scenarios sailed once per
// planner (mpgc_run --planner NAME --out DIR/NAME), then one table with a row per planner and a
// last line of JSON, read back from each run's metrics.json.
//
//   std::vector<PlannerResults> all;
//   for (planner : planners) all.push_back({planner, read_results(dir + "/" + planner, names)});
//   std::cout << compare_text(all);   // the table, every scenario a planner did not pass, the JSON
//
// A scenario whose metrics.json is missing or unreadable (the run broke) counts in `total` and
// not in `passed`, and is listed as an ERROR; the figures over scenarios (distances, elongation,
// COLREG, planning time) are over the scenarios that have a metrics.json. Nothing is left out of
// the table: every scenario a planner did not pass is named under it with its failures.
#pragma once

#include <string>
#include <vector>

namespace mpgc::scenario_runner {

// What compare reads of one scenario's metrics.json.
struct ScenarioFigures {
  std::string scenario;
  bool ran = false;           // a metrics.json was read
  std::string error;          // why not (ran == false)
  bool passed = false;
  std::vector<std::string> failures;
  int collisions = 0;         // likely_collisions.count
  double min_distance = 0;    // [m] min_distance_m.overall (NaN: null)
  double safety_distance = 0; // [m]
  double path_length = 0;     // [m]
  double straight_line = 0;   // [m]
  double plan_median_ms = 0;  // [ms] planning_ms.median of the run
  double plan_p95_ms = 0;     // [ms] planning_ms.p95 of the run
  int encounters = 0;         // encounters with a situation that the own ship met (encountered, not "none")
  int compliant = 0;          // of those, compliant: true
  bool colreg = true;         // the scenario requires COLREG (its `colreg`); the encounters of one that
                              // does not (seed 000's *_nocolreg: a violation is required) are not counted
};

// Reads `path` (a metrics.json); a missing or malformed file gives ran = false with the reason.
ScenarioFigures read_figures(const std::string& path, const std::string& scenario);

struct PlannerResults {
  std::string planner;
  std::vector<ScenarioFigures> scenarios;
};

// DIR/<scenario>/metrics.json for each of `scenarios` (the names mpgc_run gives the folders).
std::vector<ScenarioFigures> read_results(const std::string& dir, const std::vector<std::string>& scenarios);

// One planner's row. Ratios and medians are NaN where no scenario gives a value.
struct PlannerSummary {
  std::string planner;
  int passed = 0, total = 0, errors = 0;
  int collisions = 0;               // sum of likely collisions
  double min_dist_ratio_worst = 0;  // min over scenarios of min distance / d_safety
  double min_dist_ratio_median = 0; // median over scenarios of the same
  double elongation_median = 0;     // median of path_length / straight_line
  int encounters = 0, compliant = 0;  // over the scenarios that require COLREG
  double colreg_compliant_share = 0;  // compliant / encounters
  double plan_ms_median = 0;          // median over scenarios of each run's median planning time
  double plan_ms_p95 = 0;             // max over scenarios of each run's p95 (the worst scenario's p95)
};

PlannerSummary summarize(const PlannerResults& r);

// The table (one row per planner), then per planner every scenario it did not pass (FAIL with its
// failures, ERROR with why there is no metrics.json), then a per-scenario line of verdicts where
// the planners disagree or fail, and last the JSON line:
// {"planners": {NAME: {"passed", "total", "collisions", "min_dist_ratio_worst", "elongation_median",
// "colreg_compliant_share", "plan_ms_median", "plan_ms_p95"}}} (null where there is no value).
std::string compare_table(const std::vector<PlannerResults>& results);
std::string compare_json(const std::vector<PlannerResults>& results);
std::string compare_text(const std::vector<PlannerResults>& results);  // table + "\n" + JSON line

}  // namespace mpgc::scenario_runner
