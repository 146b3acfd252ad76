// ./mpgc compare's table and JSON (compare.hpp) from two fabricated metrics folders: the figures
// over scenarios, and a failed and a broken run that must show up.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "mpgc/json/json.hpp"
#include "mpgc/scenario_runner/compare.hpp"

namespace fs = std::filesystem;
namespace sr = mpgc::scenario_runner;

namespace {

struct Fake {
  bool passed = true;
  std::vector<std::string> failures;
  int collisions = 0;
  double min_d = 0, d_safe = 500, path = 0, straight = 1000, plan_median = 0, plan_p95 = 0;
  std::vector<std::pair<bool, bool>> encounters;  // (encountered with a situation, compliant)
};

void write_metrics(const fs::path& dir, const std::string& scenario, const Fake& f) {
  using mpgc::json::Json;
  fs::create_directories(dir / scenario);
  Json enc = Json::array();
  for (const auto& [met, ok] : f.encounters)
    enc.push_back({{"target_id", enc.size() + 1}, {"encountered", true}, {"situation", met ? "head-on" : "none"},
                   {"compliant", ok}});
  enc.push_back({{"target_id", 99}, {"encountered", false}, {"situation", "crossing-give-way"}, {"compliant", false}});
  Json j = {{"scenario", scenario},
            {"passed", f.passed},
            {"failures", f.failures},
            {"goal_reached", f.passed},
            {"min_distance_m", {{"overall", f.min_d}, {"fixed", nullptr}, {"targets", Json::object()}}},
            {"safety_distance_m", f.d_safe},
            {"likely_collisions", {{"r_col_cpa_m", 30.0}, {"count", f.collisions}, {"targets", Json::array()}}},
            {"path_length_m", f.path},
            {"straight_line_m", f.straight},
            {"planning_ms", {{"median", f.plan_median}, {"p95", f.plan_p95}, {"max", f.plan_p95 * 2}}},
            {"encounters", enc}};
  std::ofstream(dir / scenario / "metrics.json") << j.dump(2) << "\n";
}

class Compare : public ::testing::Test {
 protected:
  void SetUp() override {
    root = fs::temp_directory_path() / ("mpgc_compare_test_" + std::to_string(::getpid()));
    fs::remove_all(root);
    Fake a1;  // passes, 2.0 x d_safety, 10 % longer, two compliant encounters (+ one without a situation)
    a1.min_d = 1000, a1.path = 1100, a1.plan_median = 10, a1.plan_p95 = 20, a1.encounters = {{true, true}, {true, true}, {false, false}};
    Fake a2;  // passes, 1.2 x d_safety, 30 % longer, one encounter not compliant
    a2.min_d = 600, a2.path = 1300, a2.plan_median = 30, a2.plan_p95 = 50, a2.encounters = {{true, false}};
    write_metrics(root / "alpha", "s1", a1);
    write_metrics(root / "alpha", "s2", a2);
    Fake b1;  // fails: too close, a likely collision, not compliant
    b1.passed = false, b1.failures = {"min distance 400.0 m < 475.0 m"}, b1.collisions = 1;
    b1.min_d = 400, b1.path = 1500, b1.plan_median = 100, b1.plan_p95 = 400, b1.encounters = {{true, false}};
    write_metrics(root / "beta", "s1", b1);
    // beta's s2 broke: no metrics.json.
    fs::create_directories(root / "beta" / "s2");
  }
  void TearDown() override { fs::remove_all(root); }
  std::vector<sr::PlannerResults> results() const {
    return {{"alpha", sr::read_results((root / "alpha").string(), {"s1", "s2"})},
            {"beta", sr::read_results((root / "beta").string(), {"s1", "s2"})}};
  }
  fs::path root;
};

}  // namespace

