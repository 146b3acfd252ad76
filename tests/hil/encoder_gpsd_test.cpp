// The NMEA and AIS encoders decoded by a real gpsd (3.22): own-ship RMC+GGA+VTG+HDT on one UDP
// device, AIS on a second one (a gpsd 3.22 bug corrupts ATT after AIS on the same device, notes
// §5), everything on 127.0.0.1. gpsd's TPV/ATT/AIS JSON must give back the encoder's inputs at the
// sentences' resolution. The test starts and stops its own gpsd (gpsd_harness.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gpsd_harness.hpp"
#include "mpgc/nmea/ais.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/testing_ais.hpp"

using namespace mpgc;

namespace {

constexpr double kKnot = 1852.0 / 3600.0;  // [m/s]

// Reads gpsd's lines (200 ms at a time, 5 s in all) until `done(line)` returns true. With
// bad_json, a line that is not plausible JSON is a failure, counted there, and not given to done.
template <class Done>
void read_until(hil::GpsdWatch& watch, int* bad_json, Done done) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < end) {
    const auto l = watch.line(200);
    if (!l) continue;
    if (bad_json != nullptr && !hil::json_plausible(*l)) {
      ++*bad_json;
      ADD_FAILURE() << "invalid JSON from gpsd: " << *l;
      continue;
    }
    if (done(*l)) return;
  }
}

}  // namespace

