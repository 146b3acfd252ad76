#include "mpgc/dnv/situation.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <tuple>

#include <yaml-cpp/yaml.h>

#include "mpgc/geo/geodesy.hpp"

namespace mpgc::dnv {

namespace fs = std::filesystem;

namespace {
YAML::Node load(const std::string& path) {
  try {
    return YAML::LoadFile(path);  // JSON is YAML flow style
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot parse: " + e.what());
  }
}

[[noreturn]] void fail(const std::string& path, const std::string& key, const std::string& what) {
  throw std::runtime_error(path + ": " + key + ": " + what);
}

double number(const YAML::Node& n, const std::string& path, const std::string& key) {
  if (!n) fail(path, key, "missing (a number is required)");
  if (!n.IsScalar()) fail(path, key, "is not a number");
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const std::exception&) {
    fail(path, key, "'" + n.Scalar() + "' is not a number");
  }
  if (!std::isfinite(v)) fail(path, key, "is not finite");
  return v;
}

// Latitude/longitude [deg] of a position object, checked, in radians.
std::pair<double, double> latlon(const YAML::Node& pos, const std::string& path, const std::string& key) {
  if (!pos) fail(path, key, "missing (an object with lat and lon is required)");
  if (!pos.IsMap()) fail(path, key, "is not an object");
  const double lat = geo::deg2rad(number(pos["lat"], path, key + ".lat"));
  const double lon = geo::deg2rad(number(pos["lon"], path, key + ".lon"));
  try {
    geo::check_latlon(lat, lon);
  } catch (const std::invalid_argument& e) {
    fail(path, key, e.what());
  }
  return {lat, lon};
}

double speed(const YAML::Node& n, const std::string& path, const std::string& key) {
  const double v = number(n, path, key);
  if (v < 0.0) fail(path, key, "is negative");
  return v * geo::kKnot;
}

Ship read_ship(const YAML::Node& s, const std::string& path, const std::string& key) {
  // Every lookup below is on const nodes: a missing key yields an invalid node, never an insert.
  if (!s) fail(path, key, "missing (an object is required)");
  if (!s.IsMap()) fail(path, key, "is not an object");
  const YAML::Node init = s["initial"];
  if (!init) fail(path, key + ".initial", "missing (an object is required)");
  if (!init.IsMap()) fail(path, key + ".initial", "is not an object");
  const YAML::Node wps = s["waypoints"];
  if (wps && !wps.IsSequence()) fail(path, key + ".waypoints", "is not a list");
  Ship out;
  // The route (generated schema): every waypoint needs a position; leg.sog is optional after the first.
  if (wps) {
    if (wps.size() > 10000) fail(path, key + ".waypoints", "has more than 10000 entries");
    for (std::size_t i = 0; i < wps.size(); ++i) {
      const std::string wk = key + ".waypoints[" + std::to_string(i) + "]";
      const YAML::Node w = wps[i];
      if (!w.IsMap()) fail(path, wk, "is not an object");
      Waypoint p;
      std::tie(p.lat, p.lon) = latlon(w["position"], path, wk + ".position");
      const YAML::Node leg = w["leg"];
      if (leg && !leg.IsMap()) fail(path, wk + ".leg", "is not an object");
      p.sog = leg && leg["sog"] ? speed(leg["sog"], path, wk + ".leg.sog") : std::nan("");
      out.waypoints.push_back(p);
    }
  }
  // Position and speed: "initial" in the input schema, the first waypoint in the generated one.
  if (init["position"] && init["sog"]) {
    std::tie(out.lat, out.lon) = latlon(init["position"], path, key + ".initial.position");
    out.sog = speed(init["sog"], path, key + ".initial.sog");
  } else {
    if (out.waypoints.empty()) fail(path, key, "has neither initial.position/sog nor waypoints");
    out.lat = out.waypoints[0].lat;
    out.lon = out.waypoints[0].lon;
    out.sog = speed(wps[0]["leg"] ? wps[0]["leg"]["sog"] : YAML::Node(), path, key + ".waypoints[0].leg.sog");
  }
  out.heading = geo::wrap_pi(geo::deg2rad(number(init["heading"], path, key + ".initial.heading")));
  out.length = std::nan("");
  out.width = std::nan("");
  const YAML::Node st = s["static"];
  if (st && !st.IsMap()) fail(path, key + ".static", "is not an object");
  if (st) {
    const YAML::Node name = st["name"], dims = st["dimensions"], mmsi = st["mmsi"];
    if (name && name.IsScalar()) out.name = name.as<std::string>();
    if (mmsi) {
      const double m = number(mmsi, path, key + ".static.mmsi");
      if (m < 0 || m > 999999999 || m != std::floor(m)) fail(path, key + ".static.mmsi", "is not an MMSI (0..999999999)");
      out.mmsi = static_cast<std::uint32_t>(m);
    }
    if (dims && !dims.IsMap()) fail(path, key + ".static.dimensions", "is not an object");
    auto dim = [&](const char* k, double* v) {
      if (!dims || !dims[k]) return;
      *v = number(dims[k], path, key + ".static.dimensions." + k);
      if (!(*v > 0.0)) fail(path, key + ".static.dimensions." + k, "must be > 0");
    };
    dim("length", &out.length);
    dim("width", &out.width);
  }
  return out;
}
}  // namespace