TEST_F(Compare, SummariesOverScenarios) {
  const auto r = results();
  const sr::PlannerSummary a = sr::summarize(r[0]);
  EXPECT_EQ(a.passed, 2);
  EXPECT_EQ(a.total, 2);
  EXPECT_EQ(a.errors, 0);
  EXPECT_EQ(a.collisions, 0);
  EXPECT_DOUBLE_EQ(a.min_dist_ratio_worst, 1.2);
  EXPECT_DOUBLE_EQ(a.min_dist_ratio_median, 1.6);
  EXPECT_DOUBLE_EQ(a.elongation_median, 1.2);
  EXPECT_EQ(a.encounters, 3);  // the one without a situation and the one never met do not count
  EXPECT_EQ(a.compliant, 2);
  EXPECT_DOUBLE_EQ(a.colreg_compliant_share, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(a.plan_ms_median, 20.0);  // median of the runs' medians
  EXPECT_DOUBLE_EQ(a.plan_ms_p95, 50.0);     // the worst run's p95

  const sr::PlannerSummary b = sr::summarize(r[1]);
  EXPECT_EQ(b.passed, 0);
  EXPECT_EQ(b.total, 2);
  EXPECT_EQ(b.errors, 1);
  EXPECT_EQ(b.collisions, 1);
  EXPECT_DOUBLE_EQ(b.min_dist_ratio_worst, 0.8);
  EXPECT_DOUBLE_EQ(b.elongation_median, 1.5);
  EXPECT_DOUBLE_EQ(b.colreg_compliant_share, 0.0);
  EXPECT_DOUBLE_EQ(b.plan_ms_median, 100.0);
  EXPECT_DOUBLE_EQ(b.plan_ms_p95, 400.0);
}

TEST_F(Compare, EncountersOfARunWithoutColregDoNotCount) {
  auto r = results();
  r[0].scenarios[1].colreg = false;  // s2 sailed without COLREG: its violation was required
  const sr::PlannerSummary a = sr::summarize(r[0]);
  EXPECT_EQ(a.encounters, 2);
  EXPECT_EQ(a.compliant, 2);
  EXPECT_DOUBLE_EQ(a.colreg_compliant_share, 1.0);
  EXPECT_EQ(a.passed, 2);  // everything else as before
  EXPECT_DOUBLE_EQ(a.min_dist_ratio_worst, 1.2);
}

TEST_F(Compare, TableShowsEveryFailureAndTheJsonLineIsLast) {
  const std::string text = sr::compare_text(results());
  // One row per planner.
  EXPECT_NE(text.find("alpha          2/2      0          0          1.20          1.60      1.200 "), std::string::npos)
      << text;
  EXPECT_NE(text.find("beta           0/2      1          1          0.80          0.80      1.500 "), std::string::npos)
      << text;
  EXPECT_NE(text.find("2/3 0.67"), std::string::npos) << text;
  // Every scenario per planner, and why a planner did not pass it.
  EXPECT_NE(text.find("s1                             pass 2.00    FAIL 0.80"), std::string::npos) << text;
  EXPECT_NE(text.find("s2                             pass 1.20    ERROR"), std::string::npos) << text;
  EXPECT_NE(text.find("beta s1: FAIL\n    why: min distance 400.0 m < 475.0 m\n"), std::string::npos) << text;
  EXPECT_NE(text.find("beta s2: ERROR\n    why: no metrics.json"), std::string::npos) << text;
  EXPECT_EQ(text.find("alpha s1:"), std::string::npos) << text;

  // The last line is the JSON.
  ASSERT_EQ(text.back(), '\n');
  const std::string last = text.substr(text.rfind('\n', text.size() - 2) + 1);
  const auto j = mpgc::json::Json::parse(last);
  const auto& a = j.at("planners").at("alpha");
  EXPECT_EQ(a.at("passed"), 2);
  EXPECT_EQ(a.at("total"), 2);
  EXPECT_EQ(a.at("collisions"), 0);
  EXPECT_DOUBLE_EQ(a.at("min_dist_ratio_worst").get<double>(), 1.2);
  EXPECT_DOUBLE_EQ(a.at("elongation_median").get<double>(), 1.2);
  EXPECT_DOUBLE_EQ(a.at("colreg_compliant_share").get<double>(), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(a.at("plan_ms_median").get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(a.at("plan_ms_p95").get<double>(), 50.0);
  const auto& b = j.at("planners").at("beta");
  EXPECT_EQ(b.at("passed"), 0);
  EXPECT_EQ(b.at("total"), 2);
  EXPECT_EQ(b.at("collisions"), 1);
  EXPECT_DOUBLE_EQ(b.at("min_dist_ratio_worst").get<double>(), 0.8);
  EXPECT_DOUBLE_EQ(b.at("plan_ms_p95").get<double>(), 400.0);
}

TEST_F(Compare, NothingRanGivesNullsNotNumbers) {
  std::ofstream(root / "beta" / "s2" / "metrics.json") << "{ not json";
  const auto f = sr::read_figures((root / "beta" / "s2" / "metrics.json").string(), "s2");
  EXPECT_FALSE(f.ran);
  EXPECT_NE(f.error.find("not a metrics.json"), std::string::npos) << f.error;
  const std::vector<sr::PlannerResults> none{{"gamma", sr::read_results((root / "nowhere").string(), {"s1"})}};
  const auto j = mpgc::json::Json::parse(sr::compare_json(none));
  const auto& g = j.at("planners").at("gamma");
  EXPECT_EQ(g.at("passed"), 0);
  EXPECT_EQ(g.at("total"), 1);
  EXPECT_TRUE(g.at("min_dist_ratio_worst").is_null());
  EXPECT_TRUE(g.at("plan_ms_p95").is_null());
}
