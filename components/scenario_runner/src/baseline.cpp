#include "mpgc/scenario_runner/baseline.hpp"

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "mpgc/json/json.hpp"

namespace mpgc::scenario_runner {

Baseline read_baseline(const std::string& path) {
  auto bad = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  std::ifstream in(path);
  if (!in) bad("cannot be read");
  json::Json j;
  try {
    j = json::Json::parse(in);
  } catch (const std::exception& e) {
    bad(std::string("not JSON: ") + e.what());
  }
  if (!j.is_object()) bad("must be an object with \"passing\" and \"failing\"");
  Baseline b;
  if (j.contains("passing")) {
    if (!j["passing"].is_array()) bad("\"passing\" must be an array of scenario names");
    for (const auto& n : j["passing"]) {
      if (!n.is_string()) bad("\"passing\" must be an array of scenario names");
      b.passing.insert(n.get<std::string>());
    }
  }
  if (j.contains("failing")) {
    if (!j["failing"].is_object()) bad("\"failing\" must map each scenario name to its failure kinds");
    for (const auto& [name, kinds] : j["failing"].items()) {
      if (!kinds.is_array() || kinds.empty()) bad("\"failing\"." + name + ": give its failure kinds as a list of text");
      for (const auto& k : kinds) {
        if (!k.is_string() || k.get<std::string>().empty()) bad("\"failing\"." + name + ": give its failure kinds as a list of text");
        b.failing[name].push_back(k.get<std::string>());
      }
      if (b.passing.count(name)) bad(name + " is listed as passing and as failing");
    }
  }
  for (const auto& [k, v] : j.items())
    if (k != "passing" && k != "failing" && k != "comment") bad("unknown key \"" + k + "\"");
  return b;
}

std::string failure_kind(const std::string& line) {
  static const std::regex quantity("-?[0-9]+(\\.[0-9]+)? (m|s|%)(?![A-Za-z_])");
  return std::regex_replace(line, quantity, "# $2");
}

Ratchet judge(const Baseline& b, const std::vector<Judged>& results) {
  Ratchet r;
  for (const auto& j : results) {
    const auto known = b.failing.find(j.name);
    if (j.result == Result::kError) {
      r.regressions.push_back(j.name + ": the run broke (an error, not a verdict)");
    } else if (known == b.failing.end()) {
      if (j.result == Result::kFailed)
        r.regressions.push_back(j.name + (b.passing.count(j.name) ? ": listed as passing, failed" : ": not in the baseline, failed"));
    } else if (j.result == Result::kPassed) {
      r.new_passes.push_back(j.name);
    } else {
      std::string kinds;
      for (const auto& k : known->second) kinds += (kinds.empty() ? "" : "; ") + k;
      r.known_failures.push_back(j.name + ": " + kinds);
      for (const auto& f : j.failures)
        if (std::find(known->second.begin(), known->second.end(), failure_kind(f)) == known->second.end())
          r.regressions.push_back(j.name + ": a failure not listed for it: " + f);
    }
  }
  return r;
}

std::string describe(const Ratchet& r, const std::string& path) {
  std::ostringstream s;
  for (const auto& k : r.known_failures) s << "known failure (" << path << "): " << k << "\n";
  for (const auto& n : r.new_passes) s << "now passes, listed as failing in " << path << ": " << n << " (move it to \"passing\")\n";
  for (const auto& g : r.regressions) s << "REGRESSION against " << path << ": " << g << "\n";
  return s.str();
}

}  // namespace mpgc::scenario_runner
