// Integration over DDS (own domain, loopback): the real mpgc_obstacle_manager process loads the
// Annapolis crop; a reader that joins late still gets obstacles/fixed (transient-local); tracks
// come back as obstacles/moving.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/obstacle_manager/msg_convert.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/testing_dds.hpp"
#include "mpgc/topics.hpp"

extern char** environ;

namespace {

using mpgc::testing::Process;

using mpgc::testing::wait_for;

}  // namespace

TEST(ObstacleManagerProcess, LateJoinerGetsFixedObstaclesAndTracksBecomeMoving) {
  const int domain = mpgc::testing::unique_domain();
  Process proc({mpgc::testing::bin_dir() + "/mpgc_obstacle_manager", "--domain", std::to_string(domain), "--set",
                "chart.files=" + mpgc::testing::shared_data("chart/crop_annapolis_LNDARE.geojson"), "--set",
                "chart.origin_lat=38.965", "--set", "chart.origin_lon=-76.45", "--set", "region.half_size=0",
                "--set", "chart.shapes=circle 0 0 100", "--set", "moving.period=0.1",
                // No growth, so the values come back exactly (growth: test_obstacle_manager_logic).
                "--set", "tracks.speed_std=0", "--log-level", "warn"});
  mpgc::dds::Participant part(static_cast<uint32_t>(domain));
  // Join late: the component has loaded the chart and published before this reader exists.
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_TRUE(proc.running());
  mpgc::dds::Topic<mpgc::msg::FixedObstacles> fixed_topic(part, mpgc::topics::kFixedObstacles);
  mpgc::dds::Reader<mpgc::msg::FixedObstacles> fixed(part, fixed_topic, mpgc::dds::QosProfile::latched());
  mpgc::msg::FixedObstacles f;
  ASSERT_TRUE(wait_for(fixed, f, [](const auto&) { return true; }, 20.0));
  EXPECT_GE(f.version, 1u);
  EXPECT_GT(f.points.size(), 1000u);
  EXPECT_GT(f.polygons.size(), 5u);  // the crop's land rings plus the inline circle
  EXPECT_NEAR(f.origin_lat, 38.965 * M_PI / 180, 1e-12);
  EXPECT_EQ(f.point_spacing, 20.0);
  // The planner's path: message -> FixedObstacleMap. The inline circle at the origin is an obstacle;
  // the labelled land point (-76.48 E, 38.95 N) is about 2.6 km west and 1.7 km south.
  const auto map = mpgc::obstacle_manager::map_from_msg(f);
  EXPECT_TRUE(map.inside_land({0, 0}));
  EXPECT_FALSE(map.inside_land({0, 150}));

  mpgc::dds::Topic<mpgc::msg::TrackList> tracks_topic(part, mpgc::topics::kTracks);
  mpgc::dds::Writer<mpgc::msg::TrackList> tracks(part, tracks_topic, mpgc::dds::QosProfile::state());
  mpgc::dds::Topic<mpgc::msg::MovingObstacles> moving_topic(part, mpgc::topics::kMovingObstacles);
  mpgc::dds::Reader<mpgc::msg::MovingObstacles> moving(part, moving_topic, mpgc::dds::QosProfile::state());
  mpgc::msg::TrackList tl;
  // On the component's clock (wall): an older stamp would be a track aged out long ago.
  const int64_t stamp = dds_time();
  tl.header.stamp_ns = stamp;
  mpgc::msg::Track good{};
  good.id = 7;
  good.x = 500;
  good.y = 600;
  good.vx = 2;
  good.vy = -1;
  good.cov[0] = 25;
  good.cov[5] = 4;
  good.length = 100;
  good.status = mpgc::msg::TrackStatus::TRACK_CONFIRMED;
  mpgc::msg::Track bad = good;
  bad.id = 8;
  bad.x = NAN;
  mpgc::msg::Track gone = good;
  gone.id = 9;
  gone.status = mpgc::msg::TrackStatus::TRACK_DELETED;
  tl.tracks = {good, bad, gone};
  mpgc::msg::MovingObstacles m;
  bool got = false;
  for (int i = 0; i < 100 && !got; ++i) {
    tracks.write(tl);
    got = wait_for(moving, m, [stamp](const auto& v) { return v.t_valid_ns == stamp; }, 0.2);
  }
  ASSERT_TRUE(got);
  ASSERT_EQ(m.obstacles.size(), 1u);  // NaN track rejected, deleted track skipped
  EXPECT_EQ(m.obstacles[0].id, 7u);
  EXPECT_EQ(m.obstacles[0].x, 500.0);
  EXPECT_EQ(m.obstacles[0].vy, -1.0);
  EXPECT_EQ(m.obstacles[0].radius, 200.0);
  EXPECT_EQ(m.obstacles[0].position_std, 5.0);
  EXPECT_TRUE(proc.running());
}

