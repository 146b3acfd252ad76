#include "mpgc/scenario_runner/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::scenario_runner {
namespace {

[[noreturn]] void fail(const std::string& origin, const YAML::Node& n, const std::string& key, const std::string& msg) {
  const int line = n.IsDefined() ? n.Mark().line + 1 : 0;
  throw std::runtime_error(origin + ":" + std::to_string(line) + ": " + key + ": " + msg);
}

// One mapping's keys checked against the allowed set.
void only_keys(const std::string& origin, const YAML::Node& map, const std::string& where,
               const std::set<std::string>& allowed) {
  if (!map.IsMap()) fail(origin, map, where, "must be a mapping");
  for (const auto& kv : map) {
    const auto k = kv.first.as<std::string>();
    if (allowed.count(k) == 0) fail(origin, kv.first, where + "." + k, "unknown key");
  }
}

double number(const std::string& origin, const YAML::Node& map, const std::string& key, double def, double lo,
              double hi, bool required = false) {
  const YAML::Node n = map[key];
  if (!n) {
    if (required) fail(origin, map, key, "is required");
    return def;
  }
  double v = 0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(origin, n, key, "'" + n.Scalar() + "' is not a number");
  }
  if (!std::isfinite(v) || v < lo || v > hi)
    fail(origin, n, key, std::to_string(v) + " is outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return v;
}

bool boolean(const std::string& origin, const YAML::Node& map, const std::string& key, bool def) {
  const YAML::Node n = map[key];
  if (!n) return def;
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(origin, n, key, "'" + n.Scalar() + "' is not true/false");
  }
}

std::string text(const std::string& origin, const YAML::Node& map, const std::string& key, const std::string& def) {
  const YAML::Node n = map[key];
  if (!n) return def;
  if (!n.IsScalar()) fail(origin, n, key, "must be a string");
  return n.Scalar();
}

colreg::EncounterType encounter_from(const std::string& origin, const YAML::Node& n) {
  const std::string s = n.Scalar();
  using E = colreg::EncounterType;
  for (E e : {E::kNone, E::kHeadOn, E::kCrossingGiveWay, E::kCrossingStandOn, E::kOvertaking, E::kOvertaken})
    if (s == colreg::to_string(e) || s == colreg::dnv_name(e)) return e;
  fail(origin, n, "situation", "unknown situation '" + s + "'");
}

}  // namespace

YAML::Node lpp_to_metres(const YAML::Node& n, double lpp) {
  if (n.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : n) {
      std::string k = kv.first.as<std::string>();
      const std::string suffix = "_lpp";
      if (k.size() > suffix.size() && k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0 &&
          kv.second.IsScalar()) {
        const std::string base = k.substr(0, k.size() - suffix.size());
        if (n[base + "_m"]) throw std::runtime_error("both " + k + " and " + base + "_m given");
        out[base + "_m"] = kv.second.as<double>() * lpp;
      } else {
        out[k] = lpp_to_metres(kv.second, lpp);
      }
    }
    return out;
  }
  if (n.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const auto& e : n) out.push_back(lpp_to_metres(e, lpp));
    return out;
  }
  return YAML::Clone(n);
}

std::string scale_shapes(const std::string& shapes, double scale) {
  std::ostringstream out;
  std::string token;
  std::istringstream in(shapes);
  bool first = true;
  while (in >> token) {
    bool semicolon = !token.empty() && token.back() == ';';
    if (semicolon) token.pop_back();
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    out << (first ? "" : " ");
    if (!token.empty() && end != nullptr && *end == '\0') {
      std::ostringstream num;
      num.precision(12);
      num << v * scale;
      out << num.str();
    } else {
      out << token;
    }
    if (semicolon) out << ";";
    first = false;
  }
  return out.str();
}

