#include "mpgc/scenario_runner/report.hpp"

#include <algorithm>
#include <map>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "mpgc/json/json.hpp"

namespace mpgc::scenario_runner {

namespace {

// CSV number: the shortest text that reads back to the same double ("null" when not finite).
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  for (int prec = 6; prec <= 17; ++prec) {
    std::snprintf(buf, sizeof buf, "%.*g", prec, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

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
  using json::Json;
  using json::number;
  auto deg = [](double rad) { return number(rad * 180.0 / geo::kPi); };
  Json j;
  j["scenario"] = opt.scenario;
  j["passed"] = m.passed;
  j["failures"] = m.failures;
  j["goal_reached"] = m.goal_reached;
  j["time_to_goal_s"] = number(m.t_goal);
  Json targets = Json::object();
  for (const TargetDistance& d : m.min_distance_targets) targets[std::to_string(d.target_id)] = number(d.min_distance);
  j["min_distance_m"] = {{"overall", number(m.min_distance)}, {"fixed", number(m.min_distance_fixed)}, {"targets", targets}};
  j["safety_distance_m"] = number(m.safety_distance);
  j["safety_violation_s"] = number(m.safety_violation_s);
  const auto near = m.near_miss_targets(), collisions = m.likely_collision_targets();
  j["near_misses"] = {{"r_nm_m", number(m.r_nm)}, {"count", near.size()}, {"targets", near}};
  j["likely_collisions"] = {{"r_col_cpa_m", number(m.r_col_cpa)}, {"count", collisions.size()}, {"targets", collisions}};
  j["path_length_m"] = number(m.path_length);
  j["straight_line_m"] = number(m.straight_line);
  j["planning_ms"] = {{"median", number(m.planning.median_ms)}, {"p95", number(m.planning.p95_ms)},
                      {"max", number(m.planning.max_ms)}};
  j["replans"] = m.replans;
  j["relaxed_plans"] = m.relaxed_plans;
  j["no_path_plans"] = m.no_path_plans;
  j["tracking_rmse_m"] = number(m.tracking_rmse);
  j["wall_s"] = number(m.wall_s);
  j["sim_s"] = number(m.sim_s);
  Json comps = Json::object();
  for (const ComponentUsage& c : m.components)
    comps[c.name] = {{"peak_rss_mb", number(c.peak_rss_mb)}, {"cpu_s", number(c.cpu_s)}};
  j["components"] = comps;
  j["evaluation_scale"] = number(m.scale);
  Json encounters = Json::array();
  for (const EncounterResult& e : m.encounters) {
    encounters.push_back({{"target_id", e.target_id},
                          {"encountered", e.encountered},
                          {"situation", colreg::to_string(e.situation)},
                          {"role", to_string(e.role)},
                          {"t_start_s", number(e.t_start)},
                          {"range_start_m", number(e.range_start)},
                          {"beta_start_deg", deg(e.beta_start)},
                          {"alpha_start_deg", deg(e.alpha_start)},
                          {"dcpa_start_m", number(e.dcpa_start)},
                          {"tcpa_start_s", number(e.tcpa_start)},
                          {"cpa_m", number(e.cpa)},
                          {"t_cpa_s", number(e.t_cpa)},
                          {"passing_side", to_string(e.passing_side)},
                          {"bow_crossing_m", number(e.bow_crossing)},
                          {"manoeuvres", e.manoeuvres},
                          {"t_manoeuvre_s", number(e.t_manoeuvre)},
                          {"manoeuvre_side", to_string(e.manoeuvre_side)},
                          {"max_starboard_change_deg", deg(e.max_starboard_change)},
                          {"max_port_change_deg", deg(e.max_port_change)},
                          {"max_speed_reduction", number(e.max_speed_reduction)},
                          {"verdicts",
                           {{"turned_starboard", to_string(e.turned_starboard)},
                            {"passed_port_to_port", to_string(e.passed_port_to_port)},
                            {"not_crossed_ahead", to_string(e.not_crossed_ahead)},
                            {"kept_clear", to_string(e.kept_clear)},
                            {"held_course_and_speed", to_string(e.held_course_and_speed)},
                            {"not_turned_to_port", to_string(e.not_turned_to_port)},
                            {"readily_apparent", to_string(e.readily_apparent)}}},  // rule 8(b)
                          {"t_hold_end_s", number(e.t_hold_end)},
                          {"conflicting_obligation", e.conflicting_obligation},
                          {"compliant", e.compliant}});
  }
  j["encounters"] = std::move(encounters);
  // Faults and recoveries: each fault, then per component how often it was killed and came back.
  Json faults = Json::array();
  std::map<std::string, std::pair<int, int>> per_component;  // killed or stopped, recovered
  for (const FaultRecord& f : m.faults) {
    faults.push_back({{"what", f.what},
                      {"component", f.component},
                      {"planned_s", number(f.t_planned)},
                      {"t_s", number(f.t)},
                      {"end_s", number(f.t_end)},
                      {"recovered_s", number(f.t_recovered)},
                      {"recovery_s", number(f.needs_recovery ? f.t_recovered - f.t : kNaN)},
                      {"recovery_wall_s", number(f.wall_recovery)}});
    if (f.needs_recovery) {
      auto& pc = per_component[f.component];
      ++pc.first;
      pc.second += std::isfinite(f.t_recovered) ? 1 : 0;
    }
  }
  j["faults"] = std::move(faults);
  Json recoveries = Json::object();
  for (const auto& [c, n] : per_component) recoveries[c] = {{"faulted", n.first}, {"recovered", n.second}};
  j["recoveries"] = std::move(recoveries);
  o << j.dump(2) << "\n";
}

std::string close_calls_text(const Metrics& m) {
  auto f1 = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return std::string(b);
  };
  std::string near, collisions;
  int n_near = 0, n_col = 0;
  for (const TargetDistance& td : m.min_distance_targets) {
    const std::string id = "target " + std::to_string(td.target_id);
    if (td.near_miss) near += (n_near++ ? ", " : "") + id + " at " + f1(td.min_distance) + " m";
    if (td.likely_collision) collisions += (n_col++ ? ", " : "") + id;
  }
  if (n_near == 0 && n_col == 0) return "";
  std::string s = "near misses " + std::to_string(n_near) + " (" + near + "; r_nm " + f1(m.r_nm) + " m)";
  if (n_col > 0) s += ", likely collisions " + std::to_string(n_col) + " (" + collisions + "; r_col_cpa " + f1(m.r_col_cpa) + " m)";
  return s;
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

std::vector<ComponentUsage> component_usage(const std::string& launcher_log) {
  std::vector<ComponentUsage> out;
  std::istringstream in(launcher_log);
  const std::string tag = "[launch] ";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(tag, 0) != 0) continue;
    const auto open = line.rfind(" (peak RSS ");
    if (open == std::string::npos) continue;
    const auto sp = line.find(' ', tag.size());
    if (sp == std::string::npos || sp >= open) continue;
    const std::string name = line.substr(tag.size(), sp - tag.size());
    double rss = 0, cpu = 0;
    if (std::sscanf(line.c_str() + open, " (peak RSS %lf MB, CPU %lf s)", &rss, &cpu) != 2 || !std::isfinite(rss) ||
        !std::isfinite(cpu) || rss < 0 || cpu < 0)
      continue;
    auto it = std::find_if(out.begin(), out.end(), [&](const ComponentUsage& c) { return c.name == name; });
    if (it == out.end()) {
      out.push_back({name, rss, cpu});
    } else {
      it->peak_rss_mb = std::max(it->peak_rss_mb, rss);
      it->cpu_s += cpu;
    }
  }
  return out;
}

}  // namespace mpgc::scenario_runner