TEST(HilEncoderGpsd, OwnShipFixesAndHeading) {
  MPGC_HIL_GPSD_WITH_WATCH(gpsd, watch, 2);
  hil::UdpSender udp;

  // ~20 states across the hemispheres; seeded.
  struct State {
    double lat, lon, sog, cog, hdg;
  };
  std::vector<State> states = {{59.91, 10.72, 12.3, 224.0, 215.0},  {-33.856789, 151.215123, 0.0, 0.0, 0.0},
                               {-22.9, -43.2, 25.0, 359.99, 359.99}, {40.6, -74.04, 7.77, 90.0, 91.5},
                               {0.000001, -0.000001, 0.01, 180.0, 180.0}, {-0.5, 0.5, 3.0, 0.01, 359.5}};
  std::mt19937 rng(20241201);
  std::uniform_real_distribution<double> lat(-80, 80), lon(-179.99, 179.99), sog(0, 25), ang(0, 359.99);
  while (states.size() < 20) states.push_back({lat(rng), lon(rng), sog(rng), ang(rng), ang(rng)});

  // Current date (gpsd moves pre-2017 dates by 1024 weeks); 50 ms apart so each state has its own
  // TPV time and all stay within a second of the wall clock (gpsd writes it to NTP SHM, notes §4).
  const int64_t now_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                             std::chrono::system_clock::now().time_since_epoch()).count();
  const int64_t base_ns = now_ns / 1000000000 * 1000000000;

  int tpv_ok = 0, att_ok = 0, bad_json = 0;
  double max_dlat = 0, max_dlon = 0, max_dspeed_kn = 0, max_dtrack = 0, max_dhdg = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    const State& st = states[i];
    nmea::FixData f;
    f.utc_ns = base_ns + static_cast<int64_t>(i) * 50000000;
    f.lat_deg = st.lat;
    f.lon_deg = st.lon;
    f.sog_kn = st.sog;
    f.cog_deg = st.cog;
    ASSERT_TRUE(udp.send(gpsd.udp_port(0), nmea::rmc("GP", f) + nmea::gga("GP", f) + nmea::vtg("GP", f) +
                                               nmea::hdt("GP", st.hdg)));
    // Lock-step: read until this state's ATT (HDT is the last sentence of the datagram).
    const std::string want_time = hil::iso_ms(f.utc_ns);
    std::string last_tpv, att;
    read_until(watch, &bad_json, [&](const std::string& l) {
      const std::string cls = hil::json_class(l);
      if (cls == "TPV" && hil::json_string(l, "time").value_or("") == want_time) last_tpv = l;
      if (cls == "ATT") att = l;
      return !att.empty();
    });
    SCOPED_TRACE("state " + std::to_string(i) + ": " + nmea::rmc("GP", f));
    ASSERT_FALSE(last_tpv.empty()) << "no TPV with time " << want_time;
    ASSERT_FALSE(att.empty()) << "no ATT";

    const double mode = hil::json_number(last_tpv, "mode").value_or(-1);
    const auto glat = hil::json_number(last_tpv, "lat"), glon = hil::json_number(last_tpv, "lon");
    const auto gspeed = hil::json_number(last_tpv, "speed"), gtrack = hil::json_number(last_tpv, "track");
    const auto ghdg = hil::json_number(att, "heading");
    EXPECT_EQ(mode, 3.0) << last_tpv;
    ASSERT_TRUE(glat && glon && gspeed && gtrack) << last_tpv;
    ASSERT_TRUE(ghdg) << att;
    const double dlat = std::fabs(*glat - st.lat), dlon = std::fabs(*glon - st.lon);
    const double dspeed_kn = std::fabs(*gspeed / kKnot - st.sog);  // gpsd: m/s, 3 decimals
    const double dtrack = hil::angle_diff(*gtrack, st.cog), dhdg = hil::angle_diff(*ghdg, st.hdg);
    EXPECT_LE(dlat, 1e-6) << last_tpv;
    EXPECT_LE(dlon, 1e-6) << last_tpv;
    EXPECT_LE(dspeed_kn, 0.01) << last_tpv;
    EXPECT_LE(dtrack, 0.01) << last_tpv;
    EXPECT_LE(dhdg, 0.01) << att;
    const bool tpv_good = mode == 3.0 && dlat <= 1e-6 && dlon <= 1e-6 && dspeed_kn <= 0.01 && dtrack <= 0.01;
    tpv_ok += tpv_good;
    att_ok += dhdg <= 0.01;
    max_dlat = std::max(max_dlat, dlat);
    max_dlon = std::max(max_dlon, dlon);
    max_dspeed_kn = std::max(max_dspeed_kn, dspeed_kn);
    max_dtrack = std::max(max_dtrack, dtrack);
    max_dhdg = std::max(max_dhdg, dhdg);
  }
  std::printf("own ship: %d/%zu TPV and %d/%zu ATT agree; max |dlat| %.2e deg, |dlon| %.2e deg, |dspeed| %.4f kn, "
              "|dtrack| %.4f deg, |dheading| %.4f deg; %d invalid JSON lines\n",
              tpv_ok, states.size(), att_ok, states.size(), max_dlat, max_dlon, max_dspeed_kn, max_dtrack, max_dhdg,
              bad_json);
  EXPECT_EQ(tpv_ok, static_cast<int>(states.size()));
  EXPECT_EQ(att_ok, static_cast<int>(states.size()));
  EXPECT_EQ(bad_json, 0);
}

