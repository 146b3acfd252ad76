#include "mpgc/situational_awareness/dnv_situation.hpp"

#include <filesystem>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "mpgc/geo/geodesy.hpp"

namespace mpgc::sa {

namespace fs = std::filesystem;

namespace {
YAML::Node load(const std::string& path) {
  try {
    return YAML::LoadFile(path);  // JSON is YAML flow style
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot parse: " + e.what());
  }
}

double number(const YAML::Node& n, const std::string& path, const std::string& key) {
  if (!n || !n.IsScalar()) throw std::runtime_error(path + ": missing number " + key);
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const std::exception&) {
    throw std::runtime_error(path + ": " + key + " is not a number");
  }
  if (!std::isfinite(v)) throw std::runtime_error(path + ": " + key + " is not finite");
  return v;
}

DnvShip read_ship(const YAML::Node& s, const std::string& path, const std::string& key) {
  // Every lookup below is on const nodes: a missing key yields an invalid node, never an insert.
  if (!s || !s.IsMap()) throw std::runtime_error(path + ": missing object " + key);
  const YAML::Node init = s["initial"];
  if (!init || !init.IsMap()) throw std::runtime_error(path + ": missing object " + key + ".initial");
  const YAML::Node wps = s["waypoints"];
  // Position and speed: "initial" in the input schema, the first waypoint in the generated one.
  // (Nodes are bound once: yaml-cpp's Node::operator= assigns content, it does not rebind.)
  const bool in_initial = init["position"] && init["sog"];
  if (!in_initial && (!wps || !wps.IsSequence() || wps.size() == 0))
    throw std::runtime_error(path + ": " + key + " has neither initial.position/sog nor waypoints");
  const YAML::Node wp0 = in_initial ? YAML::Node() : wps[0];
  const YAML::Node leg = in_initial ? YAML::Node() : wp0["leg"];
  const YAML::Node pos = in_initial ? init["position"] : wp0["position"];
  const YAML::Node sog = in_initial ? init["sog"] : (leg ? leg["sog"] : YAML::Node());
  const std::string pos_key = key + (in_initial ? ".initial.position" : ".waypoints[0].position");
  const std::string sog_key = key + (in_initial ? ".initial.sog" : ".waypoints[0].leg.sog");
  if (!pos || !pos.IsMap()) throw std::runtime_error(path + ": missing object " + pos_key);
  DnvShip out;
  out.lat = geo::deg2rad(number(pos["lat"], path, pos_key + ".lat"));
  out.lon = geo::deg2rad(number(pos["lon"], path, pos_key + ".lon"));
  try {
    geo::check_latlon(out.lat, out.lon);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + pos_key + ": " + e.what());
  }
  out.sog = number(sog, path, sog_key) * geo::kKnot;
  if (out.sog < 0.0) throw std::runtime_error(path + ": " + sog_key + " is negative");
  out.heading = geo::wrap_pi(geo::deg2rad(number(init["heading"], path, key + ".initial.heading")));
  out.length = std::nan("");
  const YAML::Node st = s["static"];
  if (st && st.IsMap()) {
    const YAML::Node name = st["name"], dims = st["dimensions"];
    if (name && name.IsScalar()) out.name = name.as<std::string>();
    if (dims && dims.IsMap() && dims["length"])
      out.length = number(dims["length"], path, key + ".static.dimensions.length");
  }
  return out;
}
}  // namespace

DnvSituation read_dnv_situation(const std::string& path) {
  const YAML::Node root = load(path);
  if (!root.IsMap()) throw std::runtime_error(path + ": top level is not an object");
  DnvSituation s;
  s.path = path;
  if (root["title"] && root["title"].IsScalar()) s.title = root["title"].as<std::string>();
  s.own = read_ship(root["ownShip"], path, "ownShip");
  const YAML::Node ts = root["targetShips"];
  if (!ts || !ts.IsSequence()) throw std::runtime_error(path + ": missing list targetShips");
  if (ts.size() > 1000) throw std::runtime_error(path + ": more than 1000 targetShips");
  for (size_t i = 0; i < ts.size(); ++i)
    s.targets.push_back(read_ship(ts[i], path, "targetShips[" + std::to_string(i) + "]"));
  if (root["encounters"]) s.desired = read_dnv_desired(path);
  return s;
}

std::vector<std::string> read_dnv_desired(const std::string& path) {
  const YAML::Node root = load(path);
  const YAML::Node enc = root.IsMap() ? root["encounters"] : YAML::Node();
  if (!enc || !enc.IsSequence()) throw std::runtime_error(path + ": missing list encounters");
  std::vector<std::string> out;
  for (size_t i = 0; i < enc.size(); ++i) {
    const YAML::Node d = enc[i]["desiredEncounterType"];
    if (!d || !d.IsScalar())
      throw std::runtime_error(path + ": encounters[" + std::to_string(i) + "].desiredEncounterType missing");
    out.push_back(d.as<std::string>());
  }
  return out;
}

std::string find_dnv_input(const std::string& generated_path) {
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

std::vector<DnvTargetResult> assess_dnv(const DnvSituation& s, const colreg::ColregParams& p) {
  const geo::LocalNed ned({s.own.lat, s.own.lon});
  const auto own = colreg::ShipKinematics::from_course(0.0, 0.0, s.own.heading, s.own.sog, s.own.heading);
  std::vector<DnvTargetResult> out;
  for (const DnvShip& t : s.targets) {
    const geo::NorthEast ne = ned.to_ned({t.lat, t.lon});
    DnvTargetResult r;
    r.own = own;
    r.target = colreg::ShipKinematics::from_course(ne.x, ne.y, t.heading, t.sog, t.heading);
    r.assessment = colreg::assess(own, r.target, p);
    out.push_back(r);
  }
  return out;
}

colreg::EncounterType from_dnv_name(const std::string& n) {
  using colreg::EncounterType;
  if (n == "head-on") return EncounterType::kHeadOn;
  if (n == "crossing-give-way") return EncounterType::kCrossingGiveWay;
  if (n == "crossing-stand-on") return EncounterType::kCrossingStandOn;
  if (n == "overtaking-give-way") return EncounterType::kOvertaking;
  if (n == "overtaking-stand-on") return EncounterType::kOvertaken;
  return EncounterType::kNone;
}

}  // namespace mpgc::sa
