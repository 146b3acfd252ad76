// DNV ship-traffic-generator situations as scenarios: the conversion of a generated file (own
// ship, goal, targets' routes, the documented choices), all 55 files, and malformed files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "mpgc/geo/angles.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/testing.hpp"

namespace sr = mpgc::scenario_runner;
namespace geo = mpgc::geo;
using mpgc::testing::shared_data;

namespace {
std::string generated(const std::string& nn) {
  return shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_" + nn + ".json");
}

std::string error_of(const std::string& path) {
  try {
    sr::load_scenario(path);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

// A valid generated-schema situation with one target; pieces replaced by the malformed cases.
std::string situation(const std::string& own_static = R"({"dimensions": {"length": 122.0, "width": 20.0}})",
                      const std::string& target_wp1 = R"({"position": {"lat": 58.76, "lon": 10.49}, "leg": {"sog": 8.0}})") {
  return R"({"title": "T", "ownShip": {"initial": {"heading": 0.0},
      "waypoints": [{"position": {"lat": 58.70, "lon": 10.49}, "leg": {"sog": 10.0}},
                    {"position": {"lat": 58.78, "lon": 10.49}, "leg": {"sog": 10.0}}],
      "static": )" + own_static + R"(},
    "targetShips": [{"initial": {"heading": 180.0},
      "waypoints": [{"position": {"lat": 58.80, "lon": 10.49}, "leg": {"sog": 8.0}}, )" + target_wp1 + R"(],
      "static": {"dimensions": {"length": 50.0, "width": 10.0}}}]})";
}
}  // namespace

// Situation 01 (head-on): the own ship on its first waypoint with heading and SOG, the goal on the
// last one, the target on its route, and every choice of scenarios/README.md "DNV situations".
TEST(DnvScenario, ConvertsTheHeadOnSituation) {
  const sr::Scenario s = sr::load_scenario(generated("01"));
  EXPECT_EQ(s.name, "dnv_01_HO");
  EXPECT_DOUBLE_EQ(s.lpp, 122.0);
  EXPECT_NEAR(s.origin_lat_deg, 58.763449, 1e-9);
  EXPECT_NEAR(s.origin_lon_deg, 10.490654, 1e-9);
  const YAML::Node own = s.world["own_ship"];
  EXPECT_EQ(own["model"].as<std::string>(), "nomoto");
  EXPECT_DOUBLE_EQ(own["length_m"].as<double>(), 122.0);
  EXPECT_DOUBLE_EQ(own["beam_m"].as<double>(), 20.0);
  EXPECT_DOUBLE_EQ(own["x_m"].as<double>(), 0.0);
  EXPECT_NEAR(own["heading_deg"].as<double>(), 0.0, 1e-9);
  EXPECT_NEAR(own["speed_kn"].as<double>(), 10.0, 1e-9);
  // Goal: 0.0831234 deg of latitude due north (WGS84 meridian radius at 58.8 N, 6382 km: 9259 m).
  EXPECT_NEAR(s.goal.x, 9259.3, 1.0);
  EXPECT_NEAR(s.goal.y, 0.0, 0.01);
  EXPECT_DOUBLE_EQ(s.goal.radius, 244.0);  // 2 ship lengths
  EXPECT_NEAR(s.cruise_speed, 10.0 * geo::kKnot, 1e-12);
  EXPECT_DOUBLE_EQ(s.time_limit, 2700.0);  // 9259 m at 10 kn = 1800 s, x 1.5, up to 100 s
  EXPECT_DOUBLE_EQ(s.safety_distance, 926.0);
  EXPECT_NEAR(s.evaluation_min_cpa, 0.95 * 926.0, 1e-9);  // the safety criterion's lower edge
  EXPECT_TRUE(s.colreg);
  EXPECT_EQ(s.params.at("opp").at("plan.colreg_distance"), "5556");
  EXPECT_EQ(s.params.at("guidance_control").at("los.lookahead"), "305");
  // Mariner K' = 3.858, T' = 5.146 scaled to 122 m at 10 kn.
  EXPECT_NEAR(std::stod(s.params.at("guidance_control").at("heading.nomoto_K")), 0.1627, 1e-4);
  EXPECT_NEAR(std::stod(s.params.at("guidance_control").at("heading.nomoto_T")), 122.0, 0.1);
  ASSERT_EQ(s.world["targets"].size(), 1u);
  const YAML::Node t = s.world["targets"][0];
  EXPECT_NEAR(t["lat_deg"].as<double>(), 58.85500037, 1e-9);
  EXPECT_NEAR(t["course_deg"].as<double>(), 183.63 - 360.0, 1e-9);
  EXPECT_NEAR(t["speed_kn"].as<double>(), 12.1, 1e-9);
  EXPECT_DOUBLE_EQ(t["length_m"].as<double>(), 50.0);
  ASSERT_EQ(t["waypoints"].size(), 1u);
  EXPECT_NEAR(t["waypoints"][0]["lon_deg"].as<double>(), 10.48458595, 1e-9);
  EXPECT_NEAR(t["waypoints"][0]["speed_kn"].as<double>(), 12.1, 1e-9);
  EXPECT_TRUE(s.criteria.goal_required);
  EXPECT_DOUBLE_EQ(s.criteria.safety_tolerance, 0.05);
  EXPECT_DOUBLE_EQ(s.criteria.max_safety_violation_s, 60.0);
  ASSERT_EQ(s.criteria.required.size(), 1u);
  EXPECT_EQ(s.criteria.required[0].target_id, 1u);
  EXPECT_TRUE(s.criteria.required[0].compliant);
  EXPECT_NE(s.description.find("head-on"), std::string::npos);
  // The evaluation is scaled so that its minimum CPA is 0.95 d_safety.
  EXPECT_NEAR(sr::evaluation_params(s, 122.0).r_min_cpa, 0.95 * 926.0, 1e-9);
}

