#include <gtest/gtest.h>

#include <filesystem>

#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/testing.hpp"

namespace sr = mpgc::scenario_runner;

namespace {
const char* kMinimal = R"(name: t
lpp_m: 100
world:
  origin: {lat_deg: 38.8, lon_deg: -76.3}
  own_ship: {model: nomoto, x_lpp: 1, y_lpp: 2, heading_deg: 0, speed_kn: 10}
  targets:
    - {mmsi: 257000001, x_lpp: 50, y_lpp: 0, course_deg: 180, speed_kn: 10}
goal: {x_lpp: 100, y_lpp: 100}
safety_distance_lpp: 10
time_limit_s: 100
obstacles: {shapes_lpp: "circle 50 50 5; polygon 0 0 1 0 1 1"}
params: {opp: {replan.period: 15}}
criteria: {safety_tolerance: 0.05, targets: [{id: 1, situation: head-on}]}
)";

std::string error_of(const std::string& yaml) {
  try {
    sr::parse_scenario(yaml, "s.yaml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(ScenarioFile, LppKeysBecomeMetres) {
  const auto s = sr::parse_scenario(kMinimal, "s.yaml");
  EXPECT_EQ(s.world["own_ship"]["x_m"].as<double>(), 100.0);
  EXPECT_FALSE(s.world["own_ship"]["x_lpp"]);
  EXPECT_EQ(s.world["targets"][0]["x_m"].as<double>(), 5000.0);
  EXPECT_EQ(s.goal.x, 10000.0);
  EXPECT_EQ(s.goal.radius, 200.0);  // default 2 Lpp
  EXPECT_EQ(s.safety_distance, 1000.0);
  EXPECT_EQ(s.chart_shapes, "circle 5000 5000 500; polygon 0 0 100 0 100 100");
  EXPECT_EQ(s.params.at("opp").at("replan.period"), "15");
  ASSERT_EQ(s.criteria.required.size(), 1u);
  EXPECT_EQ(s.criteria.required[0].situation, mpgc::colreg::EncounterType::kHeadOn);
  EXPECT_DOUBLE_EQ(s.criteria.safety_tolerance, 0.05);
}

TEST(ScenarioFile, ErrorsNameLineAndKey) {
  std::string y = kMinimal;
  EXPECT_NE(error_of(y + "colour: red\n").find("scenario.colour: unknown key"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal).replace(y.find("time_limit_s: 100"), 17, "time_limit_s: soon"))
                .find("s.yaml:10: time_limit_s: 'soon' is not a number"),
            std::string::npos)
      << error_of(std::string(kMinimal).replace(y.find("time_limit_s: 100"), 17, "time_limit_s: soon"));
  EXPECT_NE(error_of(std::string(kMinimal).replace(y.find("goal: {x_lpp"), 5, "gaol:")).find("s.yaml:8: scenario.gaol: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("name: x\nworld: [unclosed\n").find("malformed YAML"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal).replace(y.find("head-on"), 7, "sideways")).find("unknown situation 'sideways'"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal).replace(y.find("opp:"), 4, "pop:")).find("params.pop: unknown key"),
            std::string::npos);
}

TEST(ScenarioFile, EveryShippedScenarioLoads) {
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(mpgc::testing::source_dir() + "/scenarios")) {
    if (e.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(sr::load_scenario(e.path().string())) << e.path();
    ++n;
  }
  EXPECT_GE(n, 11);
}
