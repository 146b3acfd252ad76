// The simulator as the ship's devices, decoded by a real gpsd (3.22) instead of our own decoder: a
// small world (all sensor noise 0, so what the simulator sends is its truth) is stepped for 120 s
// simulated with some rudder; every nav sample's Devices::gnss() and gyro() go to gpsd device 0,
// every AIS report's ais_target() lines (and the own ship's AIVDO) to device 1, over UDP on
// 127.0.0.1. gpsd's TPV and AIS JSON must give back what was sent at the sentences' resolution.
// gpsd 3.22 drops the $HE talker every gyro compass uses: the gyro's $HEHDT gives no ATT at all
// (that is why the bridge reads the gyro directly), while a control $GPHDT does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "gpsd_harness.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/testing_ais.hpp"

using namespace mpgc;
namespace sim = mpgc::ship_simulator;

namespace {

constexpr double kKnot = 1852.0 / 3600.0;  // [m/s]
constexpr int64_t kStepNs = 100'000'000;   // 0.1 s
constexpr double kRunS = 120.0;
constexpr int kPaceMs = 2;                 // between datagrams, so gpsd keeps up

double deg360(double rad) {
  const double d = std::fmod(geo::rad2deg(rad), 360.0);
  return d < 0 ? d + 360.0 : d;
}

// Three targets: a slow one (10 s AIS interval), a fast one that turns at 40 s (2 s), one at 16 kn (6 s).
const char* kWorld = R"(
origin: {lat_deg: 59.40, lon_deg: 10.50}
seed: 11
own_ship: {model: nomoto, nomoto_ship: Mariner, length_m: 120, beam_m: 20, heading_deg: 30, speed_kn: 12,
           mmsi: 257999999}
targets:
  - {mmsi: 257000002, name: Crossing One, x_m: 3000, y_m: 2000, course_deg: 250, speed_kn: 10,
     length_m: 101, beam_m: 17}
  - {mmsi: 257000003, name: Fast Ferry, x_m: -2000, y_m: 1500, course_deg: 10, speed_kn: 25,
     length_m: 60, beam_m: 12, max_turn_rate_deg_s: 1.0,
     legs: [{course_deg: 10, speed_kn: 25, duration_s: 40}, {course_deg: 80, speed_kn: 25}]}
  - {mmsi: 257000004, name: Slow Tug, x_m: 1000, y_m: -3000, course_deg: 120, speed_kn: 16,
     length_m: 30, beam_m: 9}
sensors:
  nav: {period_s: 0.1, sigma_position_m: 0, sigma_heading_deg: 0, sigma_sog_mps: 0, sigma_cog_deg: 0,
        sigma_rot_deg_s: 0}
  ais: {sigma_position_m: 0, sigma_sog_mps: 0, sigma_cog_deg: 0, drop_probability: 0}
)";

// What the simulator sent, in the sentences' units.
struct SentFix {
  double lat, lon, sog_kn, cog_deg;
};
struct SentAis {
  uint32_t mmsi;
  double lat, lon, sog_kn, cog_deg, heading_deg, rot_deg_min;
  int second;
};
struct SentStatic {
  std::string name;
  int length, beam;
};

}  // namespace

