// The simulator component's logic without DDS or a clock (node.hpp): what main.cpp used to do
// inline, tested here directly.
#include <gtest/gtest.h>

#include <cmath>

#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/node.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/testing_params.hpp"

namespace sim = mpgc::ship_simulator;

namespace {

std::string world_yaml(const std::string& targets = "") {
  return "origin: {lat_deg: 38.95, lon_deg: -76.45}\nown_ship: {model: nomoto, data_dir: \"" +
         mpgc::testing::shared_data("ship_models") + "\", speed_kn: 12}\n" + targets;
}

sim::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  return mpgc::testing::declared<sim::NodeParams>(sim::declare, overrides);
}

TEST(SimNode, ParametersHaveTheirDefaultsAndAWorldFileIsRequired) {
  const sim::NodeParams p = declared();
  EXPECT_EQ(p.mode, "realtime");
  EXPECT_FALSE(p.lockstep());
  EXPECT_EQ(p.step_ns(), 100'000'000);
  EXPECT_EQ(p.watchdog_engine, "reduce");
  EXPECT_THROW(sim::validate(p), std::invalid_argument);
  const sim::NodeParams f = declared({"time.mode=factor", "time.factor=4", "time.duration=2", "world.file=w.yaml"});
  EXPECT_NO_THROW(sim::validate(f));
  EXPECT_DOUBLE_EQ(f.wall_per_sim(), 0.25);
  EXPECT_FALSE(f.finished(1'999'999'999));
  EXPECT_TRUE(f.finished(2'000'000'000));
  EXPECT_FALSE(p.finished(1'000'000'000'000));  // duration 0: never
}

TEST(SimNode, WatchdogSaysWhenItTripsAndWhenOrdersComeAgain) {
  const sim::WorldConfig cfg = sim::WorldConfig::from_yaml(world_yaml());
  sim::World world(cfg, 100'000'000);
  const sim::NodeParams p = declared({"watchdog.timeout=2"});
  sim::ActuatorWatchdog wd(sim::watchdog_params(p, world.own()));
  EXPECT_DOUBLE_EQ(wd.params().timeout_s, 2.0);
  EXPECT_NE(wd.engine_safe().find("engine to at most "), std::string::npos);
  sim::DeviceOrders o{0.1, 50, true, true, 0};
  sim::ShipCommand cmd{};
  EXPECT_FALSE(wd.update(o, 1'000'000'000, &cmd));  // orders in time: nothing to say
  const auto trip = wd.update(o, 2'500'000'000, &cmd);
  ASSERT_TRUE(trip);
  EXPECT_TRUE(trip->tripped);
  EXPECT_EQ(trip->text.rfind("actuator watchdog: no order for 2.5 s, rudder amidships, engine to at most ", 0), 0u);
  EXPECT_DOUBLE_EQ(cmd.rudder, 0.0);
  EXPECT_FALSE(wd.update(o, 3'000'000'000, &cmd));  // still tripped: said once
  o.rudder_ns = 3'000'000'000;
  const auto back = wd.update(o, 3'100'000'000, &cmd);
  ASSERT_TRUE(back);
  EXPECT_FALSE(back->tripped);
  EXPECT_EQ(sim::ActuatorWatchdog(sim::watchdog_params(declared({"watchdog.engine=hold"}), world.own())).engine_safe(),
            "engine order held");
}

TEST(SimNode, TruthStaysOnItsGridAfterAResumeAndDevicesCountFromTheLastSent) {
  sim::OutputSchedule s(declared({"truth.period=1", "hil.gnss_period=0.5"}));
  EXPECT_TRUE(s.truth_due(0));
  EXPECT_FALSE(s.truth_due(900'000'000));
  EXPECT_TRUE(s.truth_due(1'000'000'000));
  s.resume(2'300'000'000);
  EXPECT_FALSE(s.truth_due(2'900'000'000));
  EXPECT_TRUE(s.truth_due(3'000'000'000));
  EXPECT_TRUE(s.gnss_due(100'000'000));
  EXPECT_FALSE(s.gnss_due(500'000'000));
  EXPECT_TRUE(s.gnss_due(600'000'000));
  EXPECT_TRUE(s.own_ais_due(0));
  EXPECT_FALSE(s.own_ais_due(9'999'999'999));
  EXPECT_TRUE(s.own_ais_due(10'000'000'000));
}

TEST(SimNode, LockstepStartsAfterSettlingDropsTheDeadAndResends) {
  const sim::NodeParams p = declared({"lockstep.start_settle=0.5", "lockstep.absent_after=0.5",
                                      "lockstep.ack_timeout=1", "lockstep.hang_timeout=3"});
  sim::LockstepBarrier b({"opp", "guidance_control"});
  sim::LockstepPacer pacer(p);
  EXPECT_DOUBLE_EQ(pacer.timer_period(), 0.05);
  using A = sim::LockstepPacer::Action;
  std::string why;
  const int64_t s = 1'000'000'000;
  EXPECT_EQ(pacer.tick(1 * s, false, 1, b, &why), A::kWait);     // one not up yet
  EXPECT_EQ(pacer.tick(2 * s, false, 2, b, &why), A::kWait);     // all up: discovery settles
  EXPECT_EQ(pacer.tick(2 * s + s / 2, false, 2, b, &why), A::kStart);
  b.begin(0);
  pacer.stepped(3 * s);
  EXPECT_EQ(pacer.tick(3 * s + s / 2, true, 2, b, &why), A::kWait);
  EXPECT_EQ(pacer.tick(4 * s + s / 10, true, 2, b, &why), A::kResend);  // ack_timeout without progress
  pacer.resent(4 * s + s / 10);
  EXPECT_EQ(pacer.tick(4 * s + s / 5, true, 2, b, &why), A::kWait);
  EXPECT_EQ(pacer.tick(4 * s, true, 1, b, &why), A::kDrop);  // one writer lost
  EXPECT_EQ(why, "liveliness lost");
  EXPECT_EQ(pacer.tick(6 * s + 1, true, 2, b, &why), A::kDrop);  // alive but silent
  EXPECT_EQ(why, "no ack within lockstep.hang_timeout");
  b.ack("opp", 0);
  EXPECT_EQ(b.drop_missing(), std::vector<std::string>{"guidance_control"});
  EXPECT_TRUE(b.complete());
  EXPECT_EQ(sim::lockstep_problem(b, "liveliness lost"), "lockstep without [guidance_control] (liveliness lost)");
  EXPECT_EQ(sim::join_names(std::vector<std::string>{"a", "b"}), "a, b");
}

TEST(SimNode, TargetsAreFoundByMmsi) {
  const sim::WorldConfig cfg = sim::WorldConfig::from_yaml(
      world_yaml("targets:\n  - {mmsi: 257000001, x_m: 1000, y_m: 0, course_deg: 0, speed_kn: 5}\n"));
  EXPECT_EQ(cfg.target(257000001).mmsi, 257000001u);
  EXPECT_THROW(cfg.target(1), std::out_of_range);
}

}  // namespace
