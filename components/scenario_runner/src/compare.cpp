#include "mpgc/scenario_runner/compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include "mpgc/json/json.hpp"

namespace mpgc::scenario_runner {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A number of metrics.json: null (a value that does not exist) is NaN.
double value(const json::Json& j, const char* key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return kNaN;
  return j[key].get<double>();
}

double median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double extreme(const std::vector<double>& v, bool lowest) {
  double r = kNaN;
  for (double x : v)
    if (std::isfinite(x) && (!std::isfinite(r) || (lowest ? x < r : x > r))) r = x;
  return r;
}

std::string fmt(const char* f, double v) {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

template <typename... A>
std::string format(const char* f, A... a) {
  char b[512];
  std::snprintf(b, sizeof b, f, a...);
  return b;
}

std::string cell(const ScenarioFigures& s) {
  if (!s.ran) return "ERROR";
  return std::string(s.passed ? "pass" : "FAIL") + " " + fmt("%.2f", s.min_distance / s.safety_distance);
}

}  // namespace

ScenarioFigures read_figures(const std::string& path, const std::string& scenario) {
  ScenarioFigures f;
  f.scenario = scenario;
  std::ifstream in(path);
  if (!in) {
    f.error = "no metrics.json (the run broke; see its components.log): " + path;
    return f;
  }
  json::Json j;
  try {
    j = json::Json::parse(in);
    f.passed = j.at("passed").get<bool>();
    for (const auto& x : j.value("failures", json::Json::array())) f.failures.push_back(x.get<std::string>());
    if (j.contains("likely_collisions")) f.collisions = j["likely_collisions"].value("count", 0);
    f.min_distance = j.contains("min_distance_m") ? value(j["min_distance_m"], "overall") : kNaN;
    f.safety_distance = value(j, "safety_distance_m");
    f.path_length = value(j, "path_length_m");
    f.straight_line = value(j, "straight_line_m");
    f.plan_median_ms = j.contains("planning_ms") ? value(j["planning_ms"], "median") : kNaN;
    f.plan_p95_ms = j.contains("planning_ms") ? value(j["planning_ms"], "p95") : kNaN;
    for (const auto& e : j.value("encounters", json::Json::array())) {
      if (!e.value("encountered", false) || e.value("situation", std::string("none")) == "none") continue;
      ++f.encounters;
      f.compliant += e.value("compliant", false) ? 1 : 0;
    }
  } catch (const std::exception& e) {
    ScenarioFigures bad;
    bad.scenario = scenario;
    bad.error = path + ": not a metrics.json (" + e.what() + ")";
    return bad;
  }
  f.ran = true;
  return f;
}

std::vector<ScenarioFigures> read_results(const std::string& dir, const std::vector<std::string>& scenarios) {
  std::vector<ScenarioFigures> r;
  for (const auto& s : scenarios)
    r.push_back(read_figures((std::filesystem::path(dir) / s / "metrics.json").string(), s));
  return r;
}

PlannerSummary summarize(const PlannerResults& r) {
  PlannerSummary p;
  p.planner = r.planner;
  std::vector<double> ratio, elongation, plan_median, plan_p95;
  for (const ScenarioFigures& s : r.scenarios) {
    ++p.total;
    if (!s.ran) {
      ++p.errors;
      continue;
    }
    p.passed += s.passed ? 1 : 0;
    p.collisions += s.collisions;
    ratio.push_back(s.safety_distance > 0 ? s.min_distance / s.safety_distance : kNaN);
    elongation.push_back(s.straight_line > 0 ? s.path_length / s.straight_line : kNaN);
    plan_median.push_back(s.plan_median_ms);
    plan_p95.push_back(s.plan_p95_ms);
    if (s.colreg) {
      p.encounters += s.encounters;
      p.compliant += s.compliant;
    }
  }
  p.min_dist_ratio_worst = extreme(ratio, true);
  p.min_dist_ratio_median = median(ratio);
  p.elongation_median = median(elongation);
  p.colreg_compliant_share = p.encounters > 0 ? static_cast<double>(p.compliant) / p.encounters : kNaN;
  p.plan_ms_median = median(plan_median);
  p.plan_ms_p95 = extreme(plan_p95, false);
  return p;
}

std::string compare_table(const std::vector<PlannerResults>& results) {
  std::string t = format("%-10s %7s %6s %10s %13s %13s %10s %14s %10s %10s\n", "planner", "passed", "errors",
                         "collisions", "d_min/d_safe", "d_min/d_safe", "elongation", "COLREG", "plan_ms", "plan_ms");
  t += format("%-10s %7s %6s %10s %13s %13s %10s %14s %10s %10s\n", "", "", "", "", "worst", "median", "median",
              "compliant", "median", "p95 worst");
  for (const PlannerResults& r : results) {
    const PlannerSummary p = summarize(r);
    const std::string colreg =
        p.encounters > 0 ? format("%d/%d %.2f", p.compliant, p.encounters, p.colreg_compliant_share) : "-";
    t += format("%-10s %7s %6d %10d %13s %13s %10s %14s %10s %10s\n", p.planner.c_str(),
                format("%d/%d", p.passed, p.total).c_str(), p.errors, p.collisions,
                fmt("%.2f", p.min_dist_ratio_worst).c_str(), fmt("%.2f", p.min_dist_ratio_median).c_str(),
                fmt("%.3f", p.elongation_median).c_str(), colreg.c_str(), fmt("%.3g", p.plan_ms_median).c_str(),
                fmt("%.3g", p.plan_ms_p95).c_str());
  }
  t += "(d_min/d_safe: each scenario's min distance / d_safety; elongation: path_length_m / straight_line_m;\n"
       " COLREG: compliant encounters / encounters met, in the scenarios that require COLREG;\n"
       " plan_ms: median of the runs' medians, p95 worst = the highest of the runs' p95;\n"
       " all over the scenarios with a metrics.json; errors count as not passed)\n";

  // Every scenario, one column per planner: its verdict and d_min/d_safe.
  std::vector<std::string> names;
  std::map<std::string, std::map<std::string, const ScenarioFigures*>> by;
  for (const PlannerResults& r : results)
    for (const ScenarioFigures& s : r.scenarios) {
      if (!by.count(s.scenario)) names.push_back(s.scenario);
      by[s.scenario][r.planner] = &s;
    }
  t += format("\n%-30s", "scenario");
  for (const PlannerResults& r : results) t += format(" %-12s", r.planner.c_str());
  t += "\n";
  for (const auto& n : names) {
    t += format("%-30s", n.c_str());
    for (const PlannerResults& r : results) {
      const auto it = by[n].find(r.planner);
      t += format(" %-12s", it == by[n].end() ? "(not run)" : cell(*it->second).c_str());
    }
    t += "\n";
  }

  // What each planner did not pass, and why.
  for (const PlannerResults& r : results)
    for (const ScenarioFigures& s : r.scenarios) {
      if (s.ran && s.passed) continue;
      t += format("%s %s: %s\n", r.planner.c_str(), s.scenario.c_str(), s.ran ? "FAIL" : "ERROR");
      if (!s.ran) t += "    why: " + s.error + "\n";
      for (const auto& f : s.failures) t += "    why: " + f + "\n";
    }
  return t;
}

std::string compare_json(const std::vector<PlannerResults>& results) {
  using json::number;
  json::Json planners = json::Json::object();
  for (const PlannerResults& r : results) {
    const PlannerSummary p = summarize(r);
    planners[p.planner] = {{"passed", p.passed},
                           {"total", p.total},
                           {"collisions", p.collisions},
                           {"min_dist_ratio_worst", number(p.min_dist_ratio_worst)},
                           {"elongation_median", number(p.elongation_median)},
                           {"colreg_compliant_share", number(p.colreg_compliant_share)},
                           {"plan_ms_median", number(p.plan_ms_median)},
                           {"plan_ms_p95", number(p.plan_ms_p95)}};
  }
  return json::Json{{"planners", planners}}.dump();
}

std::string compare_text(const std::vector<PlannerResults>& results) {
  return compare_table(results) + "\n" + compare_json(results) + "\n";
}

}  // namespace mpgc::scenario_runner
