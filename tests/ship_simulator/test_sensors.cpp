// Sensors, targets and the world: noise statistics, AIS reporting intervals, radar detection,
// scripted target manoeuvres, world file parsing and bit-for-bit determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "mpgc/geo/angles.hpp"
#include "mpgc/ship_simulator/sensors.hpp"
#include "mpgc/ship_simulator/targets.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/testing.hpp"

namespace sim = mpgc::ship_simulator;
namespace geo = mpgc::geo;

namespace {
struct Stats {
  double n = 0, s = 0, s2 = 0;
  void add(double v) {
    n += 1;
    s += v;
    s2 += v * v;
  }
  double mean() const { return s / n; }
  double std() const { return std::sqrt(s2 / n - mean() * mean()); }
};

std::string world_yaml(uint64_t seed) {
  return R"(
origin: {lat_deg: 38.95, lon_deg: -76.45}
seed: )" + std::to_string(seed) + R"(
own_ship: {model: nomoto, data_dir: ")" + mpgc::testing::shared_data("ship_models") + R"(", heading_deg: 45, speed_kn: 12}
targets:
  - {mmsi: 257000001, x_m: 3000, y_m: 3000, course_deg: 225, speed_kn: 10,
     max_turn_rate_deg_s: 2, manoeuvres: [{at_s: 20, course_deg: 180}]}
  - {mmsi: 257000002, lat_deg: 38.97, lon_deg: -76.44, speed_kn: 18,
     legs: [{course_deg: 90, speed_kn: 18, duration_s: 10}, {course_deg: 0, speed_kn: 18}]}
sensors:
  radar: {period_s: 1.0, clutter_per_scan: 2}
)";
}
}  // namespace

TEST(NavSensor, NoiseStatisticsMatchTheConfiguration) {
  sim::NavSensorConfig c;
  c.sigma_position = 2.0;
  c.sigma_heading = geo::deg2rad(0.5);
  c.sigma_sog = 0.1;
  c.seed = 1234;
  sim::NavSensor s(c);
  const sim::Kinematics truth{100.0, -50.0, 0.3, 0.35, 7.0, 0.001};
  Stats x, y, h, v;
  const int N = 20000;
  for (int i = 0; i < N; ++i) {
    const auto m = s.measure(truth);
    x.add(m.x - truth.x);
    y.add(m.y - truth.y);
    h.add(geo::angle_diff(m.heading, truth.heading));
    v.add(m.sog - truth.sog);
  }
  // Mean within 4 standard errors, standard deviation within 3 %.
  EXPECT_NEAR(x.mean(), 0.0, 4 * 2.0 / std::sqrt(N));
  EXPECT_NEAR(y.mean(), 0.0, 4 * 2.0 / std::sqrt(N));
  EXPECT_NEAR(x.std(), 2.0, 0.06);
  EXPECT_NEAR(y.std(), 2.0, 0.06);
  EXPECT_NEAR(h.std(), geo::deg2rad(0.5), geo::deg2rad(0.5) * 0.03);
  EXPECT_NEAR(v.std(), 0.1, 0.003);
  // same seed, same samples
  sim::NavSensor a(c), b(c);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.measure(truth).x, b.measure(truth).x);
  c.sigma_position = -1.0;
  EXPECT_THROW(sim::NavSensor{c}, std::invalid_argument);
}

TEST(Ais, ClassAReportingIntervalsFollowItuRM1371) {
  const double kn = geo::kKnot;
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(0.0 * kn, false, 1), 180.0);   // at anchor
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(2.0 * kn, false, 5), 180.0);   // moored
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(5.0 * kn, false, 1), 10.0);    // anchored but moving > 3 kn
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(0.0 * kn, false, 0), 10.0);    // under way, stopped
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(10.0 * kn, false, 0), 10.0);
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(10.0 * kn, true, 0), 10.0 / 3.0);
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(18.0 * kn, false, 0), 6.0);
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(18.0 * kn, true, 0), 2.0);
  EXPECT_DOUBLE_EQ(sim::ais_class_a_interval(25.0 * kn, false, 0), 2.0);
}

TEST(Ais, TransmitterKeepsTheIntervalAndShortensItWhenTurning) {
  sim::AisConfig c;
  c.seed = 7;
  sim::AisTransmitter tx(257000001, 0, c, 1);
  sim::Kinematics k{0, 0, 0, 0, 10.0 * geo::kKnot, 0.0};
  std::vector<int64_t> times;
  const int64_t dt = 100'000'000;  // 0.1 s steps
  for (int64_t t = 0; t <= 200'000'000'000; t += dt) {
    k.rot = t >= 100'000'000'000 ? geo::deg2rad(0.5) : 0.0;  // starts turning at 100 s
    sim::AisMeasurement m{};
    if (tx.poll(t, k, &m)) {
      EXPECT_EQ(m.mmsi, 257000001u);
      EXPECT_EQ(m.report_time_ns, t);
      times.push_back(t);
    }
  }
  ASSERT_GT(times.size(), 20u);
  EXPECT_LT(times.front(), 10'000'000'000);  // random phase within the first interval
  int straight = 0, turning = 0;
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double gap = (times[i] - times[i - 1]) * 1e-9;
    if (times[i] < 100'000'000'000) {
      EXPECT_NEAR(gap, 10.0, 1e-9);
      ++straight;
    } else if (times[i - 1] >= 100'000'000'000) {
      EXPECT_NEAR(gap, 3.4, 0.051);  // 3 1/3 s rounded up to the 0.1 s step
      ++turning;
    }
  }
  EXPECT_GE(straight, 8);
  EXPECT_GE(turning, 25);
}

