// The closed-loop runner's logic without DDS or processes (runner.hpp): what mpgc_run's main.cpp
// used to do inline, tested here directly.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <yaml-cpp/yaml.h>

#include "mpgc/scenario_runner/runner.hpp"

namespace sr = mpgc::scenario_runner;
namespace fs = std::filesystem;

namespace {

sr::Scenario scenario() {
  sr::Scenario s;
  s.name = "t";
  s.path = "t.yaml";
  s.lpp = 200;
  s.world = YAML::Load("own_ship: {x: 0}\n");
  s.goal.x = 1000;
  s.goal.y = 0;
  s.goal.radius = 50;
  s.time_limit = 600;
  s.safety_distance = 300;
  return s;
}

YAML::Node components(const std::string& launch) {
  YAML::Node out;
  for (const YAML::Node& c : YAML::Load(launch)["components"]) out[c["name"].as<std::string>()] = c;
  return out;
}

TEST(Runner, LockstepLaunchFileHasTheParticipantsAndTheScenariosParameters) {
  sr::Scenario s = scenario();
  s.params["opp"]["plan.seed"] = "7";
  s.chart_files = {"a.000", "b.000"};
  const auto c = components(sr::launch_file(s, "/run/x/world.yaml", sr::RunOptions{}, 3, {}, {}));
  ASSERT_EQ(c.size(), 6u);  // the five and the recorder
  EXPECT_FALSE(c["ship_bridge"]);
  EXPECT_EQ(c["recorder"]["executable"].as<std::string>(), "mpgc_record");
  EXPECT_EQ(c["recorder"]["set"]["record.file"].as<std::string>(), "/run/x/run.mcap");
  EXPECT_EQ(c["recorder"]["set"]["record.sim_time"].as<std::string>(), "true");
  EXPECT_EQ(c["ship_simulator"]["set"]["time.mode"].as<std::string>(), "lockstep");
  EXPECT_EQ(c["ship_simulator"]["set"]["lockstep.participants"].as<std::string>(),
            "scenario_runner,situational_awareness,obstacle_manager,opp,guidance_control");
  EXPECT_EQ(c["ship_simulator"]["set"]["resume.journal"].as<std::string>(), "/run/x/sim_journal.bin");
  EXPECT_EQ(c["opp"]["set"]["plan.time_budget"].as<std::string>(), "30");  // the budget is iterations
  EXPECT_EQ(c["opp"]["set"]["plan.seed"].as<std::string>(), "7");
  EXPECT_EQ(c["opp"]["set"]["memory.file"].as<std::string>(), "/run/x/opp_memory.yaml");
  EXPECT_EQ(c["obstacle_manager"]["set"]["chart.files"].as<std::string>(), "a.000,b.000");
  EXPECT_EQ(c["opp"]["executable"].as<std::string>(), "mpgc_opp");
  EXPECT_FALSE(c["opp"]["set"]["faults.accept"]);
}

TEST(Runner, DijkstraSvGetsTablesOfTheWorldsOwnShipAtTheCruiseSpeed) {
  sr::Scenario s = scenario();
  s.world = YAML::Load("own_ship: {model: nomoto, length_m: 122, beam_m: 18, speed_kn: 12}\n");
  EXPECT_TRUE(sr::turning_tables_command(s, "", "/b", "/r/t.csv").empty());         // rrtstar
  EXPECT_TRUE(sr::turning_tables_command(s, "apf-vo", "/b", "/r/t.csv").empty());
  const std::vector<std::string> want{"/b/mpgc_trial", "--model", "nomoto", "--length-m", "122", "--beam-m", "18",
                                      "--speed-kn", "12", "table", "--out", "/r/t.csv"};
  EXPECT_EQ(sr::turning_tables_command(s, "dijkstra-sv", "/b", "/r/t.csv"), want);
  s.params["opp"]["plan.planner"] = "dijkstra-sv";  // the scenario's own choice
  EXPECT_EQ(sr::turning_tables_command(s, "", "/b", "/r/t.csv"), want);
  s.cruise_speed = 10 * 1852.0 / 3600.0;  // goal.speed_kn: the plans' speed
  EXPECT_EQ(sr::turning_tables_command(s, "", "/b", "/r/t.csv")[8], "10");
  s.params["opp"]["plan.dsv.tables"] = "mine.csv";  // given: none made
  EXPECT_TRUE(sr::turning_tables_command(s, "", "/b", "/r/t.csv").empty());
}

TEST(Runner, HilLaunchFileAddsGpsdAndTheBridgeOnTheDomainsPorts) {
  sr::RunOptions o;
  o.hil = true;
  o.realtime_factor = 20;
  sr::LaunchContext ctx;
  ctx.root = true;
  const std::string y = sr::launch_file(scenario(), "/w/world.yaml", o, 5, {}, ctx);
  const auto c = components(y);
  const sr::HilPorts hp(5);
  EXPECT_EQ(hp.gpsd, 20050);
  EXPECT_EQ(c["ship_bridge"]["set"]["gpsd.port"].as<std::string>(), std::to_string(hp.gpsd));
  EXPECT_EQ(c["ship_bridge"]["set"]["own.mmsi"].as<std::string>(), std::to_string(sr::kHilOwnMmsi));
  EXPECT_EQ(c["ship_simulator"]["set"]["time.mode"].as<std::string>(), "factor");
  EXPECT_EQ(c["ship_simulator"]["set"]["hil.ais_port"].as<std::string>(), std::to_string(hp.ais));
  EXPECT_EQ(c["gpsd"]["executable"].as<std::string>(), "runuser");  // never gpsd as root
  EXPECT_FALSE(c["opp"]["set"]["plan.time_budget"]);
  EXPECT_NE(sr::world_file(scenario(), true).find(std::to_string(sr::kHilOwnMmsi)), std::string::npos);
  EXPECT_EQ(sr::world_file(scenario(), false).find(std::to_string(sr::kHilOwnMmsi)), std::string::npos);
}

TEST(Runner, OptionsNeedHostsForNetworkFlagsAndSetTheDefaults) {
  sr::RunOptions o;
  o.hil = true;
  sr::RunCommandLine cl;
  cl.late_plans = true;
  sr::resolve_options(o, cl);
  EXPECT_DOUBLE_EQ(o.realtime_factor, sr::kHilFactor);
  EXPECT_DOUBLE_EQ(o.plan_latency, 25e-6);
  cl.cuts = {"autonomy@10+5"};
  EXPECT_THROW(sr::resolve_options(o, cl), std::invalid_argument);
  sr::RunOptions c;
  c.containers = true;
  EXPECT_THROW(sr::resolve_options(c, {}), std::invalid_argument);
}

// The recorder takes every topic but the lockstep's acknowledgements (sim/faults too, except on a
// secured bus, which grants it to nobody); --no-record (record = false) launches no recorder.
TEST(Runner, TheRecorderTakesEveryTopicButTheAcksAndNoRecordLaunchesNone) {
  auto topics = [](const sr::RunOptions& o) {
    return components(sr::launch_file(scenario(), "/run/x/world.yaml", o, 3, {}, {}))["recorder"]["set"]["record.topics"]
        .as<std::string>();
  };
  const std::string open = "," + topics(sr::RunOptions{}) + ",";
  EXPECT_EQ(open.find(",clock/ack,"), std::string::npos);
  EXPECT_NE(open.find(",clock,"), std::string::npos);
  EXPECT_NE(open.find(",nav/own_state,"), std::string::npos);
  EXPECT_NE(open.find(",sim/faults,"), std::string::npos);
  sr::RunOptions secure;
  secure.secure = "/pki";
  EXPECT_EQ(("," + topics(secure) + ",").find(",sim/faults,"), std::string::npos);
  sr::RunOptions none;
  none.record = false;
  const auto c = components(sr::launch_file(scenario(), "/run/x/world.yaml", none, 3, {}, {}));
  EXPECT_EQ(c.size(), 5u);
  EXPECT_FALSE(c["recorder"]);
}

// --view: the recorder serves the live view on loopback, at a real-time factor unless one is given.
TEST(Runner, ViewServesTheLiveViewFromTheRecorderAtARealtimeFactor) {
  sr::RunOptions o;
  sr::RunCommandLine cl;
  cl.view = true;
  sr::resolve_options(o, cl);
  EXPECT_EQ(o.view_port, sr::kViewPort);
  EXPECT_DOUBLE_EQ(o.realtime_factor, sr::kViewFactor);
  const auto c = components(sr::launch_file(scenario(), "/run/x/world.yaml", o, 3, {}, {}));
  EXPECT_EQ(c["recorder"]["set"]["live.port"].as<std::string>(), "8765");
  EXPECT_FALSE(components(sr::launch_file(scenario(), "/run/x/world.yaml", sr::RunOptions{}, 3, {}, {}))["recorder"]["set"]["live.port"]);
  sr::RunOptions f;
  f.realtime_factor = 2;
  sr::resolve_options(f, cl);
  EXPECT_DOUBLE_EQ(f.realtime_factor, 2);  // the one given
  cl.hosts_file = "deploy/hosts/x.yaml";
  sr::RunOptions h;
  EXPECT_THROW(sr::resolve_options(h, cl), std::invalid_argument);  // the recorder in a namespace: not reachable
}

TEST(Runner, SuiteFilesAreSortedAndAMissingFolderIsAnError) {
  const fs::path d = fs::temp_directory_path() / ("mpgc_runner_suite_" + std::to_string(::getpid()));
  fs::create_directories(d / "paper");
  for (const char* f : {"b.yaml", "a.yaml", "c.txt"}) std::ofstream(d / "paper" / f) << "x";
  const auto files = sr::scenario_files({"first.yaml"}, "paper", d.string(), d.string());
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0], "first.yaml");
  EXPECT_EQ(fs::path(files[1]).filename(), "a.yaml");
  EXPECT_EQ(fs::path(files[2]).filename(), "b.yaml");
  EXPECT_EQ(sr::scenario_files({}, "", d.string(), d.string()), std::vector<std::string>{(d / "paper" / "s1_colreg.yaml").string()});
  EXPECT_THROW(sr::scenario_files({}, "dnv", d.string(), d.string()), std::invalid_argument);
  fs::remove_all(d);
}

