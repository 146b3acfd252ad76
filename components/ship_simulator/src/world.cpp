#include "mpgc/ship_simulator/world.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_simulator {
namespace {

class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A YAML mapping with a dotted path for error messages; rejects keys nobody asked for.
struct Map {
  YAML::Node node;
  std::string path;
  std::string origin;

  Map(YAML::Node n, std::string p, std::string o) : node(std::move(n)), path(std::move(p)), origin(std::move(o)) {
    if (node && !node.IsNull() && !node.IsMap()) fail(path.empty() ? "top level" : path, "must be a mapping");
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw WorldError(origin + ": " + key + " " + what);
  }
  std::string name(const std::string& k) const { return path.empty() ? k : path + "." + k; }
  bool has(const std::string& k) const { return node && node.IsMap() && node[k]; }
  void allow(std::initializer_list<const char*> keys) const {
    if (!node || !node.IsMap()) return;
    std::set<std::string> ok(keys.begin(), keys.end());
    for (const auto& kv : node) {
      const std::string k = kv.first.as<std::string>();
      if (!ok.count(k)) fail(name(k), "is not a known key");
    }
  }
  double num(const std::string& k, double def, double lo, double hi) const {
    if (!has(k)) return def;
    double v = 0.0;
    try {
      v = node[k].as<double>();
    } catch (const YAML::Exception&) {
      fail(name(k), "is not a number");
    }
    if (!std::isfinite(v) || v < lo || v > hi) {
      std::ostringstream o;
      o << "= " << v << " is outside [" << lo << ", " << hi << "]";
      fail(name(k), o.str());
    }
    return v;
  }
  double req(const std::string& k, double lo, double hi) const {
    if (!has(k)) fail(name(k), "is required");
    return num(k, 0.0, lo, hi);
  }
  std::string str(const std::string& k, const std::string& def) const {
    if (!has(k)) return def;
    try {
      return node[k].as<std::string>();
    } catch (const YAML::Exception&) {
      fail(name(k), "is not a string");
    }
  }
  uint64_t seed(const std::string& k, uint64_t def) const {
    if (!has(k)) return def;
    try {
      return node[k].as<uint64_t>();
    } catch (const YAML::Exception&) {
      fail(name(k), "is not a non-negative integer");
    }
  }
  Map sub(const std::string& k) const { return Map(has(k) ? node[k] : YAML::Node(), name(k), origin); }
  std::vector<Map> list(const std::string& k, std::size_t max_n) const {
    std::vector<Map> out;
    if (!has(k)) return out;
    const YAML::Node l = node[k];
    if (!l.IsSequence()) fail(name(k), "must be a list");
    if (l.size() > max_n) fail(name(k), "has more than " + std::to_string(max_n) + " entries");
    for (std::size_t i = 0; i < l.size(); ++i) out.emplace_back(l[i], name(k) + "[" + std::to_string(i) + "]", origin);
    return out;
  }
};

constexpr double kMaxCoord = 1.0e7;  // [m]

// Position from x_m/y_m or lat_deg/lon_deg (not both).
geo::NorthEast position(const Map& m, const geo::LocalNed& frame, bool required) {
  const bool xy = m.has("x_m") || m.has("y_m"), ll = m.has("lat_deg") || m.has("lon_deg");
  if (xy && ll) m.fail(m.path, "gives both x_m/y_m and lat_deg/lon_deg");
  if (ll) {
    const double lat = m.req("lat_deg", -90.0, 90.0), lon = m.req("lon_deg", -180.0, 180.0);
    return frame.to_ned({geo::deg2rad(lat), geo::deg2rad(lon)});
  }
  if (required && !xy) m.fail(m.path, "needs x_m/y_m or lat_deg/lon_deg");
  return {m.num("x_m", 0.0, -kMaxCoord, kMaxCoord), m.num("y_m", 0.0, -kMaxCoord, kMaxCoord)};
}

}  // namespace

