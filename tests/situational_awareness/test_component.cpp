// Integration over DDS (own domain, loopback): the real mpgc_situational_awareness process turns
// a radar-only head-on target and an AIS-only crossing target into confirmed tracks and the right
// encounters, and counts malformed inputs in its health.
#include <gtest/gtest.h>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

#include <dds/dds.h>

#include "mpgc/dds/dds.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

extern char** environ;
namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
using mpgc::geo::deg2rad;

namespace {
using mpgc::testing::Process;
}  // namespace

TEST(SituationalAwarenessProcess, TracksEncountersAndRejectedInputs) {
  const int domain = mpgc::testing::unique_domain();
  const double lat0 = 58.76, lon0 = 10.49;
  Process proc({mpgc::testing::bin_dir() + "/mpgc_situational_awareness", "--domain", std::to_string(domain), "--set",
                "period=0.1", "--set", "origin.source=param", "--set", "origin.lat=" + std::to_string(lat0), "--set",
                "origin.lon=" + std::to_string(lon0), "--set", "health.period=0.2", "--log-level", "error"});
  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::NavState> nav_t(part, mpgc::topics::kOwnState);
  dds::Topic<msg::AisReport> ais_t(part, mpgc::topics::kAis);
  dds::Topic<msg::RadarScan> radar_t(part, mpgc::topics::kRadar);
  dds::Topic<msg::TrackList> tracks_t(part, mpgc::topics::kTracks);
  dds::Topic<msg::EncounterList> enc_t(part, mpgc::topics::kEncounters);
  dds::Topic<msg::ComponentHealth> health_t(part, mpgc::topics::kHealth);
  dds::Writer<msg::NavState> nav(part, nav_t, dds::QosProfile::state());
  dds::Writer<msg::AisReport> ais(part, ais_t, dds::QosProfile::command(64));
  dds::Writer<msg::RadarScan> radar(part, radar_t, dds::QosProfile::state());
  dds::Reader<msg::TrackList> tracks(part, tracks_t, dds::QosProfile::state());
  dds::Reader<msg::EncounterList> encounters(part, enc_t, dds::QosProfile::state());
  dds::Reader<msg::ComponentHealth> health(part, health_t, dds::QosProfile::latched());
  const mpgc::geo::LocalNed ned({deg2rad(lat0), deg2rad(lon0)});

  // Own ship north at 5 m/s from the origin; radar target head-on (CPA 30 m); AIS target crossing
  // from starboard (CPA ~0).
  const int64_t t0 = dds_time();
  auto own_at = [&](double t) { return std::array<double, 2>{5.0 * t, 0.0}; };
  auto radar_tgt = [&](double t) { return std::array<double, 2>{3000.0 - 5.0 * t, 30.0}; };
  auto ais_tgt = [&](double t) { return std::array<double, 2>{2000.0, 2000.0 - 5.0 * t}; };
  bool head_on = false, crossing = false, confirmed_radar = false;
  uint64_t bad_mmsi = 0, future = 0;
  for (int k = 0; k < 200 && !(head_on && crossing && confirmed_radar && bad_mmsi && future); ++k) {
    const int64_t now = dds_time();
    const double t = (now - t0) * 1e-9;
    msg::NavState s{};
    s.header.stamp_ns = now;
    const auto o = own_at(t);
    s.x = o[0];
    s.y = o[1];
    const auto ll = ned.to_latlon({o[0], o[1]});
    s.lat = ll.lat;
    s.lon = ll.lon;
    s.heading = s.cog = 0.0;
    s.sog = 5.0;
    s.valid_mask = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID;
    nav.write(s);

    msg::RadarScan sc{};
    sc.header.stamp_ns = now;
    sc.antenna_x = o[0];
    sc.antenna_y = o[1];
    sc.max_range = 6000;
    const auto r = radar_tgt(t);
    sc.contacts.push_back({std::hypot(r[0] - o[0], r[1] - o[1]), std::atan2(r[1] - o[1], r[0] - o[0]), 5.0, 0.002});
    radar.write(sc);

    if (k % 5 == 0) {
      const auto a = ais_tgt(t);
      const auto all = ned.to_latlon({a[0], a[1]});
      msg::AisReport rep{};
      rep.header.stamp_ns = now;
      rep.mmsi = 257000005;
      rep.lat = all.lat;
      rep.lon = all.lon;
      rep.sog = 5.0;
      rep.cog = deg2rad(-90);  // west, meeting the own ship at (2000, 0) at t = 400 s
      rep.heading = rep.rot = std::nan("");
      rep.report_time_ns = now;
      rep.length = 80;
      ais.write(rep);
      msg::AisReport bad = rep;
      bad.mmsi = 0;
      ais.write(bad);
      msg::RadarScan fut = sc;
      fut.header.stamp_ns = now + 3600LL * 1000000000LL;
      radar.write(fut);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (const auto& tl : tracks.take())
      for (const auto& tr : tl.value.tracks)
        if (tr.mmsi == 0 && tr.status == msg::TrackStatus::TRACK_CONFIRMED &&
            tr.sources == msg::TRACK_SOURCE_RADAR && std::isfinite(tr.cov[0]))
          confirmed_radar = true;
    for (const auto& el : encounters.take())
      for (const auto& e : el.value.encounters) {
        if (e.mmsi == 0 && e.type == msg::EncounterType::ENCOUNTER_HEAD_ON && e.role == msg::OwnRole::ROLE_BOTH_GIVE_WAY &&
            std::fabs(e.cpa - 30.0) < 25.0 && e.tcpa > 0)
          head_on = true;
        if (e.mmsi == 257000005 && e.type == msg::EncounterType::ENCOUNTER_CROSSING_GIVE_WAY &&
            e.role == msg::OwnRole::ROLE_GIVE_WAY && e.cpa < 50.0)
          crossing = true;
      }
    for (const auto& h : health.take()) {
      if (h.value.component != "situational_awareness") continue;
      for (const auto& c : h.value.counters) {
        if (c.name == "rejected.ais.bad_mmsi") bad_mmsi = c.value;
        if (c.name == "rejected.radar.future_stamp") future = c.value;
      }
    }
  }
  EXPECT_TRUE(proc.running());
  EXPECT_TRUE(confirmed_radar);
  EXPECT_TRUE(head_on);
  EXPECT_TRUE(crossing);
  EXPECT_GE(bad_mmsi, 1u);
  EXPECT_GE(future, 1u);
}

TEST(SituationalAwarenessProcess, BadParameterExits) {
  const std::string cmd = mpgc::testing::bin_dir() + "/mpgc_situational_awareness --domain " +
                          std::to_string(mpgc::testing::unique_domain()) +
                          " --set tracker.confirm_m=9 --set tracker.confirm_n=5 > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc));
  EXPECT_NE(WEXITSTATUS(rc), 0);
}