// Every one of the 55 situations converts; every target carries its desired type as a requirement;
// d_safety is 0.5 NM except where a target starts closer than 0.5 NM / 0.8 (situation 17: 756 m).
TEST(DnvScenario, All55SituationsConvert) {
  int n = 0, reduced = 0;
  for (const auto& e : std::filesystem::directory_iterator(shared_data("encounters/dnv/baseline_situations_generated"))) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    const sr::Scenario s = sr::load_scenario(e.path().string());
    ++n;
    const std::size_t targets = s.world["targets"].size();
    EXPECT_GE(targets, 1u);
    EXPECT_LE(targets, 3u);
    EXPECT_EQ(s.criteria.required.size(), targets);
    EXPECT_LE(s.safety_distance, 926.0);
    if (s.safety_distance < 926.0) {
      ++reduced;
      EXPECT_EQ(s.name, "dnv_17_CR-SO_OT-GW");
      EXPECT_NEAR(s.safety_distance, 0.8 * 756.0, 2.0);
    }
  }
  EXPECT_EQ(n, 55);
  EXPECT_EQ(reduced, 1);
}

// Malformed files: the error names the file and the field.
TEST(DnvScenario, MalformedFilesNameFileAndField) {
  struct Case {
    std::string path, needle;
  };
  const std::vector<Case> cases{
      {write("dnv_broken.json", R"({"ownShip": {"initial": )"), "cannot parse"},
      {write("dnv_nolength.json", situation(R"({"name": "x"})")), "ownShip.static.dimensions.length: missing"},
      {write("dnv_badwp.json", situation(R"({"dimensions": {"length": 122.0}})",
                                         R"({"position": {"lat": 58.76, "lon": "east"}})")),
       "targetShips[0].waypoints[1].position.lon: 'east' is not a number"},
      {write("dnv_nopos.json", situation(R"({"dimensions": {"length": 122.0}})", R"({"leg": {"sog": 8.0}})")),
       "targetShips[0].waypoints[1].position: missing"},
      {write("dnv_negsog.json", situation(R"({"dimensions": {"length": 122.0}})",
                                          R"({"position": {"lat": 58.76, "lon": 10.49}, "leg": {"sog": -3}})")),
       "targetShips[0].waypoints[1].leg.sog: is negative"},
      {write("dnv_onewp.json",
             R"({"ownShip": {"initial": {"heading": 0}, "waypoints": [{"position": {"lat": 58.7, "lon": 10.4}, "leg": {"sog": 10}}],
                 "static": {"dimensions": {"length": 122}}}, "targetShips": []})"),
       "ownShip.waypoints: needs at least 2 waypoints"},
      {write("dnv_notargets.json", R"({"ownShip": {"initial": {"heading": 0}, "waypoints": []}})"),
       "ownShip: has neither initial.position/sog nor waypoints"},
  };
  for (const auto& c : cases) {
    const std::string err = error_of(c.path);
    EXPECT_NE(err.find(c.path + ": "), std::string::npos) << err;
    EXPECT_NE(err.find(c.needle), std::string::npos) << "expected '" << c.needle << "' in: " << err;
  }
  EXPECT_NE(error_of(::testing::TempDir() + "dnv_missing.json").find("dnv_missing.json"), std::string::npos);
  // A well-formed file of the same shape converts; with an unknown desired type it does not.
  const std::string ok = write("dnv_ok.json", situation());
  const auto d = mpgc::dnv::read_situation(ok);
  EXPECT_EQ(sr::dnv_scenario(d, {"head-on"}).criteria.required.size(), 1u);
  EXPECT_EQ(sr::dnv_scenario(d, {}).criteria.required.size(), 0u);
  try {
    sr::dnv_scenario(d, {"sideways"});
    ADD_FAILURE() << "accepted an unknown desired type";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(ok + ": targetShips[0]: desiredEncounterType 'sideways'"), std::string::npos)
        << e.what();
  }
}