TEST(HilEncoderGpsd, AisTargets) {
  MPGC_HIL_GPSD_WITH_WATCH(gpsd, watch, 2);
  hil::UdpSender udp;

  std::mt19937 rng(1371);
  std::uniform_real_distribution<double> lat(-85, 85), lon(-179.99, 179.99), sog(0, 30), ang(0, 359.99),
      rot(-800, 800);
  std::vector<ais::PositionReport> targets;
  for (int j = 0; j < 20; ++j) {
    ais::PositionReport m;
    m.type = 1 + j % 3;
    m.mmsi = 257000001 + static_cast<uint32_t>(j);
    m.nav_status = j % 9;
    m.rot_deg_min = j == 0 ? NAN : j == 1 ? 0.0 : j == 2 ? -5.0 : rot(rng);
    m.sog_kn = j == 0 ? 0.0 : sog(rng);
    m.accuracy = j % 2 == 0;
    m.lat_deg = j == 3 ? -89.5 : lat(rng);
    m.lon_deg = j == 3 ? -179.5 : lon(rng);
    m.cog_deg = j == 1 ? 359.99 : ang(rng);
    m.heading_deg = j == 4 ? NAN : ang(rng);
    m.second = j;
    m.radio = 1000u * static_cast<uint32_t>(j);
    targets.push_back(m);
  }

  int ais_ok = 0, bad_json = 0;
  double max_dlat = 0, max_dlon = 0, max_dsog = 0, max_dcog = 0, max_dhdg = 0;
  for (const auto& m : targets) {
    const auto lines = ais::sentences(ais::encode(m), m.mmsi % 2 ? 'A' : 'B');
    ASSERT_EQ(lines.size(), 1u);
    ASSERT_TRUE(udp.send(gpsd.udp_port(1), lines[0]));
    std::string got;
    read_until(watch, &bad_json, [&](const std::string& l) {
      if (hil::json_class(l) == "AIS" && hil::json_number(l, "mmsi").value_or(0) == m.mmsi) got = l;
      return !got.empty();
    });
    SCOPED_TRACE(lines[0]);
    ASSERT_FALSE(got.empty()) << "no AIS for mmsi " << m.mmsi;
    // Unscaled: lat/lon in 1/600000 deg, speed 0.1 kn, course 0.1 deg, heading whole degrees.
    const double glat = hil::json_number(got, "lat").value_or(NAN) / 600000.0;
    const double glon = hil::json_number(got, "lon").value_or(NAN) / 600000.0;
    const double gsog = hil::json_number(got, "speed").value_or(NAN) / 10.0;
    const double gcog = hil::json_number(got, "course").value_or(NAN) / 10.0;
    const double ghdg = hil::json_number(got, "heading").value_or(NAN);
    EXPECT_EQ(hil::json_number(got, "type").value_or(0), m.type);
    EXPECT_EQ(hil::json_number(got, "status").value_or(-1), m.nav_status);
    EXPECT_EQ(hil::json_number(got, "second").value_or(-1), m.second);
    EXPECT_EQ(hil::json_number(got, "radio").value_or(-1), m.radio);
    EXPECT_EQ(hil::json_raw(got, "accuracy").value_or(""), m.accuracy ? "true" : "false");
    EXPECT_EQ(hil::json_number(got, "turn").value_or(999), mpgc::testing::expected_rot_ais(m.rot_deg_min)) << got;
    const double dlat = std::fabs(glat - m.lat_deg), dlon = std::fabs(glon - m.lon_deg);
    const double dsog = std::fabs(gsog - m.sog_kn), dcog = hil::angle_diff(gcog, m.cog_deg);
    EXPECT_LE(dlat, 1.0 / 600000) << got;
    EXPECT_LE(dlon, 1.0 / 600000) << got;
    EXPECT_LE(dsog, 0.1) << got;
    EXPECT_LE(dcog, 0.1) << got;
    double dhdg = 0;
    if (std::isnan(m.heading_deg)) {
      EXPECT_EQ(ghdg, 511) << got;
    } else {
      dhdg = hil::angle_diff(ghdg, m.heading_deg);
      EXPECT_LE(dhdg, 1.0) << got;
      EXPECT_LT(ghdg, 360) << got;
    }
    ais_ok += dlat <= 1.0 / 600000 && dlon <= 1.0 / 600000 && dsog <= 0.1 && dcog <= 0.1 && dhdg <= 1.0;
    max_dlat = std::max(max_dlat, dlat);
    max_dlon = std::max(max_dlon, dlon);
    max_dsog = std::max(max_dsog, dsog);
    max_dcog = std::max(max_dcog, dcog);
    max_dhdg = std::max(max_dhdg, dhdg);
  }

  // Type 5 in two fragments, in one datagram.
  // mmsi, imo, callsign, name, ship type, to bow/stern/port/starboard [m], draught [m], destination
  const ais::StaticVoyage v{257000099, 9134270, "LAXY7", "MPGC TEST VESSEL", 70, 150, 45, 12, 20, 9.4, "NOBRE"};
  const auto frags = ais::sentences(ais::encode(v), 'A', 3);
  ASSERT_EQ(frags.size(), 2u);
  ASSERT_TRUE(udp.send(gpsd.udp_port(1), frags[0] + frags[1]));
  std::string t5;
  read_until(watch, nullptr, [&](const std::string& l) {  // these lines are not JSON-checked
    if (hil::json_class(l) == "AIS" && hil::json_number(l, "type").value_or(0) == 5) t5 = l;
    return !t5.empty();
  });
  ASSERT_FALSE(t5.empty()) << "no type 5 from " << frags[0] << frags[1];
  EXPECT_EQ(hil::json_number(t5, "mmsi").value_or(0), v.mmsi);
  EXPECT_EQ(hil::json_number(t5, "imo").value_or(0), v.imo);
  EXPECT_EQ(hil::json_string(t5, "shipname").value_or(""), v.name);
  EXPECT_EQ(hil::json_string(t5, "callsign").value_or(""), v.callsign);
  EXPECT_EQ(hil::json_string(t5, "destination").value_or(""), v.destination);
  EXPECT_EQ(hil::json_number(t5, "shiptype").value_or(-1), v.ship_type);
  EXPECT_EQ(hil::json_number(t5, "to_bow").value_or(-1), v.to_bow);
  EXPECT_EQ(hil::json_number(t5, "to_stern").value_or(-1), v.to_stern);
  EXPECT_EQ(hil::json_number(t5, "to_port").value_or(-1), v.to_port);
  EXPECT_EQ(hil::json_number(t5, "to_starboard").value_or(-1), v.to_starboard);
  EXPECT_EQ(hil::json_number(t5, "draught").value_or(-1), 94);  // unscaled: 0.1 m
  const bool t5_ok = hil::json_string(t5, "shipname").value_or("") == v.name &&
                     hil::json_number(t5, "to_bow").value_or(-1) == v.to_bow &&
                     hil::json_number(t5, "to_stern").value_or(-1) == v.to_stern &&
                     hil::json_number(t5, "to_port").value_or(-1) == v.to_port &&
                     hil::json_number(t5, "to_starboard").value_or(-1) == v.to_starboard;

  std::printf("AIS: %d/%zu type 1-3 agree (max |dlat| %.2e deg, |dlon| %.2e deg, |dsog| %.3f kn, |dcog| %.3f deg, "
              "|dhdg| %.2f deg); type 5 %s; %d invalid JSON lines\n",
              ais_ok, targets.size(), max_dlat, max_dlon, max_dsog, max_dcog, max_dhdg, t5_ok ? "agrees" : "DIFFERS",
              bad_json);
  EXPECT_EQ(ais_ok, static_cast<int>(targets.size()));
  EXPECT_EQ(bad_json, 0);
}