TEST(Runner, RecorderFixesTheSceneAndEndsAtTheGoalOrTheTimeLimit) {
  const sr::Scenario s = scenario();
  sr::RunRecorder rec(s, {});
  EXPECT_TRUE(rec.fresh(0));
  const sr::RunRecorder::Ship own{0, 0, {0, 0, 0, 0, 5}};
  const auto d = rec.record(1, own, {{4, 0, {500, 0, 0, 0, 0}}});
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(*d, 1000);
  EXPECT_DOUBLE_EQ(rec.run().own.length, 200);        // unknown: the scenario's Lpp
  EXPECT_DOUBLE_EQ(rec.run().targets[0].length, 100);
  EXPECT_EQ(rec.run().targets[0].id, 4u);
  EXPECT_FALSE(rec.fresh(1));
  EXPECT_FALSE(rec.record(2, own, {}));               // another scene: dropped
  EXPECT_EQ(rec.run().t.size(), 1u);
  EXPECT_EQ(rec.end_reason(2, 900), "");
  EXPECT_EQ(rec.end_reason(2, 50), "goal reached");
  EXPECT_EQ(rec.end_reason(600, 900), "time limit");
}

TEST(Runner, RecorderTakesPlansInOrderAndAShortPlanIsNoPath) {
  sr::RunRecorder rec(scenario(), {});
  sr::PlanRecord p;
  p.t = 5;
  p.status = sr::PlanStatus::kOk;
  p.waypoints = {{0, 0, 0}};
  rec.plan(p);
  ASSERT_EQ(rec.run().plans.size(), 1u);
  EXPECT_EQ(rec.run().plans[0].status, sr::PlanStatus::kNoPath);
  p.t = 4;
  rec.plan(p);  // older than the last
  EXPECT_EQ(rec.run().plans.size(), 1u);
  rec.guidance({3, 1, 0, 0});
  rec.guidance({3, 1, 1, 0});  // same time: dropped
  EXPECT_EQ(rec.run().guidance.size(), 1u);
  EXPECT_EQ(sr::plans_between(rec.run(), 4, 6), 1);
  EXPECT_EQ(sr::plans_between(rec.run(), 5, 6), 0);
}

