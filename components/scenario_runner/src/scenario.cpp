#include "mpgc/scenario_runner/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

// The five components of a run: those a scenario may set parameters of, or inject faults into.
const std::set<std::string>& run_components() {
  static const std::set<std::string> c{"ship_simulator", "situational_awareness", "obstacle_manager", "opp",
                                       "guidance_control"};
  return c;
}

std::vector<Fault> parse_faults(const std::string& origin, const YAML::Node& list, const YAML::Node& world) {
  if (!list.IsSequence()) fail(origin, list, "faults", "must be a list");
  std::set<std::uint32_t> mmsis;
  for (const auto& t : world["targets"]) if (t["mmsi"]) mmsis.insert(t["mmsi"].as<std::uint32_t>());
  std::vector<Fault> out;
  for (const auto& n : list) {
    only_keys(origin, n, "faults[]", {"at_s", "for_s", "kill", "stop", "silence", "ais_outage", "gnss_dropout", "position_jump_m"});
    Fault f;
    f.at_s = number(origin, n, "at_s", 0, 0, 1e7, true);
    int kinds = 0;
    const bool timed = n["for_s"].IsDefined();
    f.duration_s = number(origin, n, "for_s", 0, 0.001, 1e6);
    auto component = [&](const char* key) {
      f.component = text(origin, n, key, "");
      if (!run_components().count(f.component))
        fail(origin, n[key], std::string("faults[].") + key, "'" + f.component + "' is not one of the five components");
    };
    if (n["kill"]) f.kind = Fault::Kind::kKill, component("kill"), ++kinds;
    if (n["stop"]) f.kind = Fault::Kind::kStop, component("stop"), ++kinds;
    if (n["silence"]) {
      f.kind = Fault::Kind::kSilence, ++kinds;
      f.topic = text(origin, n, "silence", "");
      if (f.topic.empty()) fail(origin, n["silence"], "faults[].silence", "needs a topic name");
    }
    if (n["ais_outage"]) {
      f.kind = Fault::Kind::kAisOutage, ++kinds;
      f.mmsi = static_cast<std::uint32_t>(number(origin, n, "ais_outage", 0, 1, 999999999, true));
      if (!mmsis.count(f.mmsi)) fail(origin, n["ais_outage"], "faults[].ais_outage", "no target has MMSI " + std::to_string(f.mmsi));
    }
    if (n["gnss_dropout"]) f.kind = Fault::Kind::kGnssDropout, ++kinds;
    if (const YAML::Node j = n["position_jump_m"]) {
      f.kind = Fault::Kind::kPositionJump, ++kinds;
      if (!j.IsSequence() || j.size() != 2) fail(origin, j, "faults[].position_jump_m", "must be [north, east]");
      try {
        f.dx = j[0].as<double>(), f.dy = j[1].as<double>();
      } catch (const YAML::Exception&) {
        fail(origin, j, "faults[].position_jump_m", "must be two numbers");
      }
      if (!std::isfinite(f.dx) || !std::isfinite(f.dy) || std::hypot(f.dx, f.dy) > 1e5)
        fail(origin, j, "faults[].position_jump_m", "must be finite and within 100 km");
    }
    if (kinds != 1) fail(origin, n, "faults[]", "give exactly one of kill, stop, silence, ais_outage, gnss_dropout, position_jump_m");
    if (f.kind == Fault::Kind::kKill && timed) fail(origin, n["for_s"], "faults[].for_s", "a kill has no duration");
    if (f.kind != Fault::Kind::kKill && !timed) fail(origin, n, "faults[].for_s", "is required for this fault");
    out.push_back(f);
  }
  std::stable_sort(out.begin(), out.end(), [](const Fault& a, const Fault& b) { return a.at_s < b.at_s; });
  return out;
}

std::string expand_shared(std::string path) {
  const std::string var = "$MPGC_SHARED_DATA";
  const auto at = path.find(var);
  if (at == std::string::npos) return path;
  const char* d = std::getenv("MPGC_SHARED_DATA");
  if (d == nullptr) throw std::runtime_error("MPGC_SHARED_DATA is not set (./mpgc sets it)");
  return path.replace(at, var.size(), d);
}

PassCriteria parse_criteria(const std::string& origin, const YAML::Node& c) {
  only_keys(origin, c, "criteria",
            {"goal", "safety_tolerance", "max_safety_violation_s", "colreg_compliant", "min_ship_distance_m", "targets"});
  PassCriteria out;
  out.goal_required = boolean(origin, c, "goal", true);
  out.safety_tolerance = number(origin, c, "safety_tolerance", 0, 0, 1);
  out.max_safety_violation_s = number(origin, c, "max_safety_violation_s", 0, 0, 1e6);
  out.all_encounters_compliant = boolean(origin, c, "colreg_compliant", false);
  out.min_ship_distance = number(origin, c, "min_ship_distance_m", 0, 0, 1e6);
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
      out.required.push_back(r);
    }
  }
  return out;
}

