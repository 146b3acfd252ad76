// The step journal: a simulator killed mid-run resumes with the world exactly where it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "mpgc/ship_simulator/sensor_faults.hpp"
#include "mpgc/ship_simulator/step_log.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/testing.hpp"

namespace sim = mpgc::ship_simulator;

namespace {
std::string world_yaml() {
  return R"(
origin: {lat_deg: 38.95, lon_deg: -76.45}
seed: 7
own_ship: {model: nomoto, data_dir: ")" + mpgc::testing::shared_data("ship_models") + R"(", heading_deg: 45, speed_kn: 12}
targets:
  - {mmsi: 257000001, x_m: 3000, y_m: 3000, course_deg: 225, speed_kn: 10, manoeuvres: [{at_s: 20, course_deg: 180}]}
sensors:
  radar: {period_s: 1.0, clutter_per_scan: 2}
)";
}
std::string temp_path() {
  return ::testing::TempDir() + "/step_log_" + std::to_string(getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}
sim::ShipCommand order(int k) { return {0.3 * std::sin(k * 0.01), 80.0 + (k % 50)}; }
}  // namespace

TEST(StepLog, AKilledSimulatorResumesTheWorldBitForBit) {
  const std::string path = temp_path();
  std::remove(path.c_str());
  const auto cfg = sim::WorldConfig::from_yaml(world_yaml());
  sim::World uninterrupted(cfg, 100'000'000);
  sim::World first(cfg, 100'000'000);
  {
    sim::StepLog log(path);
    EXPECT_EQ(log.steps(), 0u);
    for (int k = 0; k < 900; ++k) {
      uninterrupted.sense(), first.sense();
      log.append(order(k));
      uninterrupted.step(order(k)), first.step(order(k));
    }
  }  // killed here
  std::ofstream(path, std::ios::app) << "torn";  // a record cut short by the kill
  sim::World resumed(cfg, 100'000'000);
  sim::StepLog log(path);
  EXPECT_EQ(log.steps(), 900u);
  const sim::ShipCommand held = sim::replay(resumed, log.take_commands(), {});
  EXPECT_EQ(held.rudder, order(899).rudder);
  for (int k = 900; k < 1000; ++k) {
    const auto a = uninterrupted.sense(), b = resumed.sense();
    ASSERT_EQ(a.nav.has_value(), b.nav.has_value());
    if (a.nav) {
      EXPECT_EQ(a.nav->x, b.nav->x) << "sensor noise stream at step " << k;
    }
    ASSERT_EQ(a.radar.has_value(), b.radar.has_value());
    if (a.radar) {
      EXPECT_EQ(a.radar->contacts.size(), b.radar->contacts.size());
    }
    log.append(order(k));
    uninterrupted.step(order(k)), resumed.step(order(k));
  }
  EXPECT_EQ(resumed.time_ns(), uninterrupted.time_ns());
  const auto u = uninterrupted.own().state().to_array(), r = resumed.own().state().to_array();
  for (size_t i = 0; i < u.size(); ++i) EXPECT_EQ(u[i], r[i]) << "own-ship state " << i;
  EXPECT_EQ(resumed.target_truth()[0].x, uninterrupted.target_truth()[0].x);
  std::remove(path.c_str());
}

TEST(StepLog, AJournalOfAnotherRunIsRefusedByName) {
  const std::string path = temp_path();
  {
    std::ofstream f(path, std::ios::binary);
    const uint64_t step = 5;  // the first record must be step 0
    const double v[2] = {0.0, 10.0};
    f.write(reinterpret_cast<const char*>(&step), 8);
    f.write(reinterpret_cast<const char*>(v), 16);
  }
  try {
    sim::StepLog log(path);
    FAIL() << "accepted a journal that starts at step 5";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
  EXPECT_THROW(sim::StepLog("/nonexistent-dir/journal"), std::runtime_error);
}

TEST(SensorFaults, OutageDropoutAndJumpChangeOnlyTheirWindow) {
  sim::SensorFaults f;
  f.add({sim::SensorFaults::Kind::kAisOutage, 10, 20, 257000001});
  f.add({sim::SensorFaults::Kind::kGnssDropout, 30, 40});
  f.add({sim::SensorFaults::Kind::kPositionJump, 50, 60, 0, 200.0, -50.0});
  EXPECT_THROW(f.add({sim::SensorFaults::Kind::kGnssDropout, 5, 5}), std::invalid_argument);
  EXPECT_THROW(f.add({sim::SensorFaults::Kind::kPositionJump, 0, 5, 0, std::nan(""), 0}), std::invalid_argument);
  auto outputs = [] {
    sim::SensorOutputs o;
    o.nav = sim::NavMeasurement{1, 2, 0, 0, 5, 0};
    o.ais.push_back({257000001, 0, 0, 0, 0, 0, 0, 0, 0});
    o.ais.push_back({257000002, 0, 0, 0, 0, 0, 0, 0, 0});
    return o;
  };
  auto o = outputs();
  EXPECT_EQ(f.apply(9, &o), 0);
  o = outputs();
  EXPECT_EQ(f.apply(10, &o), 1);
  ASSERT_EQ(o.ais.size(), 1u);
  EXPECT_EQ(o.ais[0].mmsi, 257000002u);
  o = outputs();
  EXPECT_EQ(f.apply(35, &o), 1);
  EXPECT_FALSE(o.nav.has_value());
  o = outputs();
  EXPECT_EQ(f.apply(59, &o), 1);
  EXPECT_EQ(o.nav->x, 201.0);
  EXPECT_EQ(o.nav->y, -48.0);
  o = outputs();
  EXPECT_EQ(f.apply(60, &o), 0);  // the window is [from, until)
}