Scenario parse_scenario(const std::string& yaml, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(origin + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  only_keys(origin, root, "scenario",
            {"name", "description", "lpp_m", "plot_units", "world", "goal", "safety_distance_m",
             "safety_distance_lpp", "colreg", "obstacles", "time_limit_s", "evaluation", "criteria", "params"});
  Scenario s;
  s.path = origin;
  s.name = text(origin, root, "name", "");
  if (s.name.empty()) fail(origin, root, "name", "is required");
  s.description = text(origin, root, "description", "");
  s.lpp = number(origin, root, "lpp_m", 320.0, 1.0, 1000.0);
  const std::string units = text(origin, root, "plot_units", "lpp");
  if (units != "lpp" && units != "m") fail(origin, root["plot_units"], "plot_units", "must be lpp or m");
  s.plot_in_lpp = units == "lpp";

  if (!root["world"] || !root["world"].IsMap()) fail(origin, root, "world", "is required (ship_simulator world)");
  try {
    s.world = lpp_to_metres(root["world"], s.lpp);
  } catch (const std::exception& e) {
    fail(origin, root["world"], "world", e.what());
  }
  const YAML::Node o = s.world["origin"];
  if (!o) fail(origin, root["world"], "world.origin", "is required");
  s.origin_lat_deg = number(origin, o, "lat_deg", 0, -90, 90, true);
  s.origin_lon_deg = number(origin, o, "lon_deg", 0, -180, 180, true);

  YAML::Node g = root["goal"];
  if (!g) fail(origin, root, "goal", "is required");
  g = lpp_to_metres(g, s.lpp);
  only_keys(origin, root["goal"], "goal",
            {"x_m", "y_m", "x_lpp", "y_lpp", "arrival_radius_m", "arrival_radius_lpp", "heading_deg",
             "heading_tolerance_deg", "speed_kn"});
  s.goal.x = number(origin, g, "x_m", 0, -1e7, 1e7, true);
  s.goal.y = number(origin, g, "y_m", 0, -1e7, 1e7, true);
  s.goal.radius = number(origin, g, "arrival_radius_m", 2 * s.lpp, 1.0, 1e5);
  if (g["heading_deg"]) s.goal_heading = geo::deg2rad(number(origin, g, "heading_deg", 0, -360, 360));
  s.goal_heading_tolerance = geo::deg2rad(number(origin, g, "heading_tolerance_deg", 180, 0, 180));
  // The mission speed defaults to the own ship's start speed: planning at the current speed instead
  // would make every speed loss in a turn permanent (the planned speed is the guidance's set point).
  const YAML::Node own = s.world["own_ship"];
  const double start_kn = own && own["speed_kn"] ? number(origin, own, "speed_kn", 0, 0, 40) : 0.0;
  s.cruise_speed = number(origin, g, "speed_kn", start_kn, 0, 40) * geo::kKnot;

  if (root["safety_distance_m"] && root["safety_distance_lpp"])
    fail(origin, root, "safety_distance_m", "give safety_distance_m or safety_distance_lpp, not both");
  if (root["safety_distance_lpp"])
    s.safety_distance = s.lpp * number(origin, root, "safety_distance_lpp", 0, 0.01, 1000.0, true);
  else
    s.safety_distance = number(origin, root, "safety_distance_m", 0, 1.0, 1e5, true);
  s.colreg = boolean(origin, root, "colreg", true);
  s.time_limit = number(origin, root, "time_limit_s", 0, 1.0, 1e6, true);

  if (const YAML::Node ob = root["obstacles"]) {
    only_keys(origin, ob, "obstacles", {"shapes_m", "shapes_lpp", "files"});
    if (ob["shapes_m"] && ob["shapes_lpp"]) fail(origin, ob, "obstacles", "give shapes_m or shapes_lpp, not both");
    if (ob["shapes_m"]) s.chart_shapes = text(origin, ob, "shapes_m", "");
    if (ob["shapes_lpp"]) s.chart_shapes = scale_shapes(text(origin, ob, "shapes_lpp", ""), s.lpp);
    if (ob["files"]) {
      if (!ob["files"].IsSequence()) fail(origin, ob["files"], "obstacles.files", "must be a list");
      for (const auto& f : ob["files"]) s.chart_files.push_back(f.Scalar());
    }
  }

  if (const YAML::Node ev = root["evaluation"]) {
    only_keys(origin, ev, "evaluation", {"min_cpa_m", "min_cpa_lpp"});
    if (ev["min_cpa_m"] && ev["min_cpa_lpp"]) fail(origin, ev, "evaluation", "give min_cpa_m or min_cpa_lpp, not both");
    if (ev["min_cpa_lpp"]) s.evaluation_min_cpa = s.lpp * number(origin, ev, "min_cpa_lpp", 0, 0.01, 1000.0);
    if (ev["min_cpa_m"]) s.evaluation_min_cpa = number(origin, ev, "min_cpa_m", 0, 1.0, 1e5);
  }

  if (const YAML::Node c = root["criteria"]) {
    only_keys(origin, c, "criteria", {"goal", "safety_tolerance", "max_safety_violation_s", "colreg_compliant", "targets"});
    s.criteria.goal_required = boolean(origin, c, "goal", true);
    s.criteria.safety_tolerance = number(origin, c, "safety_tolerance", 0, 0, 1);
    s.criteria.max_safety_violation_s = number(origin, c, "max_safety_violation_s", 0, 0, 1e6);
    s.criteria.all_encounters_compliant = boolean(origin, c, "colreg_compliant", false);
    if (const YAML::Node ts = c["targets"]) {
      if (!ts.IsSequence()) fail(origin, ts, "criteria.targets", "must be a list");
      for (const auto& t : ts) {
        only_keys(origin, t, "criteria.targets[]", {"id", "situation", "compliant"});
        RequiredEncounter r;
        r.target_id = static_cast<std::uint32_t>(number(origin, t, "id", 0, 1, 1e6, true));
        if (t["situation"]) {
          r.situation = encounter_from(origin, t["situation"]);
          r.check_situation = true;
        }
        r.compliant = boolean(origin, t, "compliant", true);
        s.criteria.required.push_back(r);
      }
    }
  }

  if (const YAML::Node p = root["params"]) {
    static const std::set<std::string> components{"ship_simulator", "situational_awareness", "obstacle_manager", "opp",
                                                  "guidance_control"};
    only_keys(origin, p, "params", components);
    for (const auto& kv : p) {
      const std::string comp = kv.first.as<std::string>();
      if (!kv.second.IsMap()) fail(origin, kv.second, "params." + comp, "must be a mapping name: value");
      for (const auto& nv : kv.second) {
        if (!nv.second.IsScalar()) fail(origin, nv.second, "params." + comp + "." + nv.first.Scalar(), "must be a scalar");
        s.params[comp][nv.first.as<std::string>()] = nv.second.Scalar();
      }
    }
  }
  return s;
}

EvaluationParams evaluation_params(const Scenario& s, double own_length) {
  // scaled_to multiplies the 10 m craft's distances (r_min_cpa = 100 m) by own_length / reference.
  if (s.evaluation_min_cpa > 0.0) return EvaluationParams::scaled_to(own_length, 100.0 * own_length / s.evaluation_min_cpa);
  return EvaluationParams::scaled_to(own_length);
}

Scenario load_scenario(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".json") return dnv_scenario(path);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenario '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scenario(ss.str(), path);
}

}  // namespace mpgc::scenario_runner