WorldConfig WorldConfig::from_yaml(const std::string& text, const std::string& origin) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(origin + ": malformed YAML: " + e.what());
  }
  WorldConfig c;
  const Map top(root, "", origin);
  top.allow({"origin", "seed", "own_ship", "environment", "targets", "sensors"});
  const Map o = top.sub("origin");
  o.allow({"lat_deg", "lon_deg"});
  c.origin = {geo::deg2rad(o.req("lat_deg", -89.0, 89.0)), geo::deg2rad(o.req("lon_deg", -180.0, 180.0))};
  const geo::LocalNed frame(c.origin);
  c.seed = top.seed("seed", 1);

  const Map own = top.sub("own_ship");
  own.allow({"model", "nomoto_ship", "data_dir", "length_m", "beam_m", "x_m", "y_m", "lat_deg", "lon_deg", "heading_deg",
             "speed_kn", "rpm", "mmsi"});
  c.model.kind = own.str("model", "mmg");
  if (c.model.kind != "mmg" && c.model.kind != "nomoto") own.fail("own_ship.model", "must be mmg or nomoto");
  c.model.nomoto_ship = own.str("nomoto_ship", "Mariner");
  c.model.data_dir = own.str("data_dir", "");
  if (c.model.kind != "nomoto" && (own.has("length_m") || own.has("beam_m")))
    own.fail("own_ship.length_m", "is for model nomoto only (mmg is the KVLCC2 at full scale)");
  c.model.length = own.num("length_m", 0.0, 10.0, 500.0);
  c.model.beam = own.num("beam_m", 0.0, 1.0, 100.0);
  const auto p = position(own, frame, false);
  c.own_start.x = p.x;
  c.own_start.y = p.y;
  c.own_start.psi = geo::wrap_pi(geo::deg2rad(own.num("heading_deg", 0.0, -360.0, 360.0)));
  c.own_start.u = own.num("speed_kn", 0.0, 0.0, 30.0) * geo::kKnot;
  c.own_rpm = own.num("rpm", -1.0, -1.0, 1000.0);
  c.own_mmsi = static_cast<uint32_t>(own.num("mmsi", 0.0, 0.0, 999999999.0));

  const Map env = top.sub("environment");
  env.allow({"current_north_mps", "current_east_mps", "wind_speed_mps", "wind_from_deg"});
  c.environment.current_north = env.num("current_north_mps", 0.0, -10.0, 10.0);
  c.environment.current_east = env.num("current_east_mps", 0.0, -10.0, 10.0);
  c.environment.wind_speed = env.num("wind_speed_mps", 0.0, 0.0, 70.0);
  c.environment.wind_from = geo::deg2rad(env.num("wind_from_deg", 0.0, -360.0, 360.0));

  std::set<uint32_t> mmsis;
  for (const Map& t : top.list("targets", 1000)) {
    t.allow({"mmsi", "name", "x_m", "y_m", "lat_deg", "lon_deg", "course_deg", "speed_kn", "length_m", "beam_m",
             "nav_status", "max_turn_rate_deg_s", "max_accel_mps2", "waypoint_radius_m", "legs", "waypoints",
             "manoeuvres", "behaviour", "helmsman"});
    TargetConfig tc;
    tc.mmsi = static_cast<uint32_t>(t.req("mmsi", 100000000.0, 999999999.0));
    if (!mmsis.insert(tc.mmsi).second) t.fail(t.name("mmsi"), "duplicates another target's MMSI");
    tc.name = t.str("name", "mmsi" + std::to_string(tc.mmsi));
    const auto tp = position(t, frame, true);
    tc.x0 = tp.x;
    tc.y0 = tp.y;
    tc.course0 = geo::wrap_pi(geo::deg2rad(t.num("course_deg", 0.0, -360.0, 360.0)));
    tc.speed0 = t.num("speed_kn", 0.0, 0.0, 50.0) * geo::kKnot;
    tc.length = t.num("length_m", 100.0, 1.0, 500.0);
    tc.beam = t.num("beam_m", 20.0, 1.0, 100.0);
    tc.nav_status = static_cast<uint8_t>(t.num("nav_status", 0.0, 0.0, 15.0));
    tc.max_turn_rate = geo::deg2rad(t.num("max_turn_rate_deg_s", 0.5, 0.01, 10.0));
    tc.max_accel = t.num("max_accel_mps2", 0.05, 0.001, 5.0);
    tc.waypoint_radius = t.num("waypoint_radius_m", 200.0, 1.0, 10000.0);
    // behaviour: route (default, the scripted mover) | colreg (a rule-following helmsman).
    const std::string behaviour = t.str("behaviour", "route");
    if (behaviour == "colreg") tc.behaviour = TargetBehaviour::kColreg;
    else if (behaviour != "route") t.fail(t.name("behaviour"), "= '" + behaviour + "' must be route or colreg");
    if (t.has("helmsman")) {
      if (tc.behaviour != TargetBehaviour::kColreg) t.fail(t.name("helmsman"), "is for behaviour: colreg only");
      // Wide bounds here (finite numbers); HelmsmanParams::validate() holds the real limits.
      const Map h = t.sub("helmsman");
      h.allow({"d_colreg_m", "cpa_risk_m", "tcpa_max_s", "alteration_deg", "max_alteration_deg",
               "alteration_step_deg", "act_alone", "act_alone_range_m", "act_alone_cpa_m"});
      HelmsmanParams& hp = tc.helmsman;
      hp.d_colreg = h.num("d_colreg_m", hp.d_colreg, 0.0, kMaxCoord);
      hp.cpa_risk = h.num("cpa_risk_m", hp.cpa_risk, 0.0, kMaxCoord);
      hp.tcpa_max = h.num("tcpa_max_s", hp.tcpa_max, 0.0, 1e7);
      hp.alteration = geo::deg2rad(h.num("alteration_deg", geo::rad2deg(hp.alteration), 0.0, 360.0));
      hp.max_alteration = geo::deg2rad(h.num("max_alteration_deg", geo::rad2deg(hp.max_alteration), 0.0, 360.0));
      hp.alteration_step = geo::deg2rad(h.num("alteration_step_deg", geo::rad2deg(hp.alteration_step), 0.0, 360.0));
      if (h.has("act_alone")) {
        try {
          hp.act_alone = h.node["act_alone"].as<bool>();
        } catch (const YAML::Exception&) {
          h.fail(h.name("act_alone"), "is not true or false");
        }
      }
      hp.act_alone_range = h.num("act_alone_range_m", hp.act_alone_range, 0.0, kMaxCoord);
      hp.act_alone_cpa = h.num("act_alone_cpa_m", hp.act_alone_cpa, 0.0, kMaxCoord);
    }
    for (const Map& l : t.list("legs", 10000)) {
      l.allow({"course_deg", "speed_kn", "duration_s"});
      tc.legs.push_back({geo::wrap_pi(geo::deg2rad(l.req("course_deg", -360.0, 360.0))),
                         l.req("speed_kn", 0.0, 50.0) * geo::kKnot, l.num("duration_s", 0.0, 0.0, 1e7)});
    }
    for (const Map& w : t.list("waypoints", 10000)) {
      w.allow({"x_m", "y_m", "lat_deg", "lon_deg", "speed_kn"});
      const auto wp = position(w, frame, true);
      tc.waypoints.push_back({wp.x, wp.y, w.req("speed_kn", 0.0, 50.0) * geo::kKnot});
    }
    for (const Map& m : t.list("manoeuvres", 10000)) {
      m.allow({"at_s", "course_deg", "speed_kn", "duration_s"});
      ScriptedManoeuvre sm;
      sm.at = m.req("at_s", 0.0, 1e7);
      sm.course = geo::wrap_pi(geo::deg2rad(m.req("course_deg", -360.0, 360.0)));
      sm.speed = m.has("speed_kn") ? m.num("speed_kn", 0.0, 0.0, 50.0) * geo::kKnot : -1.0;
      sm.duration = m.num("duration_s", 0.0, 0.0, 1e7);
      tc.manoeuvres.push_back(sm);
    }
    try {
      tc.validate();
    } catch (const std::invalid_argument& e) {
      t.fail(t.path, e.what());
    }
    c.targets.push_back(std::move(tc));
  }

  const Map s = top.sub("sensors");
  s.allow({"nav", "ais", "radar"});
  const Map n = s.sub("nav");
  n.allow({"period_s", "sigma_position_m", "sigma_heading_deg", "sigma_sog_mps", "sigma_cog_deg", "sigma_rot_deg_s", "seed"});
  c.nav.period = n.num("period_s", c.nav.period, 0.01, 60.0);
  c.nav.sigma_position = n.num("sigma_position_m", c.nav.sigma_position, 0.0, 1000.0);
  c.nav.sigma_heading = geo::deg2rad(n.num("sigma_heading_deg", geo::rad2deg(c.nav.sigma_heading), 0.0, 45.0));
  c.nav.sigma_sog = n.num("sigma_sog_mps", c.nav.sigma_sog, 0.0, 10.0);
  c.nav.sigma_cog = geo::deg2rad(n.num("sigma_cog_deg", geo::rad2deg(c.nav.sigma_cog), 0.0, 45.0));
  c.nav.sigma_rot = geo::deg2rad(n.num("sigma_rot_deg_s", geo::rad2deg(c.nav.sigma_rot), 0.0, 5.0));
  c.nav.seed = n.seed("seed", c.seed * 1000003ULL + 1);
  const Map a = s.sub("ais");
  a.allow({"sigma_position_m", "sigma_sog_mps", "sigma_cog_deg", "drop_probability", "turning_threshold_deg_min", "seed"});
  c.ais.sigma_position = a.num("sigma_position_m", c.ais.sigma_position, 0.0, 1000.0);
  c.ais.sigma_sog = a.num("sigma_sog_mps", c.ais.sigma_sog, 0.0, 10.0);
  c.ais.sigma_cog = geo::deg2rad(a.num("sigma_cog_deg", geo::rad2deg(c.ais.sigma_cog), 0.0, 45.0));
  c.ais.drop_probability = a.num("drop_probability", c.ais.drop_probability, 0.0, 1.0);
  c.ais.turning_threshold = geo::deg2rad(a.num("turning_threshold_deg_min", 3.0, 0.0, 300.0)) / 60.0;
  c.ais.seed = a.seed("seed", c.seed * 1000003ULL + 2);
  const Map r = s.sub("radar");
  r.allow({"period_s", "max_range_m", "min_range_m", "sigma_range_m", "sigma_bearing_deg", "detection_probability",
           "clutter_per_scan", "antenna_x_m", "seed"});
  c.radar.period = r.num("period_s", c.radar.period, 0.1, 60.0);
  c.radar.max_range = r.num("max_range_m", c.radar.max_range, 100.0, 200000.0);
  c.radar.min_range = r.num("min_range_m", c.radar.min_range, 0.0, c.radar.max_range);
  c.radar.sigma_range = r.num("sigma_range_m", c.radar.sigma_range, 0.0, 1000.0);
  c.radar.sigma_bearing = geo::deg2rad(r.num("sigma_bearing_deg", geo::rad2deg(c.radar.sigma_bearing), 0.0, 20.0));
  c.radar.detection_probability = r.num("detection_probability", c.radar.detection_probability, 0.0, 1.0);
  c.radar.clutter_per_scan = r.num("clutter_per_scan", c.radar.clutter_per_scan, 0.0, 100.0);
  c.radar_antenna_x = r.num("antenna_x_m", 0.0, -500.0, 500.0);
  c.radar.seed = r.seed("seed", c.seed * 1000003ULL + 3);
  return c;
}

