// Report of one evaluated run: metrics.json, the time series as CSV, and two SVG figures written
// by hand (no plotting library): the trajectory map and the distance to the closest obstacle over
// time against d_safety (the DTC figures of seed 000, Fig. 10/16/19).
//
//   const auto m = scenario_runner::evaluate(run, params, criteria);
//   scenario_runner::ReportOptions opt;
//   opt.scenario = "paper_s1_colreg";
//   opt.length_unit = 320.0, opt.length_unit_name = "Lpp";  // axes in ship lengths
//   m.wall_s = ...;                                          // the runner knows it
//   scenario_runner::write_report("out/paper_s1_colreg", run, m, opt);
//
// Keys of metrics.json are snake_case with the unit as suffix and stay stable (see
// write_metrics_json); non-finite numbers (a value that does not exist, e.g. no time to a goal not
// reached) are written as null. Written through nlohmann-json (mpgc/json/json.hpp).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "mpgc/scenario_runner/evaluation.hpp"

namespace mpgc::scenario_runner {

struct ReportOptions {
  std::string scenario;                 // name in the titles and in metrics.json
  double length_unit = 1.0;             // [m] plot axes in multiples of this (e.g. Lpp = 320 m)
  std::string length_unit_name = "m";   // its name on the axes ("m", "Lpp", "km")
  int snapshot_instants = 4;            // evenly spaced instants with ship markers and d_safety
                                        // circles around the targets (plus each target's CPA)
  bool show_plans = true;               // planned paths at the re-plan instants (thin lines)
  void validate() const;                // throws std::invalid_argument naming the field
};

// metrics.json: one object. Keys: scenario, passed, failures[], goal_reached, time_to_goal_s,
// min_distance_m {overall, fixed, targets {"<id>": m}}, safety_distance_m, safety_violation_s,
// near_misses {r_nm_m, count, targets [ids]}, likely_collisions {r_col_cpa_m, count, targets [ids]},
// path_length_m, straight_line_m, planning_ms {median, p95, max}, replans, relaxed_plans,
// no_path_plans, tracking_rmse_m, wall_s, sim_s, evaluation_scale, components {"<name>":
// {peak_rss_mb, cpu_s}} (empty when the launcher's log had none), encounters[] {target_id,
// encountered, situation, role, t_start_s, range_start_m, beta_start_deg, alpha_start_deg,
// dcpa_start_m, cpa_m, t_cpa_s, passing_side, bow_crossing_m, t_manoeuvre_s, manoeuvre_side,
// max_starboard_change_deg, max_port_change_deg, max_speed_reduction, verdicts {turned_starboard,
// passed_port_to_port, not_crossed_ahead, kept_clear, held_course_and_speed: "pass"|"fail"|"n/a"},
// t_hold_end_s, conflicting_obligation, compliant}.
void write_metrics_json(std::ostream& out, const Metrics& m, const ReportOptions& opt);

// The processes' usage from a launcher's log: its lines "[launch] NAME exited ... (peak RSS X MB,
// CPU Y s)", in order; a name that ended twice (restarted) keeps the larger peak and the sum of
// the CPU. Other lines, and malformed figures, are skipped.
std::vector<ComponentUsage> component_usage(const std::string& launcher_log);

// The near misses and likely collisions of the run summary, e.g. "near misses 2 (target 1 at
// 1234.5 m, target 3 at 500.0 m; r_nm 1600.0 m), likely collisions 1 (target 3; r_col_cpa
// 960.0 m)"; "" when there is neither.
std::string close_calls_text(const Metrics& m);

// One row per truth sample: t_s; own_x_m, own_y_m, own_heading_rad, own_cog_rad, own_sog_mps; per
// target tgt<id>_x_m ... tgt<id>_sog_mps and dist_tgt<id>_m; dist_fixed_m (with fixed obstacles);
// dist_closest_m; plan_id and path_distance_m (the active plan and the own ship's distance to it,
// empty before the first plan); guidance_plan_id, active_waypoint, cross_track_error_m (last
// guidance sample at or before t, empty before the first).
void write_timeseries_csv(std::ostream& out, const RunRecord& run);

// The trajectory map (north up, east right, equal scale): own and target tracks, fixed obstacles
// filled, d_safety circles around the targets at a few instants, planned paths, start and goal
// with its arrival circle, legend outside the plot.
void write_trajectory_svg(std::ostream& out, const RunRecord& run, const Metrics& m, const ReportOptions& opt);

// Distance from the own ship to each target and to the fixed obstacles over time, with d_safety
// as a dashed horizontal line.
void write_dtc_svg(std::ostream& out, const RunRecord& run, const Metrics& m, const ReportOptions& opt);

// Writes metrics.json, timeseries.csv, trajectory.svg and dtc.svg into `dir` (created if needed)
// and returns their paths. Throws std::runtime_error naming the file it cannot write.
std::vector<std::string> write_report(const std::string& dir, const RunRecord& run, const Metrics& m,
                                      const ReportOptions& opt);

}  // namespace mpgc::scenario_runner