TEST(Runner, HealthNewsSaysDownAndBackButNotTheFirstUp) {
  sr::HealthNews h({"opp"}, 0);
  bool restarted = true;
  EXPECT_TRUE(h.sample("opp", 1, mpgc::rt::Reported::kOk, "", 1'000'000'000, &restarted).empty());
  EXPECT_FALSE(restarted);
  h.killed("opp", 2'000'000'000);
  EXPECT_EQ(h.changes(2'000'000'000), std::vector<std::string>{"health: opp down: killed (fault injected)"});
  h.sample("opp", 1, mpgc::rt::Reported::kOk, "", 3'000'000'000, &restarted);
  EXPECT_FALSE(restarted);  // the same seq is no new process
  const auto again = h.sample("opp", 0, mpgc::rt::Reported::kOk, "", 4'000'000'000, &restarted);
  EXPECT_TRUE(restarted);
  ASSERT_FALSE(again.empty());
  EXPECT_EQ(again[0], "health: opp is back (a new process)");
  EXPECT_TRUE(h.sample("stranger", 0, mpgc::rt::Reported::kDegraded, "x", 4'000'000'000, nullptr).empty());
}

TEST(Runner, CutsBeginOnSimulatedTimeAndEndOnWallTime) {
  sr::CutSchedule cuts({{"autonomy", 10, 2}, {"bridge", 1000, 1}});
  EXPECT_TRUE(cuts.begin(5, 0).empty());
  ASSERT_EQ(cuts.begin(10, 1).size(), 1u);
  EXPECT_TRUE(cuts.begin(11, 1.5).empty());  // once
  EXPECT_TRUE(cuts.end(2.5, 11).empty());
  ASSERT_EQ(cuts.end(3, 12).size(), 1u);
  EXPECT_DOUBLE_EQ(cuts.cuts()[0].sim_end, 12);
  EXPECT_TRUE(cuts.end_all(20).empty());
  sr::RunRecord run;
  const auto notes = sr::network_notes(cuts.cuts(), run, {{"autonomy", "netem: 3 dropped"}});
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(notes[0], "cut autonomy at sim 10 s for 2.0 s wall (sim 10-12 s): 0 plans arrived meanwhile");
  EXPECT_EQ(notes[1], "cut bridge at sim 1000 s never happened (run ended first)");
  EXPECT_EQ(notes[2], "autonomy: netem: 3 dropped");
}

TEST(Runner, SummaryCountsFailuresAndErrors) {
  std::vector<std::pair<std::string, sr::Outcome>> r(2);
  r[0].first = "good";
  r[0].second.ran = true;
  r[0].second.metrics.passed = true;
  r[0].second.metrics.goal_reached = true;
  r[0].second.metrics.min_distance = 930.4;
  r[1].first = "bad";
  r[1].second.error = "run aborted";
  const std::string t = sr::summary(r, "out");
  EXPECT_NE(t.find("good                           pass   yes         930"), std::string::npos) << t;
  EXPECT_NE(t.find("bad                            ERROR  run aborted\n"), std::string::npos) << t;
  EXPECT_NE(t.find("1 passed, 1 failed   (outputs in out/<scenario>/"), std::string::npos) << t;
  EXPECT_EQ(sr::num_text(std::nan("")), "-");
  EXPECT_EQ(sr::num_text(2.25, "%.1f"), "2.2");
  EXPECT_EQ(sr::progress_line("s", 12, 345, 3, 1.5), "  s                            sim     12 s  to goal     345 m  plans   3  wall   1.5 s\n");
}

}  // namespace