const TargetConfig& WorldConfig::target(uint32_t mmsi) const {
  for (const auto& t : targets)
    if (t.mmsi == mmsi) return t;
  throw std::out_of_range("no target with MMSI " + std::to_string(mmsi));
}

WorldConfig WorldConfig::from_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open world file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return from_yaml(ss.str(), path);
}

World::World(WorldConfig cfg, int64_t step_ns)
    : cfg_(std::move(cfg)), step_ns_(step_ns), frame_(cfg_.origin), nav_(cfg_.nav), radar_(cfg_.radar) {
  if (step_ns_ <= 0 || step_ns_ > 10'000'000'000LL) throw std::invalid_argument("world step must be in (0, 10] s");
  own_ = make_model(cfg_.model);
  own_->set_environment(cfg_.environment);
  ShipState s = cfg_.own_start;
  s.rpm = cfg_.own_rpm >= 0.0 ? cfg_.own_rpm : (s.u > 0.0 ? straight_rpm(*own_, s.u) : 0.0);
  if (s.rpm > own_->max_rpm()) throw std::invalid_argument("own_ship.rpm is above the model's maximum");
  own_->set_state(s);
  for (std::size_t i = 0; i < cfg_.targets.size(); ++i) {
    targets_.emplace_back(cfg_.targets[i]);
    any_colreg_ = any_colreg_ || cfg_.targets[i].behaviour == TargetBehaviour::kColreg;
    ais_.emplace_back(cfg_.targets[i].mmsi, cfg_.targets[i].nav_status, cfg_.ais, i + 1);
  }
}

void World::step(const ShipCommand& cmd) {
  const double dt = static_cast<double>(step_ns_) * 1e-9;
  const double t = static_cast<double>(time_ns()) * 1e-9;
  // What the rule-following targets see: every ship at t, before anyone moves (so the order of
  // the targets does not matter). Built only when some target has a helmsman.
  std::vector<SeenShip> seen;
  if (any_colreg_) {
    const Kinematics o = own_kinematics();
    seen.push_back({0, colreg::ShipKinematics::from_course(o.x, o.y, o.cog, o.sog, o.heading)});
    for (const auto& tg : targets_)
      seen.push_back({tg.config().mmsi, colreg::ShipKinematics::from_course(tg.state().x, tg.state().y, tg.state().course,
                                                                            tg.state().speed, tg.state().course)});
  }
  own_->step(dt, cmd);
  std::vector<SeenShip> others;
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    if (targets_[i].config().behaviour != TargetBehaviour::kColreg) {
      targets_[i].step(t, dt);
      continue;
    }
    others.clear();
    for (std::size_t j = 0; j < seen.size(); ++j)
      if (j != i + 1) others.push_back(seen[j]);  // seen[0] is the own ship
    targets_[i].step(t, dt, others);
  }
  ++step_;
}

