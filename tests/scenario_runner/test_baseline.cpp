// The suites' ratchet (scenarios/baseline.json): what fails a run, what is only reported, and the
// file's errors; and the shipped baseline itself reads and names only scenarios that exist.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mpgc/scenario_runner/baseline.hpp"
#include "mpgc/testing.hpp"

namespace sr = mpgc::scenario_runner;
using sr::Result;

namespace {
std::string write(const std::string& name, const std::string& text) {
  const auto p = std::filesystem::temp_directory_path() / name;
  std::ofstream(p) << text;
  return p.string();
}
}  // namespace

TEST(Baseline, FailureKindsKeepIdsAndDropMeasuredQuantities) {
  EXPECT_EQ(sr::failure_kind("min distance 863.1 m < 879.7 m (d_safety 926.0 m, tolerance 5.0 %)"),
            "min distance # m < # m (d_safety # m, tolerance # %)");
  EXPECT_EQ(sr::failure_kind("COLREG: target 2 (head-on): no readily apparent action (rule 8(b))"),
            "COLREG: target 2 (head-on): no readily apparent action (rule 8(b))");
  EXPECT_EQ(sr::failure_kind("below d_safety for 53 s (allowed 60.0 s)"), "below d_safety for # s (allowed # s)");
}

TEST(Baseline, OnlyAListedPassThatFailsANewKindOfFailureOrABrokenRunFails) {
  const auto b = sr::read_baseline(write("baseline_ok.json", R"J({"passing": ["a", "b"],
      "failing": {"c": ["COLREG: target 1 (head-on): no readily apparent action (rule 8(b))"], "d": ["x"]}})J"));
  const std::string rule8 = "COLREG: target 1 (head-on): no readily apparent action (rule 8(b))";
  auto r = sr::judge(b, {{"a", Result::kPassed, {}}, {"c", Result::kFailed, {rule8}}});
  EXPECT_TRUE(r.ok());
  ASSERT_EQ(r.known_failures.size(), 1u);
  EXPECT_EQ(r.known_failures[0], "c: " + rule8);
  r = sr::judge(b, {{"a", Result::kFailed, {"goal not reached"}},
                    {"d", Result::kPassed, {}},
                    {"new", Result::kFailed, {"y"}},
                    {"c", Result::kFailed, {rule8, "min distance 800.0 m < 879.7 m"}},
                    {"b", Result::kError, {}}});
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.regressions.size(), 4u);
  EXPECT_EQ(r.regressions[0], "a: listed as passing, failed");
  EXPECT_EQ(r.regressions[1], "new: not in the baseline, failed");
  EXPECT_EQ(r.regressions[2], "c: a failure not listed for it: min distance 800.0 m < 879.7 m");
  EXPECT_EQ(r.regressions[3], "b: the run broke (an error, not a verdict)");
  EXPECT_EQ(r.new_passes, std::vector<std::string>{"d"});
  const std::string text = sr::describe(r, "baseline.json");
  EXPECT_NE(text.find("REGRESSION against baseline.json: a: listed as passing, failed"), std::string::npos) << text;
  EXPECT_NE(text.find("now passes, listed as failing in baseline.json: d"), std::string::npos) << text;
}

TEST(Baseline, BadFilesAreNamed) {
  auto expect_error = [](const std::string& text, const std::string& what) {
    try {
      sr::read_baseline(write("baseline_bad.json", text));
      ADD_FAILURE() << "no error for " << text;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  expect_error("{", "not JSON");
  expect_error("[]", "must be an object");
  expect_error(R"J({"passing": "a"})J", "\"passing\" must be an array");
  expect_error(R"J({"failing": {"a": ""}})J", "give its failure kinds");
  expect_error(R"J({"failing": {"a": []}})J", "give its failure kinds");
  expect_error(R"J({"passing": ["a"], "failing": {"a": ["x"]}})J", "a is listed as passing and as failing");
  expect_error(R"J({"pasing": []})J", "unknown key \"pasing\"");
  EXPECT_THROW(sr::read_baseline("/nonexistent/baseline.json"), std::runtime_error);
}

TEST(Baseline, TheShippedBaselineReads) {
  const auto b = sr::read_baseline(mpgc::testing::source_dir() + "/scenarios/baseline.json");
  EXPECT_FALSE(b.passing.empty());
}