TEST(Ais, PositionNoiseAndDrops) {
  sim::AisConfig c;
  c.sigma_position = 10.0;
  c.drop_probability = 0.2;
  c.seed = 99;
  sim::AisTransmitter tx(257000009, 0, c, 3);
  const sim::Kinematics k{500, 500, 0, 0, 30.0 * geo::kKnot, 0};  // 2 s interval
  Stats e;
  int reports = 0, polls = 0;
  for (int64_t t = 0; t < 40'000'000'000'000LL; t += 2'000'000'000) {
    sim::AisMeasurement m{};
    ++polls;
    if (tx.poll(t, k, &m)) {
      ++reports;
      e.add(m.x - 500.0);
    }
  }
  EXPECT_NEAR(e.std(), 10.0, 0.5);
  EXPECT_NEAR(e.mean(), 0.0, 0.5);
  EXPECT_NEAR(static_cast<double>(tx.dropped()) / (reports + tx.dropped()), 0.2, 0.02);
  EXPECT_GT(polls, reports);
}

TEST(Radar, DetectionRangeNoiseAndClutter) {
  sim::RadarConfig c;
  c.max_range = 10000.0;
  c.detection_probability = 0.8;
  c.sigma_range = 20.0;
  c.sigma_bearing = geo::deg2rad(1.0);
  c.clutter_per_scan = 1.5;
  c.seed = 5;
  sim::RadarSensor r(c);
  const std::vector<sim::Kinematics> targets = {{3000, 4000, 0, 0, 5, 0}, {20000, 0, 0, 0, 5, 0}};
  Stats range, brg, clutter;
  int detected = 0;
  const int N = 5000;
  for (int i = 0; i < N; ++i) {
    const auto cs = r.sweep(0.0, 0.0, targets);
    int nc = 0;
    for (const auto& k : cs) {
      EXPECT_LE(k.range, c.max_range + 100.0);
      if (k.clutter) {
        ++nc;
        continue;
      }
      ++detected;
      range.add(k.range - 5000.0);
      brg.add(geo::angle_diff(k.bearing, std::atan2(4000.0, 3000.0)));
    }
    clutter.add(nc);
  }
  EXPECT_NEAR(static_cast<double>(detected) / N, 0.8, 0.02);  // the far target is never seen
  EXPECT_NEAR(range.std(), 20.0, 0.8);
  EXPECT_NEAR(range.mean(), 0.0, 1.5);
  EXPECT_NEAR(brg.std(), geo::deg2rad(1.0), geo::deg2rad(0.04));
  EXPECT_NEAR(clutter.mean(), 1.5, 0.06);
}

TEST(Targets, LegsManoeuvresAndWaypoints) {
  sim::TargetConfig c;
  c.mmsi = 257000003;
  c.speed0 = 5.0;
  c.max_turn_rate = geo::deg2rad(1.0);
  c.max_accel = 0.1;
  c.waypoint_radius = 50.0;
  c.length = 100;
  c.beam = 20;
  c.legs = {{0.0, 5.0, 100.0}, {geo::deg2rad(90.0), 5.0, 0.0}};
  c.manoeuvres = {{300.0, geo::deg2rad(180.0), 2.0, 100.0}};
  sim::TargetShip t(c);
  double course = 0, speed = 0;
  for (int k = 0; k < 5000; ++k) {
    const double time = k * 0.1;
    t.step(time, 0.1);
    EXPECT_LE(std::abs(t.state().rot), geo::deg2rad(1.0) + 1e-12);
    if (k == 999) {
      EXPECT_NEAR(t.state().course, 0.0, 1e-12);  // still first leg at 100 s
    }
    if (k == 2500) {
      EXPECT_NEAR(t.state().course, geo::deg2rad(90.0), 1e-9);  // second leg after the turn
    }
    if (k == 3990) {  // inside the manoeuvre window 300..400 s
      EXPECT_NEAR(t.state().course, geo::deg2rad(180.0), 1e-9);
      EXPECT_NEAR(t.state().speed, 2.0, 1e-9);
    }
  }
  t.ordered(450.0, &course, &speed);  // after the manoeuvre: back to the route
  EXPECT_NEAR(course, geo::deg2rad(90.0), 1e-12);
  EXPECT_NEAR(speed, 5.0, 1e-12);

  sim::TargetConfig w = c;
  w.legs.clear();
  w.manoeuvres.clear();
  w.waypoints = {{1000.0, 0.0, 5.0}, {1000.0, 1000.0, 5.0}};
  sim::TargetShip tw(w);
  double d1 = 1e9, d2 = 1e9;  // closest approach to each waypoint
  for (int k = 0; k < 6000; ++k) {
    tw.step(k * 0.1, 0.1);
    d1 = std::min(d1, std::hypot(tw.state().x - 1000.0, tw.state().y));
    d2 = std::min(d2, std::hypot(tw.state().x - 1000.0, tw.state().y - 1000.0));
  }
  EXPECT_LT(d1, 50.0);
  EXPECT_LT(d2, 50.0);

  sim::TargetConfig bad = c;
  bad.mmsi = 12;
  EXPECT_THROW(sim::TargetShip{bad}, std::invalid_argument);
  bad = c;
  bad.legs[0].speed = std::nan("");
  EXPECT_THROW(sim::TargetShip{bad}, std::invalid_argument);
}