Kinematics World::own_kinematics() const {
  const ShipState& s = own_->state();
  const auto& e = cfg_.environment;
  const double c = std::cos(s.psi), sn = std::sin(s.psi);
  const double vn = s.u * c - s.v * sn + e.current_north, ve = s.u * sn + s.v * c + e.current_east;
  return {s.x, s.y, geo::wrap_pi(s.psi), geo::course_of(vn, ve), std::hypot(vn, ve), s.r};
}

TruthShip World::own_truth() const {
  const ShipState& s = own_->state();
  const Kinematics k = own_kinematics();
  return {0, cfg_.own_mmsi, s.x, s.y, k.heading, k.cog, k.sog, s.u, s.v, s.r, own_->length(), own_->beam()};
}

std::vector<TruthShip> World::target_truth() const {
  std::vector<TruthShip> out;
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const auto& s = targets_[i].state();
    const auto& c = targets_[i].config();
    out.push_back({static_cast<uint32_t>(i + 1), c.mmsi, s.x, s.y, s.course, s.course, s.speed, s.speed, 0.0, s.rot,
                   c.length, c.beam});
  }
  return out;
}

SensorOutputs World::sense() {
  SensorOutputs out;
  const int64_t t = time_ns();
  if (t >= next_nav_ns_) {
    out.nav = nav_.measure(own_kinematics());
    next_nav_ns_ += static_cast<int64_t>(std::llround(cfg_.nav.period * 1e9));
  }
  for (std::size_t i = 0; i < targets_.size(); ++i) {
    const auto& s = targets_[i].state();
    AisMeasurement m{};
    if (ais_[i].poll(t, Kinematics{s.x, s.y, s.course, s.course, s.speed, s.rot}, &m)) out.ais.push_back(m);
  }
  if (t >= next_radar_ns_) {
    const ShipState& o = own_->state();
    const double ax = o.x + cfg_.radar_antenna_x * std::cos(o.psi), ay = o.y + cfg_.radar_antenna_x * std::sin(o.psi);
    std::vector<Kinematics> tk;
    for (const auto& tg : targets_) tk.push_back({tg.state().x, tg.state().y, tg.state().course, tg.state().course,
                                                   tg.state().speed, tg.state().rot});
    out.radar = RadarScanOut{ax, ay, cfg_.radar.max_range, radar_.sweep(ax, ay, tk)};
    next_radar_ns_ += static_cast<int64_t>(std::llround(cfg_.radar.period * 1e9));
  }
  return out;
}

}  // namespace mpgc::ship_simulator
