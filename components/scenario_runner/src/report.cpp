#include "mpgc/scenario_runner/report.hpp"

#include <map>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace mpgc::scenario_runner {

namespace {

// Shortest text that reads back to the same double; null when not finite (JSON has no NaN).
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  for (int prec = 6; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

std::string quote(const std::string& s) {
  std::string r = "\"";
  for (const unsigned char c : s) {
    switch (c) {
      case '"': r += "\\\""; break;
      case '\\': r += "\\\\"; break;
      case '\n': r += "\\n"; break;
      case '\r': r += "\\r"; break;
      case '\t': r += "\\t"; break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          r += buf;
        } else {
          r += static_cast<char>(c);
        }
    }
  }
  return r + "\"";
}

const char* boolean(bool b) { return b ? "true" : "false"; }
std::string deg(double rad) { return num(rad * 180.0 / geo::kPi); }

// CSV cell: empty when not finite.
std::string cell(double v) { return std::isfinite(v) ? num(v) : ""; }

}  // namespace

void ReportOptions::validate() const {
  if (!(std::isfinite(length_unit) && length_unit > 0.0))
    throw std::invalid_argument("ReportOptions.length_unit must be finite and > 0");
  if (length_unit_name.empty()) throw std::invalid_argument("ReportOptions.length_unit_name is empty");
  if (snapshot_instants < 0 || snapshot_instants > 50)
    throw std::invalid_argument("ReportOptions.snapshot_instants must be in [0, 50]");
}

void write_metrics_json(std::ostream& o, const Metrics& m, const ReportOptions& opt) {
  o << "{\n";
  o << "  \"scenario\": " << quote(opt.scenario) << ",\n";
  o << "  \"passed\": " << boolean(m.passed) << ",\n";
  o << "  \"failures\": [";
  for (std::size_t i = 0; i < m.failures.size(); ++i) o << (i ? ", " : "") << quote(m.failures[i]);
  o << "],\n";
  o << "  \"goal_reached\": " << boolean(m.goal_reached) << ",\n";
  o << "  \"time_to_goal_s\": " << num(m.t_goal) << ",\n";
  o << "  \"min_distance_m\": {\"overall\": " << num(m.min_distance) << ", \"fixed\": " << num(m.min_distance_fixed)
    << ", \"targets\": {";
  for (std::size_t i = 0; i < m.min_distance_targets.size(); ++i)
    o << (i ? ", " : "") << "\"" << m.min_distance_targets[i].target_id
      << "\": " << num(m.min_distance_targets[i].min_distance);
  o << "}},\n";
  o << "  \"safety_distance_m\": " << num(m.safety_distance) << ",\n";
  o << "  \"safety_violation_s\": " << num(m.safety_violation_s) << ",\n";
  o << "  \"path_length_m\": " << num(m.path_length) << ",\n";
  o << "  \"straight_line_m\": " << num(m.straight_line) << ",\n";
  o << "  \"planning_ms\": {\"median\": " << num(m.planning.median_ms) << ", \"p95\": " << num(m.planning.p95_ms)
    << ", \"max\": " << num(m.planning.max_ms) << "},\n";
  o << "  \"replans\": " << m.replans << ",\n";
  o << "  \"relaxed_plans\": " << m.relaxed_plans << ",\n";
  o << "  \"no_path_plans\": " << m.no_path_plans << ",\n";
  o << "  \"tracking_rmse_m\": " << num(m.tracking_rmse) << ",\n";
  o << "  \"wall_s\": " << num(m.wall_s) << ",\n";
  o << "  \"sim_s\": " << num(m.sim_s) << ",\n";
  o << "  \"evaluation_scale\": " << num(m.scale) << ",\n";
  o << "  \"encounters\": [";
  for (std::size_t i = 0; i < m.encounters.size(); ++i) {
    const EncounterResult& e = m.encounters[i];
    o << (i ? ",\n" : "\n") << "    {\"target_id\": " << e.target_id << ", \"encountered\": " << boolean(e.encountered)
      << ", \"situation\": " << quote(colreg::to_string(e.situation)) << ", \"role\": " << quote(to_string(e.role))
      << ",\n     \"t_start_s\": " << num(e.t_start) << ", \"range_start_m\": " << num(e.range_start)
      << ", \"beta_start_deg\": " << deg(e.beta_start) << ", \"alpha_start_deg\": " << deg(e.alpha_start)
      << ", \"dcpa_start_m\": " << num(e.dcpa_start) << ",\n     \"cpa_m\": " << num(e.cpa)
      << ", \"t_cpa_s\": " << num(e.t_cpa) << ", \"passing_side\": " << quote(to_string(e.passing_side))
      << ", \"bow_crossing_m\": " << num(e.bow_crossing) << ",\n     \"t_manoeuvre_s\": " << num(e.t_manoeuvre)
      << ", \"manoeuvre_side\": " << quote(to_string(e.manoeuvre_side))
      << ", \"max_starboard_change_deg\": " << deg(e.max_starboard_change)
      << ", \"max_port_change_deg\": " << deg(e.max_port_change)
      << ", \"max_speed_reduction\": " << num(e.max_speed_reduction) << ",\n     \"verdicts\": {\"turned_starboard\": "
      << quote(to_string(e.turned_starboard)) << ", \"passed_port_to_port\": " << quote(to_string(e.passed_port_to_port))
      << ", \"not_crossed_ahead\": " << quote(to_string(e.not_crossed_ahead))
      << ", \"kept_clear\": " << quote(to_string(e.kept_clear))
      << ", \"held_course_and_speed\": " << quote(to_string(e.held_course_and_speed))
      << "},\n     \"t_hold_end_s\": " << num(e.t_hold_end)
      << ", \"conflicting_obligation\": " << boolean(e.conflicting_obligation)
      << ", \"compliant\": " << boolean(e.compliant) << "}";
  }
  o << (m.encounters.empty() ? "],\n" : "\n  ],\n");
  // Faults and recoveries: each fault, then per component how often it was killed and came back.
  o << "  \"faults\": [";
  std::map<std::string, std::pair<int, int>> per_component;  // killed or stopped, recovered
  for (std::size_t i = 0; i < m.faults.size(); ++i) {
    const FaultRecord& f = m.faults[i];
    o << (i ? ",\n" : "\n") << "    {\"what\": " << quote(f.what) << ", \"component\": " << quote(f.component)
      << ", \"planned_s\": " << num(f.t_planned) << ", \"t_s\": " << num(f.t) << ", \"end_s\": " << num(f.t_end)
      << ", \"recovered_s\": " << num(f.t_recovered) << ", \"recovery_s\": "
      << num(f.needs_recovery ? f.t_recovered - f.t : kNaN) << ", \"recovery_wall_s\": " << num(f.wall_recovery) << "}";
    if (f.needs_recovery) {
      auto& pc = per_component[f.component];
      ++pc.first;
      pc.second += std::isfinite(f.t_recovered) ? 1 : 0;
    }
  }
  o << (m.faults.empty() ? "],\n" : "\n  ],\n") << "  \"recoveries\": {";
  std::size_t k = 0;
  for (const auto& [c, n] : per_component)
    o << (k++ ? ", " : "") << quote(c) << ": {\"faulted\": " << n.first << ", \"recovered\": " << n.second << "}";
  o << "}\n}\n";
}

