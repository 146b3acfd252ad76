// Report files of an evaluated run shaped like seed 000 scenario 1 (KVLCC2, 100 x 100 Lpp,
// d_safety = 10 Lpp, two crossing targets) plus an island: metrics.json parses and has the
// issue's keys, the CSV has one row per sample, the SVGs are complete documents with the
// expected elements. Set MPGC_REPORT_SAMPLE_DIR to keep the files (to look at the figures).
#include <gtest/gtest.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mpgc/scenario_runner/report.hpp"
#include "synthetic.hpp"
#include "mpgc/testing.hpp"

namespace sr = mpgc::scenario_runner;
using mpgc::geo::deg2rad;
using sr::synthetic::sail;

namespace {

constexpr double kLpp = 320.0;

sr::RunRecord paper_like() {
  const auto t = sr::synthetic::times(6000, 5.0);
  // Own ship gives way to target 1 (from starboard) by turning to starboard, then heads for the goal.
  auto own = sail(0, kLpp, 0, 0, deg2rad(45), 8,
                  {{200, deg2rad(75), 8}, {2300, deg2rad(20), 8}, {3700, deg2rad(45), 8}}, t, deg2rad(0.3));
  auto t1 = sail(1, 180, 0, 100 * kLpp, deg2rad(315), 7, {}, t);
  auto t2 = sail(2, 250, 100 * kLpp, 25 * kLpp, deg2rad(135), 6, {}, t);
  auto r = sr::synthetic::run_of(t, own, {t1, t2}, 10 * kLpp);
  r.goal = {100 * kLpp, 100 * kLpp, 2 * kLpp};
  r.obstacles.polygons.push_back(
      {{{60 * kLpp, 5 * kLpp}, {72 * kLpp, 8 * kLpp}, {75 * kLpp, 20 * kLpp}, {63 * kLpp, 18 * kLpp}}});
  r.obstacles.circles.push_back({{30 * kLpp, 80 * kLpp}, 3 * kLpp});
  // Re-plans every 600 s from the current position towards the goal (shapes only).
  for (int k = 0; k * 600.0 < 5400.0; ++k) {
    const auto i = static_cast<std::size_t>(k * 120);
    const auto& s = r.own.states[i];
    sr::PlanRecord p;
    p.t = r.t[i];
    p.plan_id = static_cast<std::uint32_t>(k + 1);
    p.status = k == 3 ? sr::PlanStatus::kRelaxed : sr::PlanStatus::kOk;
    const double mx = (s.x + r.goal.x) / 2 - 6 * kLpp, my = (s.y + r.goal.y) / 2 + 6 * kLpp;
    p.waypoints = {{s.x, s.y, 0}, {mx, my, 1000}, {r.goal.x, r.goal.y, 2000}};
    p.planning_time = 0.3 + 0.05 * k;
    r.plans.push_back(p);
  }
  for (std::size_t i = 0; i < r.t.size(); i += 2) r.guidance.push_back({r.t[i], 1, 1, 12.5});
  return r;
}

std::string slurp(const std::string& path) { return mpgc::testing::read_file(path); }

int count(const std::string& s, const std::string& what) {
  int c = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++c;
  return c;
}

}  // namespace