Situation read_situation(const std::string& path) {
  const YAML::Node root = load(path);
  if (!root.IsMap()) fail(path, "top level", "is not an object");
  Situation s;
  s.path = path;
  if (root["title"] && root["title"].IsScalar()) s.title = root["title"].as<std::string>();
  s.own = read_ship(root["ownShip"], path, "ownShip");
  const YAML::Node ts = root["targetShips"];
  if (!ts) fail(path, "targetShips", "missing (a list is required)");
  if (!ts.IsSequence()) fail(path, "targetShips", "is not a list");
  if (ts.size() > 1000) fail(path, "targetShips", "has more than 1000 entries");
  for (size_t i = 0; i < ts.size(); ++i)
    s.targets.push_back(read_ship(ts[i], path, "targetShips[" + std::to_string(i) + "]"));
  if (root["encounters"]) s.desired = read_desired(path);
  return s;
}

std::vector<std::string> read_desired(const std::string& path) {
  const YAML::Node root = load(path);
  const YAML::Node enc = root.IsMap() ? root["encounters"] : YAML::Node();
  if (!enc || !enc.IsSequence()) fail(path, "encounters", "missing (a list is required)");
  std::vector<std::string> out;
  for (size_t i = 0; i < enc.size(); ++i) {
    const YAML::Node e = enc[i];
    const YAML::Node d = e.IsMap() ? e["desiredEncounterType"] : YAML::Node();
    if (!d || !d.IsScalar()) fail(path, "encounters[" + std::to_string(i) + "].desiredEncounterType", "missing");
    out.push_back(d.as<std::string>());
  }
  return out;
}

std::string find_input(const std::string& generated_path) {
  const fs::path g(generated_path);
  const std::string stem = g.stem().string();  // traffic_situation_NN
  const auto us = stem.rfind('_');
  if (us == std::string::npos) return {};
  const std::string nn = stem.substr(us + 1);
  const fs::path dir = g.parent_path().parent_path() / "baseline_situations_input";
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return {};
  const std::string prefix = "baseline_situation_" + nn + "_";
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) == 0 && e.path().extension() == ".json") return e.path().string();
  }
  return {};
}

std::vector<TargetResult> assess(const Situation& s, const colreg::ColregParams& p) {
  const geo::LocalNed ned({s.own.lat, s.own.lon});
  const auto own = colreg::ShipKinematics::from_course(0.0, 0.0, s.own.heading, s.own.sog, s.own.heading);
  std::vector<TargetResult> out;
  for (const Ship& t : s.targets) {
    const geo::NorthEast ne = ned.to_ned({t.lat, t.lon});
    TargetResult r;
    r.own = own;
    r.target = colreg::ShipKinematics::from_course(ne.x, ne.y, t.heading, t.sog, t.heading);
    r.assessment = colreg::assess(own, r.target, p);
    out.push_back(r);
  }
  return out;
}

colreg::EncounterType encounter_type(const std::string& n) {
  using colreg::EncounterType;
  // The inverse of colreg::dnv_name, so that the DNV names are written once.
  for (const EncounterType t : {EncounterType::kHeadOn, EncounterType::kCrossingGiveWay, EncounterType::kCrossingStandOn,
                                EncounterType::kOvertaking, EncounterType::kOvertaken})
    if (n == colreg::dnv_name(t)) return t;
  return EncounterType::kNone;
}

}  // namespace mpgc::dnv