// The harness's replay mode (for the log-replay tests): gpsfake on saab-r4.log gives its 14 TPV and
// 14 AIS (notes §2), then the end of the device.
TEST(HilGpsdHarness, GpsfakeReplay) {
  ASSERT_FALSE(hil::find_exe("gpsfake").empty()) << "gpsfake is not installed: apt-get install gpsd-clients";
  auto fake = hil::GpsdProcess::gpsfake(mpgc::testing::shared_data("nmea/gpsd/saab-r4.log"));
  ASSERT_TRUE(fake.ok()) << fake.error();
  hil::GpsdWatch watch(fake.port());
  ASSERT_TRUE(watch.ok()) << watch.error();
  int tpv = 0, ais_n = 0;
  bool ended = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!ended && std::chrono::steady_clock::now() < end) {
    const auto l = watch.line(500);
    if (!l) {
      ended = watch.closed();
      continue;
    }
    const std::string cls = hil::json_class(*l);
    tpv += cls == "TPV";
    ais_n += cls == "AIS";
    if (cls == "DEVICE" && hil::json_raw(*l, "activated").value_or("") == "0") ended = true;
  }
  std::printf("gpsfake saab-r4.log: %d TPV, %d AIS, end of device %s\n", tpv, ais_n, ended ? "seen" : "NOT seen");
  EXPECT_TRUE(ended);
  EXPECT_EQ(tpv, 14);
  EXPECT_EQ(ais_n, 14);
  EXPECT_EQ(fake.wait_exit(10000).value_or(-1), 0) << fake.stderr_text();
}
