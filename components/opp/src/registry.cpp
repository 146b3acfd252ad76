#include "mpgc/opp/registry.hpp"

#include <functional>
#include <stdexcept>
#include <utility>

#include "mpgc/opp/apf_vo.hpp"
#include "mpgc/opp/dijkstra_sv.hpp"
#include "mpgc/opp/rrtstar.hpp"

namespace mpgc::opp {

namespace {
// Every planner, once: a new one is one line here (and its own files).
const std::vector<std::pair<std::string, std::function<std::unique_ptr<Planner>()>>>& table() {
  static const std::vector<std::pair<std::string, std::function<std::unique_ptr<Planner>()>>> t = {
      {"rrtstar", [] { return std::make_unique<RrtStar>(); }},
      {"apf-vo", [] { return std::make_unique<ApfVo>(); }},
      {"dijkstra-sv", [] { return std::make_unique<DijkstraSv>(); }},
  };
  return t;
}
}  // namespace

std::vector<std::string> planner_names() {
  std::vector<std::string> n;
  for (const auto& e : table()) n.push_back(e.first);
  return n;
}

std::unique_ptr<Planner> make_planner(const std::string& name) {
  for (const auto& e : table())
    if (e.first == name) return e.second();
  std::string known;
  for (const auto& e : table()) known += (known.empty() ? "" : ", ") + e.first;
  throw std::invalid_argument("unknown planner '" + name + "' (known: " + known + ")");
}

}  // namespace mpgc::opp
