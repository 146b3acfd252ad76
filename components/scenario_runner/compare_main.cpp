// mpgc_compare (./mpgc compare): the planners side by side. Sails the same scenarios once per
// planner with mpgc_run --planner NAME --out DIR/NAME (one after the other: the runs are lockstep
// and compete for the cores), then prints one table (a row per planner, every scenario a planner
// did not pass named under it) and a last line of JSON, from each run's metrics.json
// (mpgc/scenario_runner/compare.hpp). mpgc_run's own summary goes to DIR/NAME/run.log.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "mpgc/opp/registry.hpp"
#include "mpgc/runtime/process.hpp"
#include "mpgc/scenario_runner/compare.hpp"
#include "mpgc/scenario_runner/runner.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace fs = std::filesystem;
namespace sr = mpgc::scenario_runner;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> r;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, ',');)
    if (!x.empty()) r.push_back(x);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc_compare: the planners side by side on the same scenarios"};
  std::vector<std::string> files;
  std::string suites, planners_arg = "rrtstar,apf-vo,dijkstra-sv", out = "out/compare";
  bool no_run = false;
  app.add_option("scenarios", files, "scenario files (scenarios/*.yaml, or DNV traffic-generator situations *.json)");
  app.add_option("--suite", suites, "suites, comma-separated (paper, chart, faults, rules, dnv, all)");
  app.add_option("--planners", planners_arg, "planners, comma-separated (default rrtstar,apf-vo,dijkstra-sv)");
  app.add_option("--out", out, "output folder: DIR/<planner>/<scenario>/ (default out/compare)");
  app.add_flag("--no-run", no_run, "sail nothing: the table of the metrics.json already in DIR/<planner>/");
  CLI11_PARSE(app, argc, argv);

  const auto planners = split(planners_arg);
  const auto known = mpgc::opp::planner_names();
  if (planners.empty()) {
    std::cerr << "mpgc_compare: --planners is empty\n";
    return 2;
  }
  for (const auto& p : planners)
    if (std::find(known.begin(), known.end(), p) == known.end()) {
      std::cerr << "mpgc_compare: unknown planner " << p << " (known:";
      for (const auto& k : known) std::cerr << " " << k;
      std::cerr << ")\n";
      return 2;
    }

  const char* src = std::getenv("MPGC_SOURCE_DIR");
  const fs::path scen_dir = fs::path(src != nullptr ? src : ".") / "scenarios";
  const char* shared = std::getenv("MPGC_SHARED_DATA");
  const fs::path data_dir = shared != nullptr ? fs::path(shared) : scen_dir.parent_path() / ".." / "shared" / "data";
  std::vector<std::string> paths, names;
  std::vector<bool> colreg;
  try {
    std::vector<std::string> all = suites.empty() ? sr::scenario_files(files, "", scen_dir.string(), data_dir.string())
                                                  : files;
    for (const auto& s : split(suites)) {
      const auto f = sr::scenario_files({}, s, scen_dir.string(), data_dir.string());
      all.insert(all.end(), f.begin(), f.end());
    }
    for (const auto& f : all) {
      const std::string p = fs::absolute(f).string();
      if (std::find(paths.begin(), paths.end(), p) != paths.end()) continue;
      paths.push_back(p);
      const sr::Scenario sc = sr::load_scenario(p);
      names.push_back(sc.name);
      colreg.push_back(sc.colreg);
    }
  } catch (const std::exception& e) {
    std::cerr << "mpgc_compare: " << e.what() << "\n";
    return 2;
  }

  const std::string run_exe = (fs::canonical("/proc/self/exe").parent_path() / "mpgc_run").string();
  std::vector<sr::PlannerResults> results;
  for (const auto& p : planners) {
    const fs::path dir = fs::absolute(fs::path(out) / p);
    if (!no_run) {
      fs::create_directories(dir);
      // A run that breaks must not be read from an earlier run's files.
      for (const auto& n : names) fs::remove(dir / n / "metrics.json");
      std::vector<std::string> args{run_exe, "--planner", p, "--out", dir.string(), "--quiet"};
      args.insert(args.end(), paths.begin(), paths.end());
      std::fprintf(stderr, "compare: %s on %zu scenario(s), log %s\n", p.c_str(), paths.size(),
                   (dir / "run.log").string().c_str());
      const int rc = mpgc::rt::wait_exit(mpgc::rt::spawn_logged(args, (dir / "run.log").string(), false));
      std::fprintf(stderr, "compare: %s done (mpgc_run exit %d)\n", p.c_str(), rc);
    }
    results.push_back({p, sr::read_results(dir.string(), names)});
    for (std::size_t k = 0; k < names.size(); ++k) results.back().scenarios[k].colreg = colreg[k];
  }
  std::fputs(sr::compare_text(results).c_str(), stdout);
  return 0;
}