// Issue 15: when sa/tracks goes silent the component says so on health, keeps the last obstacles
// (uncertainty growing) until tracks.max_age, then publishes an empty list; tracks again: OK.
TEST(ObstacleManagerProcess, SilentTracksDegradeHealthAndAgeOutToAnEmptyList) {
  const int domain = mpgc::testing::unique_domain();
  Process proc({mpgc::testing::bin_dir() + "/mpgc_obstacle_manager", "--domain", std::to_string(domain), "--set",
                "chart.shapes=circle 0 0 100", "--set", "region.half_size=0", "--set", "moving.period=0.1", "--set",
                "tracks.timeout=1", "--set", "tracks.max_age=3", "--set", "tracks.speed_std=2", "--set",
                "health.period=0.2", "--log-level", "warn"});
  namespace msg = mpgc::msg;
  mpgc::dds::Participant part(static_cast<uint32_t>(domain));
  mpgc::dds::Topic<msg::TrackList> tracks_topic(part, mpgc::topics::kTracks);
  mpgc::dds::Writer<msg::TrackList> tracks(part, tracks_topic, mpgc::dds::QosProfile::state());
  mpgc::dds::Topic<msg::MovingObstacles> moving_topic(part, mpgc::topics::kMovingObstacles);
  mpgc::dds::Reader<msg::MovingObstacles> moving(part, moving_topic, mpgc::dds::QosProfile::state());
  mpgc::dds::Topic<msg::ComponentHealth> health_topic(part, mpgc::topics::kHealth);
  mpgc::dds::Reader<msg::ComponentHealth> health(part, health_topic, mpgc::dds::QosProfile::latched());
  auto track_list = [] {
    msg::TrackList tl;
    tl.header.stamp_ns = dds_time();
    msg::Track t{};
    t.id = 3;
    t.x = 100;
    t.vx = 1;
    t.cov[0] = t.cov[5] = 9;
    t.length = NAN;
    t.since_update = 0.5;
    t.status = msg::TrackStatus::TRACK_CONFIRMED;
    tl.tracks = {t};
    return tl;
  };
  // Fresh tracks: published, health OK.
  msg::MovingObstacles m;
  bool got = false;
  for (int i = 0; i < 100 && !got; ++i) {
    tracks.write(track_list());
    got = wait_for(moving, m, [](const auto& v) { return v.obstacles.size() == 1; }, 0.1);
  }
  ASSERT_TRUE(got);
  msg::ComponentHealth h;
  ASSERT_TRUE(wait_for(health, h, [](const auto& v) { return v.state == msg::HealthState::HEALTH_OK; }, 10.0));
  const int64_t last_stamp = dds_time();
  tracks.write(track_list());
  // Silence: degraded with the reason, the obstacle still there and its uncertainty grown.
  // (A start slower than tracks.timeout may have said "... since start" before the first list.)
  ASSERT_TRUE(wait_for(health, h, [](const auto& v) {
    return v.state == msg::HealthState::HEALTH_DEGRADED && v.detail.find("predicting") != std::string::npos;
  }, 10.0));
  EXPECT_NE(h.detail.find("no tracks from situational_awareness for"), std::string::npos) << h.detail;
  ASSERT_TRUE(wait_for(moving, m, [](const auto& v) { return v.obstacles.size() == 1; }, 2.0));
  EXPECT_GT(m.obstacles[0].position_std, 3.5);  // sqrt(3^2 + (2 m/s x > 1 s)^2) > 3.6
  EXPECT_GT(m.obstacles[0].radius, 50.0);
  EXPECT_LE(m.t_valid_ns, dds_time());
  // After max_age: an empty list, valid now; health says every track aged out.
  ASSERT_TRUE(wait_for(moving, m, [](const auto& v) { return v.obstacles.empty(); }, 10.0));
  EXPECT_GT(m.t_valid_ns, last_stamp + 2'000'000'000);
  ASSERT_TRUE(wait_for(health, h, [](const auto& v) {
    return v.detail.find("every track aged out") != std::string::npos;
  }, 10.0));
  auto counter = [&h](const std::string& name) {
    for (const auto& c : h.counters)
      if (c.name == name) return c.value;
    return uint64_t{0};
  };
  EXPECT_GE(counter("tracks_timeout"), 1u);
  EXPECT_EQ(counter("tracks_aged_out"), 1u);
  EXPECT_EQ(counter("moving_emptied"), 1u);
  // Tracks again: OK.
  got = false;
  for (int i = 0; i < 100 && !got; ++i) {
    tracks.write(track_list());
    got = wait_for(health, h, [](const auto& v) { return v.state == msg::HealthState::HEALTH_OK; }, 0.1);
  }
  EXPECT_TRUE(got);
  EXPECT_TRUE(proc.running());
}

TEST(ObstacleManagerProcess, BadChartExitsWithError) {
  const int domain = mpgc::testing::unique_domain();
  const std::string bin = mpgc::testing::bin_dir() + "/mpgc_obstacle_manager";
  const std::string cmd = bin + " --domain " + std::to_string(domain) +
                          " --set chart.files=/nonexistent/chart.geojson > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 1);
}

TEST(ObstacleManagerProcess, WholeS57CellOverDdsAbove1e5Points) {
  const int domain = mpgc::testing::unique_domain();
  Process proc({mpgc::testing::bin_dir() + "/mpgc_obstacle_manager", "--domain", std::to_string(domain), "--set",
                "chart.files=" + mpgc::testing::shared_data("chart/US4MD81M/US4MD81M.000"), "--set",
                "chart.origin_lat=38.965", "--set", "chart.origin_lon=-76.45", "--set", "chart.depth_areas=false",
                "--set", "chart.spacing=5",
                "--set", "region.half_size=15000", "--set", "region.republish_distance=1000", "--log-level", "warn"});
  mpgc::dds::Participant part(static_cast<uint32_t>(domain));
  mpgc::dds::Topic<mpgc::msg::FixedObstacles> fixed_topic(part, mpgc::topics::kFixedObstacles);
  mpgc::dds::Reader<mpgc::msg::FixedObstacles> fixed(part, fixed_topic, mpgc::dds::QosProfile::latched());
  mpgc::dds::Topic<mpgc::msg::NavState> nav_topic(part, mpgc::topics::kOwnState);
  mpgc::dds::Writer<mpgc::msg::NavState> nav(part, nav_topic, mpgc::dds::QosProfile::state());
  mpgc::msg::NavState s{};
  s.valid_mask = mpgc::msg::NAV_POSITION_VALID;
  s.lat = NAN;  // no lat/lon: no origin cross-check
  s.lon = NAN;
  // Nothing is published before the own position is known (region mode); then the region around it.
  // Loading the cell takes ~0.5 s in a release build and ~15 s under the sanitizers: allow 90 s.
  mpgc::msg::FixedObstacles f;
  bool got = false;
  for (int i = 0; i < 450 && !got && proc.running(); ++i) {
    nav.write(s);
    got = wait_for(fixed, f, [](const auto&) { return true; }, 0.2);
  }
  ASSERT_TRUE(got);
  EXPECT_EQ(f.region_min_x, -15000.0);
  EXPECT_GT(f.points.size(), 100000u);
  const auto map = mpgc::obstacle_manager::map_from_msg(f);
  // The labelled land point (lon -76.46, lat 38.99) and water point (-76.43, 38.96).
  const mpgc::geo::LocalNed frame({38.965 * M_PI / 180, -76.45 * M_PI / 180});
  const auto land = frame.to_ned({38.99 * M_PI / 180, -76.46 * M_PI / 180});
  const auto water = frame.to_ned({38.96 * M_PI / 180, -76.43 * M_PI / 180});
  EXPECT_TRUE(map.inside_land({land.x, land.y}));
  EXPECT_FALSE(map.inside_land({water.x, water.y}));
  // Moving 3 km north re-centres the region: a second, newer version.
  s.x = 3000.0;
  mpgc::msg::FixedObstacles f2;
  got = false;
  for (int i = 0; i < 300 && !got; ++i) {
    nav.write(s);
    got = wait_for(fixed, f2, [](const auto& v) { return v.version > 1; }, 0.2);
  }
  ASSERT_TRUE(got);
  EXPECT_EQ(f2.region_min_x, -12000.0);
}
