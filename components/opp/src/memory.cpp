#include "mpgc/opp/memory.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mpgc::opp {

std::string to_yaml(const PlannerMemory& m) {
  YAML::Emitter e;
  e.SetDoublePrecision(17);
  e << YAML::BeginMap << YAML::Key << "goal_id" << YAML::Value << m.goal_id << YAML::Key << "plan_id" << YAML::Value
    << m.plan_id << YAML::Key << "warm_goal" << YAML::Value << m.warm_goal;
  e << YAML::Key << "last_path" << YAML::Value << YAML::BeginSeq;
  for (const auto& p : m.last_path) e << YAML::Flow << YAML::BeginSeq << p.x << p.y << YAML::EndSeq;
  e << YAML::EndSeq << YAML::Key << "pinned" << YAML::Value << YAML::BeginSeq;
  for (const auto& r : m.pinned)
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "id" << YAML::Value << r.id << YAML::Key << "obligation"
      << YAML::Value << static_cast<int>(r.e.obligation) << YAML::Key << "course0" << YAML::Value << r.e.course0
      << YAML::Key << "track_side" << YAML::Value << r.e.track_side << YAML::Key << "target_course" << YAML::Value
      << r.e.target_course << YAML::Key << "range0" << YAML::Value << r.range0 << YAML::EndMap;
  e << YAML::EndSeq << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

PlannerMemory memory_from_yaml(const std::string& text, const std::string& origin) {
  PlannerMemory m;
  try {
    const YAML::Node n = YAML::Load(text);
    if (!n.IsMap()) throw std::invalid_argument("not a map");
    m.goal_id = n["goal_id"].as<uint32_t>();
    m.plan_id = n["plan_id"].as<uint32_t>();
    m.warm_goal = n["warm_goal"].as<uint32_t>();
    for (const auto& p : n["last_path"]) {
      if (!p.IsSequence() || p.size() != 2) throw std::invalid_argument("last_path: a point is not [x, y]");
      const Vec2 v{p[0].as<double>(), p[1].as<double>()};
      if (!std::isfinite(v.x) || !std::isfinite(v.y)) throw std::invalid_argument("last_path: a non-finite point");
      m.last_path.push_back(v);
    }
    for (const auto& r : n["pinned"]) {
      PinnedRecord rec;
      rec.id = r["id"].as<uint32_t>();
      const int o = r["obligation"].as<int>();
      if (o < 0 || o > static_cast<int>(Obligation::kOvertaken) || !pinnable(static_cast<Obligation>(o)))
        throw std::invalid_argument("pinned: unknown obligation " + std::to_string(o) + " (colreg::EncounterType: 1, 2 or 4)");
      rec.e.obligation = static_cast<Obligation>(o);
      rec.e.course0 = r["course0"].as<double>();
      rec.e.track_side = r["track_side"].as<int>();
      rec.e.target_course = r["target_course"].as<double>();
      rec.range0 = r["range0"].as<double>();
      m.pinned.push_back(rec);
    }
    EncounterMemory check;
    check.restore(m.pinned);  // the same validation a restore gets
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(origin + ": planner memory: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(origin + ": planner memory: " + e.what());
  }
  return m;
}

void save_memory(const std::string& path, const PlannerMemory& m) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::trunc);
    f << to_yaml(m);
    if (!f) throw std::runtime_error("planner memory " + tmp + ": cannot write");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("planner memory " + path + ": cannot rename");
}

std::optional<PlannerMemory> load_memory(const std::string& path) {
  std::ifstream f(path);
  if (!f) return std::nullopt;
  std::stringstream ss;
  ss << f.rdbuf();
  return memory_from_yaml(ss.str(), path);
}

}  // namespace mpgc::opp