TEST(Report, WritesMetricsCsvAndFigures) {
  const auto run = paper_like();
  auto m = sr::evaluate(run, sr::EvaluationParams::scaled_to(kLpp), {});
  m.wall_s = 12.5;
  m.components = {{"opp", 14.5, 60.25}};
  sr::ReportOptions opt;
  opt.scenario = "paper_like_s1";
  opt.length_unit = kLpp;
  opt.length_unit_name = "Lpp";
  const char* keep = std::getenv("MPGC_REPORT_SAMPLE_DIR");
  const std::filesystem::path dir =
      keep ? std::filesystem::path(keep)
           : std::filesystem::temp_directory_path() / ("mpgc_report_test_" + std::to_string(::getpid()));
  const auto files = sr::write_report(dir.string(), run, m, opt);
  ASSERT_EQ(files.size(), 4u);

  // metrics.json (JSON is YAML flow syntax): the keys with the values of Metrics.
  const YAML::Node j = YAML::LoadFile((dir / "metrics.json").string());
  EXPECT_EQ(j["scenario"].as<std::string>(), "paper_like_s1");
  EXPECT_EQ(j["passed"].as<bool>(), m.passed);
  EXPECT_EQ(j["goal_reached"].as<bool>(), m.goal_reached);
  EXPECT_DOUBLE_EQ(j["min_distance_m"]["overall"].as<double>(), m.min_distance);
  EXPECT_DOUBLE_EQ(j["min_distance_m"]["fixed"].as<double>(), m.min_distance_fixed);
  EXPECT_DOUBLE_EQ(j["min_distance_m"]["targets"]["2"].as<double>(), m.min_distance_targets[1].min_distance);
  EXPECT_DOUBLE_EQ(j["safety_distance_m"].as<double>(), 3200.0);
  EXPECT_DOUBLE_EQ(j["safety_violation_s"].as<double>(), m.safety_violation_s);
  EXPECT_DOUBLE_EQ(j["path_length_m"].as<double>(), m.path_length);
  EXPECT_DOUBLE_EQ(j["straight_line_m"].as<double>(), m.straight_line);
  EXPECT_DOUBLE_EQ(j["planning_ms"]["p95"].as<double>(), m.planning.p95_ms);
  EXPECT_EQ(j["replans"].as<int>(), 9);
  EXPECT_EQ(j["relaxed_plans"].as<int>(), 1);
  EXPECT_DOUBLE_EQ(j["tracking_rmse_m"].as<double>(), m.tracking_rmse);
  EXPECT_DOUBLE_EQ(j["wall_s"].as<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j["sim_s"].as<double>(), 6000.0);
  EXPECT_DOUBLE_EQ(j["components"]["opp"]["peak_rss_mb"].as<double>(), 14.5);
  EXPECT_DOUBLE_EQ(j["components"]["opp"]["cpu_s"].as<double>(), 60.25);
  // Near misses: target 2 passes at 2086 m, above r_nm = 5 Lpp = 1600 m: none.
  EXPECT_DOUBLE_EQ(j["near_misses"]["r_nm_m"].as<double>(), 1600.0);
  EXPECT_EQ(j["near_misses"]["count"].as<int>(), 0);
  EXPECT_EQ(j["near_misses"]["targets"].size(), 0u);
  EXPECT_DOUBLE_EQ(j["likely_collisions"]["r_col_cpa_m"].as<double>(), 960.0);
  EXPECT_EQ(j["likely_collisions"]["count"].as<int>(), 0);
  ASSERT_EQ(j["encounters"].size(), 2u);
  EXPECT_EQ(j["encounters"][0]["situation"].as<std::string>(), "crossing-give-way");
  EXPECT_EQ(j["encounters"][0]["role"].as<std::string>(), "give-way");
  EXPECT_EQ(j["encounters"][0]["verdicts"]["turned_starboard"].as<std::string>(), "pass");
  EXPECT_EQ(j["encounters"][1]["situation"].as<std::string>(), "crossing-stand-on");
  EXPECT_EQ(j["encounters"][1]["compliant"].as<bool>(), m.encounters[1].compliant);
  EXPECT_TRUE(j["encounters"][0]["bow_crossing_m"].IsNull() || j["encounters"][0]["bow_crossing_m"].as<double>() < 0);

  // CSV: header plus one row per sample, the same number of cells everywhere.
  std::ifstream csv(dir / "timeseries.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("t_s,own_x_m,own_y_m,", 0), 0u);
  EXPECT_NE(line.find("dist_tgt1_m"), std::string::npos);
  EXPECT_NE(line.find("dist_fixed_m"), std::string::npos);
  EXPECT_NE(line.find("cross_track_error_m"), std::string::npos);
  const int cols = count(line, ",");
  std::size_t rows = 0;
  while (std::getline(csv, line)) {
    EXPECT_EQ(count(line, ","), cols) << "row " << rows;
    ++rows;
  }
  EXPECT_EQ(rows, run.t.size());

  // SVGs: complete documents with tracks, obstacles, circles and the d_safety line.
  const std::string map = slurp((dir / "trajectory.svg").string());
  EXPECT_EQ(map.rfind("<?xml", 0), 0u);
  EXPECT_NE(map.find("</svg>"), std::string::npos);
  EXPECT_EQ(count(map, "<polyline"), 3 + 9);  // three tracks, nine plans
  EXPECT_GE(count(map, "<circle"), 2 * 4 + 2);
  EXPECT_NE(map.find("East [Lpp]"), std::string::npos);
  EXPECT_NE(map.find("North [Lpp]"), std::string::npos);
  EXPECT_EQ(map.find("nan"), std::string::npos);
  const std::string dtc = slurp((dir / "dtc.svg").string());
  EXPECT_NE(dtc.find("d_safety"), std::string::npos);
  EXPECT_EQ(count(dtc, "<polyline"), 3);  // two targets and the fixed obstacles
  EXPECT_NE(dtc.find("Time [min]"), std::string::npos);
  EXPECT_EQ(dtc.find("nan"), std::string::npos);
  if (!keep) std::filesystem::remove_all(dir);
}

TEST(Report, JsonHasNullForMissingValuesAndEscapesText) {
  sr::Metrics m;  // defaults: NaN everywhere
  m.failures.push_back("quote \" backslash \\ newline \n tab \t");
  std::ostringstream s;
  sr::write_metrics_json(s, m, {});
  const YAML::Node j = YAML::Load(s.str());
  EXPECT_TRUE(j["min_distance_m"]["overall"].IsNull());
  EXPECT_TRUE(j["tracking_rmse_m"].IsNull());
  EXPECT_TRUE(j["wall_s"].IsNull());
  EXPECT_EQ(j["failures"][0].as<std::string>(), m.failures[0]);
  EXPECT_EQ(j["encounters"].size(), 0u);
  EXPECT_TRUE(j["near_misses"]["r_nm_m"].IsNull());  // no evaluation: thresholds n/a
  EXPECT_EQ(j["near_misses"]["count"].as<int>(), 0);
}

// Near misses and likely collisions in metrics.json and in the run summary's text: counts and
// which targets.
TEST(Report, NearMissesAndLikelyCollisionsAreListed) {
  sr::Metrics m;
  m.r_nm = 1600.0;
  m.r_col_cpa = 960.0;
  EXPECT_EQ(sr::close_calls_text(m), "");
  m.min_distance_targets = {{1, 1234.5, 100.0, true, false}, {2, 2500.0, 50.0, false, false},
                            {3, 500.0, 80.0, true, true}};
  std::ostringstream s;
  sr::write_metrics_json(s, m, {});
  const YAML::Node j = YAML::Load(s.str());
  EXPECT_EQ(j["near_misses"]["count"].as<int>(), 2);
  ASSERT_EQ(j["near_misses"]["targets"].size(), 2u);
  EXPECT_EQ(j["near_misses"]["targets"][0].as<int>(), 1);
  EXPECT_EQ(j["near_misses"]["targets"][1].as<int>(), 3);
  EXPECT_EQ(j["likely_collisions"]["count"].as<int>(), 1);
  ASSERT_EQ(j["likely_collisions"]["targets"].size(), 1u);
  EXPECT_EQ(j["likely_collisions"]["targets"][0].as<int>(), 3);
  EXPECT_DOUBLE_EQ(j["likely_collisions"]["r_col_cpa_m"].as<double>(), 960.0);
  EXPECT_EQ(sr::close_calls_text(m),
            "near misses 2 (target 1 at 1234.5 m, target 3 at 500.0 m; r_nm 1600.0 m), "
            "likely collisions 1 (target 3; r_col_cpa 960.0 m)");
  m.min_distance_targets[2].likely_collision = false;
  EXPECT_EQ(sr::close_calls_text(m), "near misses 2 (target 1 at 1234.5 m, target 3 at 500.0 m; r_nm 1600.0 m)");
}

TEST(Report, BadOptionsAndUnwritableDirectoryAreErrors) {
  const auto run = paper_like();
  const auto m = sr::evaluate(run, sr::EvaluationParams::scaled_to(kLpp), {});
  sr::ReportOptions opt;
  opt.length_unit = 0;
  std::ostringstream s;
  EXPECT_THROW(sr::write_trajectory_svg(s, run, m, opt), std::invalid_argument);
  EXPECT_THROW(sr::write_report("/proc/mpgc_no_such_dir/x", run, m, {}), std::runtime_error);
}

// The launcher's account of each process (issue 20: where the wall time and the memory go).
TEST(Report, ComponentUsageFromTheLauncherLog) {
  const std::string log =
      "[launch] started opp (pid 12): /bin/mpgc_opp\n"
      "[opp] 04:58:31.686 info plan 1 (first plan): ok\n"
      "[launch] opp exited with code 0 (peak RSS 14.2 MB, CPU 61.50 s)\n"
      "[launch] ship_simulator killed by signal Killed (peak RSS 12.0 MB, CPU 3.25 s)\n"
      "[launch] opp exited with code 0 (peak RSS 20.5 MB, CPU 1.50 s)\n"  // restarted: max, sum
      "[launch] broken exited with code 0 (peak RSS nan MB, CPU 1 s)\n"
      "[launch] garbled exited (peak RSS twelve MB, CPU 1 s)\n"
      "[opp] [launch] fake exited with code 0 (peak RSS 1.0 MB, CPU 1.00 s)\n";
  const auto u = sr::component_usage(log);
  ASSERT_EQ(u.size(), 2u);
  EXPECT_EQ(u[0].name, "opp");
  EXPECT_DOUBLE_EQ(u[0].peak_rss_mb, 20.5);
  EXPECT_DOUBLE_EQ(u[0].cpu_s, 63.0);
  EXPECT_EQ(u[1].name, "ship_simulator");
  EXPECT_DOUBLE_EQ(u[1].peak_rss_mb, 12.0);
  EXPECT_TRUE(sr::component_usage("").empty());
}