TEST(HilDevicesGpsd, SimulatorOutputDecodedByGpsdGivesBackTheTruth) {
  const sim::WorldConfig cfg = sim::WorldConfig::from_yaml(kWorld, "devices_gpsd_test world");
  ASSERT_EQ(cfg.nav.sigma_position, 0.0);
  ASSERT_EQ(cfg.ais.sigma_position, 0.0);
  sim::World world(cfg, kStepNs);

  MPGC_HIL_GPSD_WITH_WATCH(gpsd, watch, 2);
  hil::UdpSender udp;

  // What gpsd says, as it arrives (read while pacing the sends).
  std::map<std::string, std::string> tpv_by_time;  // the last (most complete) TPV of each time
  std::vector<std::string> ais_lines, att_lines;
  int bad_json = 0, tpv_lines = 0;
  const auto take = [&](const std::string& l) {
    if (!hil::json_plausible(l)) {
      ++bad_json;
      ADD_FAILURE() << "invalid JSON from gpsd: " << l;
      return;
    }
    const std::string cls = hil::json_class(l);
    if (cls == "TPV") {
      ++tpv_lines;
      if (const auto t = hil::json_string(l, "time")) tpv_by_time[*t] = l;
    } else if (cls == "AIS") {
      ais_lines.push_back(l);
    } else if (cls == "ATT") {
      att_lines.push_back(l);
    }
  };
  const auto pace = [&](int ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) break;
      if (const auto l = watch.line(static_cast<int>(left))) take(*l);
    }
  };
  const auto send = [&](int port, const std::string& d) {
    const bool ok = udp.send(port, d);
    pace(kPaceMs);
    return ok;
  };

  const int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::system_clock::now().time_since_epoch()).count();
  const int64_t utc0 = now_ns / 1000000000 * 1000000000;  // current date: gpsd moves old ones
  sim::Devices dev(world.frame(), utc0);

  std::map<std::string, SentFix> sent_fix;       // by gpsd's TPV time
  std::map<uint32_t, std::deque<SentAis>> sent_ais;  // type 1 per MMSI, in order
  std::map<uint32_t, SentStatic> sent_static;
  std::map<uint32_t, int> sent_static_n;
  std::deque<SentAis> sent_own;
  int gyro_datagrams = 0, truth_mismatch = 0;
  int64_t next_own_ns = 0;
  sim::ShipCommand cmd = world.initial_command();
  const auto steps = static_cast<uint64_t>(std::llround(kRunS * 1e9 / kStepNs));
  for (uint64_t k = 0; k <= steps; ++k) {
    const int64_t t = world.time_ns();
    const double ts = static_cast<double>(t) * 1e-9;
    cmd.rudder = ts < 10.0 ? 0.0 : ts < 60.0 ? geo::deg2rad(10.0) : geo::deg2rad(-15.0);
    const sim::SensorOutputs out = world.sense();
    if (out.nav) {
      const sim::NavMeasurement& n = *out.nav;
      // Noise 0: the measurement is the truth.
      const sim::TruthShip tr = world.own_truth();
      if (std::fabs(n.x - tr.x) > 1e-9 || std::fabs(n.y - tr.y) > 1e-9 || std::fabs(n.sog - tr.sog) > 1e-12 ||
          std::fabs(geo::angle_diff(n.heading, tr.heading)) > 1e-12 || std::fabs(geo::angle_diff(n.cog, tr.cog)) > 1e-12 ||
          std::fabs(n.rot - tr.r) > 1e-15)
        ++truth_mismatch;
      const geo::LatLon ll = world.frame().to_latlon({n.x, n.y});
      sent_fix[hil::iso_ms(utc0 + t)] = {geo::rad2deg(ll.lat), geo::rad2deg(ll.lon), n.sog / kKnot, deg360(n.cog)};
      ASSERT_TRUE(send(gpsd.udp_port(0), dev.gnss(n, t)));
      ASSERT_TRUE(send(gpsd.udp_port(0), dev.gyro(n)));
      ++gyro_datagrams;
      if (t >= next_own_ns) {  // the own ship's transponder, every 10 s
        for (const auto& l : dev.ais_own(cfg.own_mmsi, n, t)) ASSERT_TRUE(send(gpsd.udp_port(1), l));
        sent_own.push_back({cfg.own_mmsi, geo::rad2deg(ll.lat), geo::rad2deg(ll.lon), n.sog / kKnot, deg360(n.cog),
                            deg360(n.heading), geo::rad2deg(n.rot) * 60.0,
                            static_cast<int>((utc0 + t) / 1000000000 % 60)});
        next_own_ns = t + 10'000'000'000;
      }
    }
    const std::vector<sim::TruthShip> truth = world.target_truth();
    for (const sim::AisMeasurement& a : out.ais) {
      const auto tc = std::find_if(cfg.targets.begin(), cfg.targets.end(), [&](const auto& x) { return x.mmsi == a.mmsi; });
      ASSERT_NE(tc, cfg.targets.end());
      const auto tt = std::find_if(truth.begin(), truth.end(), [&](const auto& x) { return x.mmsi == a.mmsi; });
      ASSERT_NE(tt, truth.end());
      if (std::fabs(a.x - tt->x) > 1e-9 || std::fabs(a.y - tt->y) > 1e-9 || std::fabs(a.sog - tt->sog) > 1e-12 ||
          std::fabs(geo::angle_diff(a.cog, tt->cog)) > 1e-12)
        ++truth_mismatch;
      const std::vector<std::string> lines = dev.ais_target(a, *tc, t);
      ASSERT_FALSE(lines.empty());
      const geo::LatLon ll = world.frame().to_latlon({a.x, a.y});
      sent_ais[a.mmsi].push_back({a.mmsi, geo::rad2deg(ll.lat), geo::rad2deg(ll.lon), a.sog / kKnot, deg360(a.cog),
                                  deg360(a.heading), geo::rad2deg(a.rot) * 60.0,
                                  static_cast<int>((utc0 + t) / 1000000000 % 60)});
      if (lines.size() > 1) {  // type 5 follows: the name as the transponder sends it
        std::string name = tc->name;
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
        sent_static[a.mmsi] = {name, static_cast<int>(std::lround(tc->length)), static_cast<int>(std::lround(tc->beam))};
        ++sent_static_n[a.mmsi];
      }
      for (const auto& l : lines) ASSERT_TRUE(send(gpsd.udp_port(1), l));  // one sentence per datagram, as the simulator
    }
    world.step(cmd);
  }
  // Everything gpsd still has to say, then a control heading with a talker gpsd accepts.
  pace(1500);
  const size_t att_from_gyro = att_lines.size();
  const double control_hdg = 123.45;
  ASSERT_TRUE(udp.send(gpsd.udp_port(0), nmea::hdt("GP", control_hdg)));
  pace(1500);
  // The ship really manoeuvred: the heading changed by tens of degrees.
  EXPECT_GT(std::fabs(geo::rad2deg(geo::angle_diff(world.own_truth().heading, geo::deg2rad(30.0)))), 10.0);
  EXPECT_EQ(truth_mismatch, 0) << "with all sigmas 0 the measurements must equal the truth";

  // ---- own ship: TPV ----
  int tpv_found = 0, tpv_ok = 0;
  double max_dlat = 0, max_dlon = 0, max_dspeed_kn = 0, max_dtrack = 0;
  for (const auto& [time, want] : sent_fix) {
    const auto it = tpv_by_time.find(time);
    if (it == tpv_by_time.end()) {
      ADD_FAILURE() << "no TPV with time " << time;
      continue;
    }
    ++tpv_found;
    const std::string& l = it->second;
    const double mode = hil::json_number(l, "mode").value_or(-1);
    const auto glat = hil::json_number(l, "lat"), glon = hil::json_number(l, "lon");
    const auto gspeed = hil::json_number(l, "speed"), gtrack = hil::json_number(l, "track");
    if (!(glat && glon && gspeed && gtrack)) {
      ADD_FAILURE() << "TPV without lat/lon/speed/track: " << l;
      continue;
    }
    const double dlat = std::fabs(*glat - want.lat), dlon = std::fabs(*glon - want.lon);
    const double dspeed_kn = std::fabs(*gspeed / kKnot - want.sog_kn), dtrack = hil::angle_diff(*gtrack, want.cog_deg);
    const bool good = mode == 3.0 && dlat <= 1e-6 && dlon <= 1e-6 && dspeed_kn <= 0.01 && dtrack <= 0.01;
    if (!good)
      ADD_FAILURE() << "TPV differs: sent lat " << want.lat << " lon " << want.lon << " sog " << want.sog_kn
                    << " kn cog " << want.cog_deg << "; gpsd: " << l;
    tpv_ok += good;
    max_dlat = std::max(max_dlat, dlat);
    max_dlon = std::max(max_dlon, dlon);
    max_dspeed_kn = std::max(max_dspeed_kn, dspeed_kn);
    max_dtrack = std::max(max_dtrack, dtrack);
  }

  // ---- AIS: type 1 per MMSI in order (matched by UTC second), type 5, own AIVDO ----
  int ais1_n = 0, ais1_ok = 0, ais1_missing = 0, t5_ok = 0, t5_seen = 0, own_ok = 0, unexpected = 0;
  double max_alat = 0, max_alon = 0, max_asog = 0, max_acog = 0, max_ahdg = 0;
  size_t sent_ais_n = 0;
  for (const auto& [m, q] : sent_ais) sent_ais_n += q.size();
  std::map<uint32_t, std::deque<SentAis>> pending = sent_ais;
  const auto compare_position = [&](const std::string& l, const SentAis& w, bool check_turn) {
    const double glat = hil::json_number(l, "lat").value_or(NAN) / 600000.0;
    const double glon = hil::json_number(l, "lon").value_or(NAN) / 600000.0;
    const double gsog = hil::json_number(l, "speed").value_or(NAN) / 10.0;
    const double gcog = hil::json_number(l, "course").value_or(NAN) / 10.0;
    const double ghdg = hil::json_number(l, "heading").value_or(NAN);
    const double gturn = hil::json_number(l, "turn").value_or(NAN);
    const double dlat = std::fabs(glat - w.lat), dlon = std::fabs(glon - w.lon);
    const double dsog = std::fabs(gsog - w.sog_kn), dcog = hil::angle_diff(gcog, w.cog_deg), dhdg = hil::angle_diff(ghdg, w.heading_deg);
    // Resolution: 1/600000 deg, 0.1 kn, 0.1 deg, whole degrees; rounding gives half of it at most.
    const bool good = dlat <= 0.5 / 600000 + 1e-12 && dlon <= 0.5 / 600000 + 1e-12 && dsog <= 0.05 + 1e-9 &&
                      dcog <= 0.05 + 1e-9 && dhdg <= 0.5 + 1e-9 && ghdg < 360 &&
                      (!check_turn || gturn == mpgc::testing::expected_rot_ais(w.rot_deg_min));
    if (!good)
      ADD_FAILURE() << "AIS differs: sent lat " << w.lat << " lon " << w.lon << " sog " << w.sog_kn << " kn cog "
                    << w.cog_deg << " hdg " << w.heading_deg << " rot " << w.rot_deg_min << " deg/min (turn "
                    << mpgc::testing::expected_rot_ais(w.rot_deg_min) << "); gpsd: " << l;
    max_alat = std::max(max_alat, dlat);
    max_alon = std::max(max_alon, dlon);
    max_asog = std::max(max_asog, dsog);
    max_acog = std::max(max_acog, dcog);
    max_ahdg = std::max(max_ahdg, dhdg);
    return good;
  };
  for (const std::string& l : ais_lines) {
    const int type = static_cast<int>(hil::json_number(l, "type").value_or(0));
    const auto mmsi = static_cast<uint32_t>(hil::json_number(l, "mmsi").value_or(0));
    const int second = static_cast<int>(hil::json_number(l, "second").value_or(-1));
    if (type == 1 && mmsi == cfg.own_mmsi) {
      while (!sent_own.empty() && sent_own.front().second != second) sent_own.pop_front();
      if (sent_own.empty()) {
        ADD_FAILURE() << "own-ship AIS not sent: " << l;
        continue;
      }
      own_ok += compare_position(l, sent_own.front(), true);
      sent_own.pop_front();
    } else if (type == 1) {
      auto& q = pending[mmsi];
      while (!q.empty() && q.front().second != second) {
        q.pop_front();
        ++ais1_missing;
      }
      if (q.empty()) {
        ++unexpected;
        ADD_FAILURE() << "AIS type 1 not sent (or out of order): " << l;
        continue;
      }
      ++ais1_n;
      ais1_ok += compare_position(l, q.front(), true);
      q.pop_front();
    } else if (type == 5) {
      ++t5_seen;
      const auto it = sent_static.find(mmsi);
      if (it == sent_static.end()) {
        ++unexpected;
        ADD_FAILURE() << "type 5 not sent: " << l;
        continue;
      }
      const int length = static_cast<int>(hil::json_number(l, "to_bow").value_or(-1000) +
                                          hil::json_number(l, "to_stern").value_or(-1000));
      const int beam = static_cast<int>(hil::json_number(l, "to_port").value_or(-1000) +
                                        hil::json_number(l, "to_starboard").value_or(-1000));
      const bool good = hil::json_string(l, "shipname").value_or("") == it->second.name &&
                        length == it->second.length && beam == it->second.beam &&
                        hil::json_number(l, "shiptype").value_or(-1) == 70;
      if (!good)
        ADD_FAILURE() << "type 5 differs: sent '" << it->second.name << "' " << it->second.length << " x "
                      << it->second.beam << " m; gpsd: " << l;
      t5_ok += good;
    } else {
      ++unexpected;
      ADD_FAILURE() << "unexpected AIS: " << l;
    }
  }
  for (const auto& [m, q] : pending) ais1_missing += static_cast<int>(q.size());
  int t5_sent = 0;
  for (const auto& [m, n] : sent_static_n) t5_sent += n;
  const int own_sent = static_cast<int>(std::llround(std::floor(kRunS / 10.0))) + 1;

  // ---- heading: $HEHDT is dropped by gpsd 3.22; the control $GPHDT is decoded ----
  int control_att = 0;
  for (size_t i = att_from_gyro; i < att_lines.size(); ++i)
    control_att += hil::angle_diff(hil::json_number(att_lines[i], "heading").value_or(NAN), control_hdg) <= 0.005;

  std::printf("gpsd vs the simulator (120 s, rudder 0/+10/-15 deg, sigmas 0):\n"
              "  TPV: %d of %zu fixes agree (%d found, %d TPV lines); max |dlat| %.2e deg, |dlon| %.2e deg, "
              "|dspeed| %.4f kn, |dtrack| %.4f deg\n"
              "  AIS type 1: %d of %zu agree (%d decoded, %d missing); max |dlat| %.2e deg, |dlon| %.2e deg, "
              "|dsog| %.3f kn, |dcog| %.3f deg, |dhdg| %.2f deg\n"
              "  AIS type 5: %d of %d agree (%d decoded); own AIVDO: %d of %d agree\n"
              "  ATT from %d $HEHDT datagrams: %zu (gpsd 3.22 drops talker HE); control $GPHDT: %d of 1 ATT\n"
              "  %d invalid JSON lines, %d unexpected AIS\n",
              tpv_ok, sent_fix.size(), tpv_found, tpv_lines, max_dlat, max_dlon, max_dspeed_kn, max_dtrack, ais1_ok,
              sent_ais_n, ais1_n, ais1_missing, max_alat, max_alon, max_asog, max_acog, max_ahdg, t5_ok, t5_sent,
              t5_seen, own_ok, own_sent, gyro_datagrams, att_from_gyro, control_att, bad_json, unexpected);

  EXPECT_EQ(sent_fix.size(), steps + 1);
  EXPECT_EQ(tpv_ok, static_cast<int>(sent_fix.size()));
  EXPECT_GE(sent_ais_n, 60u);  // the fast ferry alone sends every 2 s
  EXPECT_EQ(ais1_ok, static_cast<int>(sent_ais_n));
  EXPECT_EQ(ais1_missing, 0);
  EXPECT_EQ(t5_sent, static_cast<int>(cfg.targets.size()));  // once each, at the first report (6-min interval)
  EXPECT_EQ(t5_ok, t5_sent);
  EXPECT_EQ(own_ok, own_sent);
  EXPECT_EQ(att_from_gyro, 0u) << "gpsd decoded $HEHDT into ATT: " << (att_lines.empty() ? "" : att_lines.front());
  EXPECT_EQ(control_att, 1) << "the watch shows no ATT even for $GPHDT: the 0 above would prove nothing";
  EXPECT_EQ(bad_json, 0);
  EXPECT_EQ(unexpected, 0);
}
