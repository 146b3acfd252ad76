#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/scenario_runner/scenario_obstacles.hpp"
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
criteria: {safety_tolerance: 0.05, min_ship_distance_m: 1296.4, targets: [{id: 1, situation: head-on}]}
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
  EXPECT_DOUBLE_EQ(s.criteria.min_ship_distance, 1296.4);
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

TEST(ScenarioFile, FaultsAreParsedInTimeOrderAndCheckedByName) {
  const std::string y = std::string(kMinimal) + R"(faults:
  - {at_s: 50, stop: opp, for_s: 10}
  - {at_s: 20, kill: guidance_control}
  - {at_s: 30, silence: sensors/ais, for_s: 5}
  - {at_s: 40, ais_outage: 257000001, for_s: 60}
  - {at_s: 60, gnss_dropout: true, for_s: 2}
  - {at_s: 70, position_jump_m: [200, -50], for_s: 3}
)";
  const sr::Scenario s = sr::parse_scenario(y, "s.yaml");
  ASSERT_EQ(s.faults.size(), 6u);
  EXPECT_EQ(s.faults[0].kind, sr::Fault::Kind::kKill);
  EXPECT_EQ(s.faults[0].component, "guidance_control");
  EXPECT_EQ(s.faults[1].describe(), "silence sensors/ais for 5 s");
  EXPECT_EQ(s.faults[2].mmsi, 257000001u);
  EXPECT_EQ(s.faults[3].describe(), "stop opp for 10 s");
  EXPECT_EQ(s.faults[5].dy, -50.0);
  const std::string base = std::string(kMinimal) + "faults:\n";
  EXPECT_NE(error_of(base + "  - {at_s: 1, kill: radar}\n").find("'radar' is not one of the five components"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: 1, kill: opp, for_s: 3}\n").find("a kill has no duration"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: 1, stop: opp}\n").find("for_s: is required"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: 1, ais_outage: 99, for_s: 3}\n").find("no target has MMSI 99"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: 1, kill: opp, gnss_dropout: true}\n").find("exactly one of"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: 1, position_jump_m: [.nan, 0], for_s: 3}\n").find("finite"), std::string::npos);
  EXPECT_NE(error_of(base + "  - {at_s: -1, kill: opp}\n").find("at_s"), std::string::npos);
}

TEST(ScenarioFile, FromTakesAnotherScenarioAndOverridesNameFaultsAndCriteria) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "scenario_from";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "base.yaml") << kMinimal;
  std::ofstream(dir / "derived.yaml") << "name: d\nfrom: base.yaml\ntime_limit_s: 500\nfaults: [{at_s: 9, kill: opp}]\n"
                                         "criteria: {goal: false}\nparams: {opp: {plan.seed: 3}}\n";
  const sr::Scenario s = sr::load_scenario((dir / "derived.yaml").string());
  EXPECT_EQ(s.name, "d");
  EXPECT_EQ(s.time_limit, 500.0);
  EXPECT_DOUBLE_EQ(s.safety_distance, 1000.0);  // the base's
  EXPECT_FALSE(s.criteria.goal_required);
  EXPECT_EQ(s.params.at("opp").at("replan.period"), "15");  // the base's parameters stay
  EXPECT_EQ(s.params.at("opp").at("plan.seed"), "3");
  ASSERT_EQ(s.faults.size(), 1u);
  std::ofstream(dir / "bad.yaml") << "name: b\nfrom: nowhere.yaml\n";
  try {
    sr::load_scenario((dir / "bad.yaml").string());
    FAIL() << "accepted a missing base";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no such scenario file"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "bad2.yaml") << "name: b\nfrom: base.yaml\nworld: {}\n";
  EXPECT_THROW(sr::load_scenario((dir / "bad2.yaml").string()), std::runtime_error);
}

// The evaluation's fixed obstacles come from the scenario itself: circles exact, other shapes and
// chart files through the chart loader; an unreadable chart is an error naming it.
TEST(ScenarioObstacles, TheScenariosOwnShapesAndChart) {
  sr::Scenario s;
  s.origin_lat_deg = 38.965;
  s.origin_lon_deg = -76.45;
  s.chart_shapes = "circle 1000 0 100; polygon 0 500 100 500 100 600; line -500 0 -500 100";
  auto o = sr::scenario_obstacles(s, "");
  ASSERT_EQ(o.circles.size(), 1u);
  EXPECT_DOUBLE_EQ(o.circles[0].radius, 100.0);
  EXPECT_NEAR(sr::distance_to_obstacles({1000, 150}, o), 50.0, 1e-9);  // exact, not the circumscribed polygon
  EXPECT_EQ(o.polygons.size(), 2u);
  EXPECT_NEAR(sr::distance_to_obstacles({-500, 50}, o), 0.0, 1e-9);     // on the line
  s.chart_shapes = "circle 0 0";
  EXPECT_THROW(sr::scenario_obstacles(s, ""), std::runtime_error);      // add_shapes names it
  s.chart_shapes = "";
  s.chart_files = {"chart/crop_annapolis_LNDARE.geojson"};
  o = sr::scenario_obstacles(s, mpgc::testing::source_dir() + "/../shared/data");
  EXPECT_GE(o.polygons.size(), 5u);  // the crop's 8 land areas
  s.chart_files = {"chart/no_such_chart.geojson"};
  EXPECT_ANY_THROW(sr::scenario_obstacles(s, mpgc::testing::source_dir() + "/../shared/data"));
}
