// The ratchet of the closed-loop suites (scenarios/baseline.json, issue 17): which scenarios are
// known to pass and which are known to fail, each with the kinds of its failures (the evaluation's
// failure lines with their measured quantities as '#'). A run judged against it fails when a
// scenario listed as passing (or not listed at all) does not pass, when a known failure fails in
// a way not listed for it, or when a run broke (an error, not a verdict); a known failure is
// reported, never hidden; one that now passes is reported too, so that the file is tightened.
// No DDS, no clock.
//
//   const auto b = scenario_runner::read_baseline("scenarios/baseline.json");
//   const auto r = scenario_runner::judge(b, {{"paper_s1_colreg", Result::kPassed, {}}, ...});
//   std::cout << describe(r, path);  return r.ok() ? 0 : 1;
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mpgc::scenario_runner {

struct Baseline {
  std::set<std::string> passing;               // scenario names that must pass
  std::map<std::string, std::vector<std::string>> failing;  // known failures: name -> failure kinds
};

// Throws std::runtime_error naming the file and what is wrong (not JSON, a field of the wrong
// type, a name listed both ways).
Baseline read_baseline(const std::string& path);

enum class Result { kPassed, kFailed, kError };  // kError: the run broke (no verdict)

struct Judged {
  std::string name;
  Result result = Result::kFailed;
  std::vector<std::string> failures;  // the evaluation's failure lines (Metrics::failures)
};

// A failure line's kind: every measured quantity (a number followed by m, s or %) becomes '#', so
// "min distance 863.1 m < 879.7 m" is "min distance # m < # m"; ids and rule numbers stay.
std::string failure_kind(const std::string& line);

struct Ratchet {
  std::vector<std::string> regressions;     // "name: why": listed passing (or unlisted) and not passed, a
                                            //   failure of a kind not listed, or a broken run
  std::vector<std::string> known_failures;  // "name: kind; kind" as listed
  std::vector<std::string> new_passes;      // listed failing and passed
  bool ok() const { return regressions.empty(); }
};

Ratchet judge(const Baseline& b, const std::vector<Judged>& results);
// Lines for the run's summary (empty when there is nothing to say).
std::string describe(const Ratchet& r, const std::string& baseline_path);

}  // namespace mpgc::scenario_runner
