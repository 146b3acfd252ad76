// DNV ship-traffic-generator situations as scenarios. The reading is common's DNV reader
// (mpgc/dnv/situation.hpp: one parser for mpgc_classify and the runner); this file only converts. The choices for
// what the JSON does not give are documented in scenarios/README.md ("DNV situations").
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/nomoto_model.hpp"

namespace mpgc::scenario_runner {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& field, const std::string& what) {
  throw std::runtime_error(file + ": " + field + ": " + what);
}

std::string num(double v) {
  std::ostringstream o;
  o.precision(10);
  o << v;
  return o.str();
}

// "dnv_07_HO_CR-GW" from traffic_situation_07.json titled "HO, CR-GW".
std::string name_of(const std::string& path, const std::string& title) {
  const std::string stem = std::filesystem::path(path).stem().string();
  const auto us = stem.rfind('_');
  std::string n = "dnv_" + (us == std::string::npos ? stem : stem.substr(us + 1));
  std::string t;
  for (char ch : title) {
    const bool keep = std::isalnum(static_cast<unsigned char>(ch)) || ch == '-';
    if (keep) t += ch;
    else if (!t.empty() && t.back() != '_') t += '_';
  }
  while (!t.empty() && t.back() == '_') t.pop_back();
  return t.empty() ? n : n + "_" + t;
}

}  // namespace