void write_timeseries_csv(std::ostream& o, const RunRecord& run) {
  run.validate();
  const DistanceSeries ds = distance_series(run);
  const std::vector<int> active = active_plan_index(run);
  o << "t_s,own_x_m,own_y_m,own_heading_rad,own_cog_rad,own_sog_mps";
  for (const auto& tg : run.targets) {
    const std::string p = "tgt" + std::to_string(tg.id) + "_";
    o << "," << p << "x_m," << p << "y_m," << p << "heading_rad," << p << "cog_rad," << p << "sog_mps,dist_" << p << "m";
  }
  if (!ds.fixed.empty()) o << ",dist_fixed_m";
  o << ",dist_closest_m,plan_id,path_distance_m,guidance_plan_id,active_waypoint,cross_track_error_m\n";
  std::size_t g = 0;
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    auto state = [&](const ShipState& s) {
      o << "," << num(s.x) << "," << num(s.y) << "," << num(s.heading) << "," << num(s.cog) << "," << num(s.sog);
    };
    o << num(run.t[i]);
    state(run.own.states[i]);
    for (std::size_t k = 0; k < run.targets.size(); ++k) {
      state(run.targets[k].states[i]);
      o << "," << num(ds.target[k][i]);
    }
    if (!ds.fixed.empty()) o << "," << num(ds.fixed[i]);
    o << "," << cell(ds.closest[i]);
    if (active[i] >= 0) {
      const PlanRecord& p = run.plans[static_cast<std::size_t>(active[i])];
      o << "," << p.plan_id << ","
        << num(distance_to_path({run.own.states[i].x, run.own.states[i].y}, p.waypoints));
    } else {
      o << ",,";
    }
    while (g < run.guidance.size() && run.guidance[g].t <= run.t[i]) ++g;
    if (g > 0) {
      const GuidanceRecord& gr = run.guidance[g - 1];
      o << "," << gr.plan_id << "," << gr.active_waypoint << "," << cell(gr.cross_track_error) << "\n";
    } else {
      o << ",,,\n";
    }
  }
}

std::vector<std::string> write_report(const std::string& dir, const RunRecord& run, const Metrics& m,
                                      const ReportOptions& opt) {
  opt.validate();
  run.validate();
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the report directory: " + ec.message());
  std::vector<std::string> paths;
  auto write = [&](const char* name, auto&& body) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    std::ostringstream s;  // build first: a failing writer leaves no half file behind
    body(s);
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f << s.str();
    f.close();
    if (!f) throw std::runtime_error(path + ": cannot write");
    paths.push_back(path);
  };
  write("metrics.json", [&](std::ostream& s) { write_metrics_json(s, m, opt); });
  write("timeseries.csv", [&](std::ostream& s) { write_timeseries_csv(s, run); });
  write("trajectory.svg", [&](std::ostream& s) { write_trajectory_svg(s, run, m, opt); });
  write("dtc.svg", [&](std::ostream& s) { write_dtc_svg(s, run, m, opt); });
  return paths;
}

}  // namespace mpgc::scenario_runner