TEST(WorldConfig, ParsesAndNamesBadKeys) {
  const auto c = sim::WorldConfig::from_yaml(world_yaml(3));
  ASSERT_EQ(c.targets.size(), 2u);
  EXPECT_NEAR(c.targets[1].x0, (38.97 - 38.95) * 111000.0, 300.0);  // lat/lon converted to NED
  EXPECT_EQ(c.model.kind, "nomoto");
  auto expect_error = [](const std::string& yaml, const std::string& needle) {
    try {
      sim::WorldConfig::from_yaml(yaml, "w.yaml");
      ADD_FAILURE() << "accepted: " << yaml;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\nbogus: 1\n", "bogus");
  expect_error("origin: {lat_deg: 1}\n", "origin.lon_deg");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\nown_ship: {speed_kn: .nan}\n", "own_ship.speed_kn");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\ntargets: [{mmsi: 257000001}]\n", "targets[0]");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\ntargets: [{mmsi: 25, x_m: 0, y_m: 0}]\n", "targets[0].mmsi");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\nsensors: {radar: {detection_probability: 2}}\n",
               "sensors.radar.detection_probability");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\nown_ship: {model: mmg, length_m: 122}\n", "own_ship.length_m");
  expect_error("origin: {lat_deg: 1, lon_deg: 2}\nown_ship: {model: nomoto, length_m: 5000}\n", "own_ship.length_m");
  const auto small = sim::WorldConfig::from_yaml("origin: {lat_deg: 1, lon_deg: 2}\nown_ship: {model: nomoto, length_m: 122, beam_m: 20}\n");
  EXPECT_EQ(small.model.length, 122.0);
  EXPECT_EQ(small.model.beam, 20.0);
  expect_error("origin: [1, 2\n", "malformed");
  EXPECT_THROW(sim::WorldConfig::from_file("/nonexistent/world.yaml"), std::runtime_error);
}

namespace {
// Everything the world produced over a run, flattened to doubles.
std::vector<double> run_world(uint64_t seed) {
  sim::World w(sim::WorldConfig::from_yaml(world_yaml(seed)), 100'000'000);
  std::vector<double> out;
  sim::ShipCommand cmd = w.initial_command();
  for (int k = 0; k < 600; ++k) {
    const auto s = w.sense();
    if (s.nav) out.insert(out.end(), {s.nav->x, s.nav->y, s.nav->heading, s.nav->sog});
    for (const auto& a : s.ais) out.insert(out.end(), {double(a.mmsi), a.x, a.y, a.cog, a.sog});
    if (s.radar)
      for (const auto& c : s.radar->contacts) out.insert(out.end(), {c.range, c.bearing});
    for (const auto& t : w.target_truth()) out.insert(out.end(), {t.x, t.y, t.heading});
    const auto& o = w.own().state();
    out.insert(out.end(), {o.x, o.y, o.psi, o.u, o.v, o.r, o.rudder, o.rpm});
    cmd.rudder = k > 100 ? geo::deg2rad(10.0) : 0.0;
    w.step(cmd);
  }
  return out;
}
}  // namespace

TEST(World, SameSeedSameRunBitForBit) {
  const auto a = run_world(42), b = run_world(42), c = run_world(43);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(double)));
  EXPECT_NE(a, c);  // another seed, other noise
}

TEST(World, TargetsAndSensorsMoveWithTime) {
  sim::World w(sim::WorldConfig::from_yaml(world_yaml(1)), 100'000'000);
  int nav = 0, radar = 0;
  std::size_t ais = 0;
  for (int k = 0; k < 600; ++k) {  // 60 s
    const auto s = w.sense();
    nav += s.nav ? 1 : 0;
    radar += s.radar ? 1 : 0;
    ais += s.ais.size();
    w.step(w.initial_command());
  }
  EXPECT_EQ(w.time_ns(), 60'000'000'000);
  EXPECT_EQ(nav, 600);   // 10 Hz
  EXPECT_EQ(radar, 60);  // 1 s sweeps
  EXPECT_GE(ais, 2u * 5u);
  const auto t = w.target_truth();
  EXPECT_NEAR(t[0].heading, geo::deg2rad(180.0), 1e-9);  // the scripted turn at 20 s
  EXPECT_NEAR(t[1].heading, 0.0, 1e-9);                  // second leg after 10 s
  EXPECT_NEAR(w.own_truth().heading, geo::deg2rad(45.0), 1e-9);
}