void parse_params(const std::string& origin, const YAML::Node& p,
                  std::map<std::string, std::map<std::string, std::string>>* params) {
  only_keys(origin, p, "params", run_components());
  for (const auto& kv : p) {
    const std::string comp = kv.first.as<std::string>();
    if (!kv.second.IsMap()) fail(origin, kv.second, "params." + comp, "must be a mapping name: value");
    for (const auto& nv : kv.second) {
      if (!nv.second.IsScalar()) fail(origin, nv.second, "params." + comp + "." + nv.first.Scalar(), "must be a scalar");
      (*params)[comp][nv.first.as<std::string>()] = nv.second.Scalar();
    }
  }
}

// `from: FILE` with the file's own name, description, faults, criteria, time limit and parameters.
Scenario derived_scenario(const YAML::Node& root, const std::string& origin);

}  // namespace

const char* to_string(Fault::Kind k) {
  switch (k) {
    case Fault::Kind::kKill: return "kill";
    case Fault::Kind::kStop: return "stop";
    case Fault::Kind::kSilence: return "silence";
    case Fault::Kind::kAisOutage: return "ais_outage";
    case Fault::Kind::kGnssDropout: return "gnss_dropout";
    case Fault::Kind::kPositionJump: return "position_jump";
  }
  return "?";
}

std::string Fault::describe() const {
  char b[160];
  switch (kind) {
    case Kind::kKill: return "kill " + component;
    case Kind::kStop: std::snprintf(b, sizeof b, "stop %s for %.0f s", component.c_str(), duration_s); break;
    case Kind::kSilence: std::snprintf(b, sizeof b, "silence %s for %.0f s", topic.c_str(), duration_s); break;
    case Kind::kAisOutage: std::snprintf(b, sizeof b, "AIS outage of %u for %.0f s", mmsi, duration_s); break;
    case Kind::kGnssDropout: std::snprintf(b, sizeof b, "GNSS dropout for %.0f s", duration_s); break;
    case Kind::kPositionJump:
      std::snprintf(b, sizeof b, "position jump (%.0f, %.0f) m for %.0f s", dx, dy, duration_s);
      break;
  }
  return b;
}

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
  if (root.IsMap() && root["from"]) return derived_scenario(root, origin);
  only_keys(origin, root, "scenario",
            {"name", "description", "lpp_m", "plot_units", "world", "goal", "safety_distance_m",
             "safety_distance_lpp", "colreg", "obstacles", "time_limit_s", "evaluation", "criteria", "params",
             "faults"});
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

  if (const YAML::Node c = root["criteria"]) s.criteria = parse_criteria(origin, c);
  if (const YAML::Node p = root["params"]) parse_params(origin, p, &s.params);
  if (const YAML::Node f = root["faults"]) s.faults = parse_faults(origin, f, s.world);
  return s;
}

EvaluationParams evaluation_params(const Scenario& s, double own_length) {
  // scaled_to multiplies the 10 m craft's distances (r_min_cpa = 100 m) by own_length / reference.
  if (s.evaluation_min_cpa > 0.0) return EvaluationParams::scaled_to(own_length, 100.0 * own_length / s.evaluation_min_cpa);
  return EvaluationParams::scaled_to(own_length);
}

namespace {
Scenario derived_scenario(const YAML::Node& root, const std::string& origin) {
  only_keys(origin, root, "scenario", {"from", "name", "description", "time_limit_s", "criteria", "params", "faults"});
  std::string from;
  try {
    from = expand_shared(text(origin, root, "from", ""));
  } catch (const std::exception& e) {
    fail(origin, root["from"], "from", e.what());
  }
  const std::filesystem::path base_path =
      std::filesystem::path(from).is_absolute() ? std::filesystem::path(from) : std::filesystem::path(origin).parent_path() / from;
  if (!std::filesystem::exists(base_path)) fail(origin, root["from"], "from", "no such scenario file " + base_path.string());
  Scenario s = load_scenario(base_path.string());
  s.path = origin;
  s.name = text(origin, root, "name", "");
  if (s.name.empty()) fail(origin, root, "name", "is required");
  s.description = text(origin, root, "description", s.description);
  s.time_limit = number(origin, root, "time_limit_s", s.time_limit, 1.0, 1e6);
  if (const YAML::Node c = root["criteria"]) s.criteria = parse_criteria(origin, c);
  if (const YAML::Node p = root["params"]) parse_params(origin, p, &s.params);
  if (const YAML::Node f = root["faults"]) s.faults = parse_faults(origin, f, s.world);
  return s;
}
}  // namespace

Scenario load_scenario(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".json") return dnv_scenario(path);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read scenario '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scenario(ss.str(), path);
}

}  // namespace mpgc::scenario_runner
