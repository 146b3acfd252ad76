// The runner's fault bookkeeping (fault_run.hpp) with fake processes: what is signalled when, what
// each FaultRecord says, and when a component counts as back.
#include <gtest/gtest.h>

#include <signal.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "mpgc/scenario_runner/fault_run.hpp"

namespace sr = mpgc::scenario_runner;

namespace {

sr::Fault fault(sr::Fault::Kind k, double at, const std::string& component, double duration = 0.0) {
  sr::Fault f;
  f.kind = k;
  f.at_s = at;
  f.component = component;
  f.duration_s = duration;
  if (k == sr::Fault::Kind::kSilence) f.topic = "sensors/ais";
  return f;
}

struct Fake {
  std::map<std::string, int> pids{{"opp", 101}, {"ship_simulator", 102}};
  std::vector<std::pair<int, int>> signals;
  std::vector<std::string> commands, killed, said;
  sr::FaultEffects fx() {
    sr::FaultEffects e;
    e.pid_of = [this](const std::string& c) { return pids.count(c) ? pids[c] : -1; };
    e.signal = [this](int pid, int sig) { signals.push_back({pid, sig}); };
    e.command = [this](const sr::Fault& f) { commands.push_back(f.topic); };
    e.killed = [this](const std::string& c) { killed.push_back(c); };
    e.say = [this](const std::string& s) { said.push_back(s); };
    return e;
  }
};

}  // namespace

TEST(FaultRun, KillIsSentWhenDueAndRecoveredByTheNextIncarnation) {
  Fake fake;
  sr::FaultRun run({fault(sr::Fault::Kind::kKill, 100, "opp"), fault(sr::Fault::Kind::kKill, 200, "guidance_control")},
                   fake.fx());
  run.at_sim(99.9, 1.0);
  EXPECT_TRUE(fake.signals.empty());
  run.at_sim(100.0, 2.0);
  ASSERT_EQ(fake.signals.size(), 1u);
  EXPECT_EQ(fake.signals[0], std::make_pair(101, SIGKILL));
  EXPECT_EQ(fake.killed, std::vector<std::string>{"opp"});
  run.on_health("opp", false, 100.1, 2.1);  // the old incarnation's last sample: not back
  EXPECT_TRUE(std::isnan(run.records()[0].t_recovered));
  run.on_health("opp", true, 100.2, 3.2);
  EXPECT_DOUBLE_EQ(run.records()[0].t, 100.0);
  EXPECT_DOUBLE_EQ(run.records()[0].t_recovered, 100.2);
  EXPECT_DOUBLE_EQ(run.records()[0].wall_recovery, 1.2);
  EXPECT_TRUE(run.records()[0].needs_recovery);
  // guidance_control is not running: the fault never happens, and says so.
  run.at_sim(250.0, 5.0);
  EXPECT_EQ(fake.signals.size(), 1u);
  EXPECT_TRUE(std::isnan(run.records()[1].t));
  EXPECT_NE(fake.said.back().find("not possible"), std::string::npos);
}

TEST(FaultRun, StopsLastInSimulatedTimeExceptTheSimulatorsInWallTime) {
  Fake fake;
  sr::FaultRun run({fault(sr::Fault::Kind::kStop, 10, "opp", 30), fault(sr::Fault::Kind::kStop, 20, "ship_simulator", 5)},
                   fake.fx());
  run.at_sim(10, 100.0);
  run.at_sim(20, 101.0);
  ASSERT_EQ(fake.signals.size(), 2u);
  EXPECT_EQ(fake.signals[1], std::make_pair(102, SIGSTOP));
  EXPECT_FALSE(run.at_wall(105.9, 20));  // the simulator's 5 s are wall seconds
  EXPECT_TRUE(run.at_wall(106.0, 20));
  EXPECT_EQ(fake.signals.back(), std::make_pair(102, SIGCONT));
  EXPECT_DOUBLE_EQ(run.records()[1].t_end, 20);
  run.on_health("ship_simulator", false, 20.1, 106.5);  // after SIGCONT any sample is the sign of life
  EXPECT_DOUBLE_EQ(run.records()[1].wall_recovery, 0.5);
  run.on_health("opp", false, 30, 107.0);  // still stopped: a sample from before is no recovery
  EXPECT_TRUE(std::isnan(run.records()[0].t_recovered));
  run.at_sim(39.9, 108.0);
  EXPECT_EQ(fake.signals.size(), 3u);
  run.at_sim(40.0, 109.0);
  EXPECT_EQ(fake.signals.back(), std::make_pair(101, SIGCONT));
  EXPECT_DOUBLE_EQ(run.records()[0].t_end, 40.0);
  run.on_health("opp", false, 40.5, 109.25);
  EXPECT_DOUBLE_EQ(run.records()[0].t_recovered, 40.5);
  EXPECT_DOUBLE_EQ(run.records()[0].wall_recovery, 0.25);
  run.release();  // nothing left stopped
  EXPECT_EQ(fake.signals.size(), 4u);
}

TEST(FaultRun, TimedFaultsGoOutAsCommandsAndReleaseContinuesWhatIsStillStopped) {
  Fake fake;
  sr::FaultRun run({fault(sr::Fault::Kind::kSilence, 5, "", 60), fault(sr::Fault::Kind::kStop, 6, "opp", 1000)}, fake.fx());
  run.at_sim(7, 1.0);  // both due in one step, in order
  EXPECT_EQ(fake.commands, std::vector<std::string>{"sensors/ais"});
  EXPECT_DOUBLE_EQ(run.records()[0].t, 7);
  EXPECT_DOUBLE_EQ(run.records()[0].t_end, 67);
  EXPECT_FALSE(run.records()[0].needs_recovery);
  EXPECT_EQ(run.records()[0].component, "");
  run.release();
  EXPECT_EQ(fake.signals.back(), std::make_pair(101, SIGCONT));
}