Scenario dnv_scenario(const dnv::Situation& d, const std::vector<std::string>& desired, const DnvChoices& c) {
  const std::string& f = d.path;
  const dnv::Ship& own = d.own;
  if (own.waypoints.size() < 2) fail(f, "ownShip.waypoints", "needs at least 2 waypoints (start and goal)");
  if (!std::isfinite(own.length)) fail(f, "ownShip.static.dimensions.length", "missing (it sets the own ship's model)");
  if (own.length < 10.0 || own.length > 500.0) fail(f, "ownShip.static.dimensions.length", "must be in [10, 500] m");
  if (!(own.sog > 0.1)) fail(f, "ownShip.waypoints[0].leg.sog", "must be > 0 (the own ship's speed)");
  if (own.sog > 30.0 * geo::kKnot) fail(f, "ownShip.waypoints[0].leg.sog", "must be <= 30 kn");

  Scenario s;
  s.path = f;
  s.name = name_of(f, d.title);
  s.lpp = own.length;
  s.plot_in_lpp = true;
  s.origin_lat_deg = geo::rad2deg(own.waypoints[0].lat);
  s.origin_lon_deg = geo::rad2deg(own.waypoints[0].lon);
  const geo::LocalNed ned({own.waypoints[0].lat, own.waypoints[0].lon});

  // The own ship: a Nomoto hull of the own ship's size (Mariner K', T'), on its first waypoint.
  YAML::Node world(YAML::NodeType::Map);
  world["origin"]["lat_deg"] = s.origin_lat_deg;
  world["origin"]["lon_deg"] = s.origin_lon_deg;
  world["seed"] = 1;
  YAML::Node os(YAML::NodeType::Map);
  os["model"] = "nomoto";
  os["nomoto_ship"] = "Mariner";
  os["length_m"] = own.length;
  if (std::isfinite(own.width) && own.width >= 1.0 && own.width <= 100.0) os["beam_m"] = own.width;
  os["x_m"] = 0.0;
  os["y_m"] = 0.0;
  os["heading_deg"] = geo::rad2deg(own.heading);
  os["speed_kn"] = own.sog / geo::kKnot;
  if (own.mmsi >= 100000000u) os["mmsi"] = own.mmsi;
  world["own_ship"] = os;

  // Targets follow their waypoints at the legs' SOG; the speed towards waypoint i is the SOG of
  // the leg that starts at waypoint i - 1.
  double nearest = std::numeric_limits<double>::infinity();
  std::set<std::uint32_t> mmsis{own.mmsi};
  YAML::Node targets(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < d.targets.size(); ++i) {
    const dnv::Ship& t = d.targets[i];
    const std::string key = "targetShips[" + std::to_string(i) + "]";
    if (t.sog > 50.0 * geo::kKnot) fail(f, key + ".waypoints[0].leg.sog", "must be <= 50 kn");
    YAML::Node y(YAML::NodeType::Map);
    std::uint32_t mmsi = t.mmsi;
    if (mmsi < 100000000u || mmsis.count(mmsi)) mmsi = 257990001u + static_cast<std::uint32_t>(i);
    mmsis.insert(mmsi);
    y["mmsi"] = mmsi;
    y["name"] = t.name.empty() ? "target_ship_" + std::to_string(i + 1) : t.name;
    y["lat_deg"] = geo::rad2deg(t.lat);
    y["lon_deg"] = geo::rad2deg(t.lon);
    y["course_deg"] = geo::rad2deg(t.heading);
    y["speed_kn"] = t.sog / geo::kKnot;
    if (std::isfinite(t.length)) {
      if (t.length > 500.0) fail(f, key + ".static.dimensions.length", "must be <= 500 m");
      y["length_m"] = t.length;
    }
    if (std::isfinite(t.width)) {
      if (t.width > 100.0) fail(f, key + ".static.dimensions.width", "must be <= 100 m");
      y["beam_m"] = std::max(1.0, t.width);
    }
    double speed = t.sog;
    YAML::Node wps(YAML::NodeType::Sequence);
    for (std::size_t k = 1; k < t.waypoints.size(); ++k) {
      if (std::isfinite(t.waypoints[k - 1].sog)) speed = t.waypoints[k - 1].sog;
      if (speed > 50.0 * geo::kKnot)
        fail(f, key + ".waypoints[" + std::to_string(k - 1) + "].leg.sog", "must be <= 50 kn");
      YAML::Node w(YAML::NodeType::Map);
      w["lat_deg"] = geo::rad2deg(t.waypoints[k].lat);
      w["lon_deg"] = geo::rad2deg(t.waypoints[k].lon);
      w["speed_kn"] = speed / geo::kKnot;
      wps.push_back(w);
    }
    if (wps.size() > 0) y["waypoints"] = wps;
    targets.push_back(y);
    const geo::NorthEast p = ned.to_ned({t.lat, t.lon});
    nearest = std::min(nearest, std::hypot(p.x, p.y));
  }
  if (targets.size() > 0) world["targets"] = targets;
  s.world = world;

  // Goal: the last waypoint, at the own ship's SOG; the time limit from the route length.
  const geo::NorthEast g = ned.to_ned({own.waypoints.back().lat, own.waypoints.back().lon});
  double route = 0.0;
  geo::NorthEast prev{0.0, 0.0};
  for (std::size_t k = 1; k < own.waypoints.size(); ++k) {
    const geo::NorthEast p = ned.to_ned({own.waypoints[k].lat, own.waypoints[k].lon});
    route += std::hypot(p.x - prev.x, p.y - prev.y);
    prev = p;
  }
  s.goal.x = g.x;
  s.goal.y = g.y;
  s.goal.radius = c.arrival_lengths * own.length;
  if (std::hypot(g.x, g.y) <= s.goal.radius) fail(f, "ownShip.waypoints", "the last waypoint is within the arrival radius of the first");
  s.cruise_speed = own.sog;
  s.time_limit = std::ceil(route / own.sog * c.time_factor / 100.0) * 100.0;

  // Safety: 0.5 NM unless a target starts so close that it cannot be kept.
  s.safety_distance = std::min(c.safety_distance, c.min_range_share * nearest);
  if (!(s.safety_distance >= 1.0)) fail(f, "targetShips", "a target starts on the own ship");
  // Rule 13's "keep clear" (r_min_cpa) at the lower edge of what the safety criterion accepts:
  // with r_min_cpa = d_safety an overtaking passed at 0.998 d_safety failed COLREG while it met
  // the safety criterion, whose tolerance is there for the same tracking errors.
  s.evaluation_min_cpa = (1.0 - c.safety_tolerance) * s.safety_distance;
  s.colreg = true;

  // Heading controller by pole placement on the own hull's Nomoto K, T at its speed (the
  // simulator's scaling of the same table row), LOS distances in ship lengths.
  ship_simulator::NomotoParams np;
  const std::string table = ship_simulator::default_ship_data_dir() + "/nomoto_kt.csv";
  try {
    np = ship_simulator::load_nomoto_csv(table, "Mariner", own.sog);
  } catch (const std::exception& e) {
    throw std::runtime_error(f + ": converting needs the Nomoto table (set MPGC_SHARED_DATA): " + e.what());
  }
  const double K = np.K_ref * np.L_ref / np.U_ref * own.sog / own.length;
  const double T = np.T_ref * np.U_ref / np.L_ref * own.length / own.sog;
  auto& gc = s.params["guidance_control"];
  gc["heading.nomoto_K"] = num(K);
  gc["heading.nomoto_T"] = num(T);
  gc["heading.omega_n"] = "0.05";
  gc["heading.zeta"] = "0.9";
  gc["heading.integral_ratio"] = "10";
  gc["los.lookahead"] = num(c.lookahead_lengths * own.length);
  gc["los.acceptance_radius"] = num(c.lookahead_lengths * own.length);
  s.params["opp"]["plan.colreg_distance"] = num(std::max(c.colreg_distance, s.safety_distance));

  // Pass: the goal, d_safety within the tolerance, and a compliant COLREG verdict for every target
  // with a desired encounter type (the evaluator classifies the situation itself).
  s.criteria.goal_required = true;
  s.criteria.safety_tolerance = c.safety_tolerance;
  s.criteria.max_safety_violation_s = c.max_safety_violation_s;
  std::string wanted;
  for (std::size_t i = 0; i < d.targets.size() && i < desired.size(); ++i) {
    if (desired[i].empty()) continue;
    if (dnv::encounter_type(desired[i]) == colreg::EncounterType::kNone)
      fail(f, "targetShips[" + std::to_string(i) + "]", "desiredEncounterType '" + desired[i] + "' is not a DNV encounter type");
    RequiredEncounter r;
    r.target_id = static_cast<std::uint32_t>(i + 1);
    r.compliant = true;
    s.criteria.required.push_back(r);
    wanted += (wanted.empty() ? "" : ", ") + std::to_string(i + 1) + " " + desired[i];
  }
  s.description = "DNV situation \"" + d.title + "\"" + (wanted.empty() ? "" : " (desired: " + wanted + ")");
  return s;
}

Scenario dnv_scenario(const std::string& path, const DnvChoices& choices) {
  dnv::Situation d = dnv::read_situation(path);
  std::vector<std::string> desired = d.desired;
  if (desired.empty()) {
    const std::string in = dnv::find_input(path);
    if (!in.empty()) desired = dnv::read_desired(in);
  }
  return dnv_scenario(d, desired, choices);
}

}  // namespace mpgc::scenario_runner
