// The real mpgc_ship_bridge process between gpsfake (replaying saab-r4.log, a real AIS transponder
// with GPS) and the real mpgc_situational_awareness, over DDS on loopback: own-ship fixes become a
// valid NavState whose heading and rate of turn are the log's own $HEHDT/$HEROT (sent to the
// bridge's gyro port, since gpsd 3.22 drops that talker), the own ship's AIVDO never becomes a
// target, and SA builds tracks from the real AIS of the other ships.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <set>
#include <thread>

#include "gpsd_harness.hpp"
#include "mpgc/dds/dds.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/net/udp.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace geo = mpgc::geo;

namespace {

constexpr uint32_t kOwnMmsi = 244121341;  // saab-r4.log's AIVDO (gpsd.md §2)

int free_udp_port() {
  for (int p = 31000 + getpid() % 2000;; ++p)
    if (mpgc::hil::port_free(p, false)) return p;
}

}  // namespace

TEST(ShipBridgeProcess, SaabR4ThroughGpsfakeBridgeAndSituationalAwareness) {
  const std::string log = mpgc::testing::shared_data("nmea/gpsd/saab-r4.log");
  std::vector<std::string> gyro_lines;
  std::set<double> hdt_values, rot_values;
  {
    std::ifstream in(log);
    for (std::string l; std::getline(in, l);) {
      if (l.rfind("$HEHDT", 0) == 0) hdt_values.insert(std::stod(l.substr(7)));
      if (l.rfind("$HEROT", 0) == 0) rot_values.insert(std::stod(l.substr(7)));
      if (l.rfind("$HE", 0) == 0) gyro_lines.push_back(l);
    }
  }
  ASSERT_FALSE(gyro_lines.empty()) << "no $HE sentences in " << log;

  const int domain = mpgc::testing::unique_domain();
  const int gyro_port = free_udp_port();
  // Paced (0.1 s per sentence, about the log's real 12 s) so the AIS reports are spread out.
  auto fake = mpgc::hil::GpsdProcess::gpsfake(log, {"-c", "0.1"});
  ASSERT_TRUE(fake.ok()) << fake.error();
  const std::string bin = mpgc::testing::bin_dir();
  mpgc::testing::Process bridge({bin + "/mpgc_ship_bridge", "--domain", std::to_string(domain), "--set",
                                 "gpsd.port=" + std::to_string(fake.port()), "--set", "gyro.port=" + std::to_string(gyro_port),
                                 "--set", "own.mmsi=" + std::to_string(kOwnMmsi), "--set", "origin.source=first_fix",
                                 "--set", "nav.fix_timeout=5", "--set", "nav.heading_timeout=5", "--log-level", "warn"});
  mpgc::testing::Process sa({bin + "/mpgc_situational_awareness", "--domain", std::to_string(domain), "--set", "period=0.2",
                             "--set", "origin.source=nav", "--log-level", "warn"});
  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::NavState> nav_t(part, mpgc::topics::kOwnState);
  dds::Topic<msg::AisReport> ais_t(part, mpgc::topics::kAis);
  dds::Topic<msg::TrackList> tracks_t(part, mpgc::topics::kTracks);
  dds::Reader<msg::NavState> nav(part, nav_t, dds::QosProfile::state());
  dds::Reader<msg::AisReport> ais(part, ais_t, dds::QosProfile::command(64));
  dds::Reader<msg::TrackList> tracks(part, tracks_t, dds::QosProfile::state());
  mpgc::net::UdpSender gyro("127.0.0.1", gyro_port);

  int valid_nav = 0, invalid_nav = 0, heading_from_log = 0, rate_from_log = 0;
  std::set<uint32_t> ais_mmsi, track_mmsi;
  size_t next_gyro = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(40);
  while (std::chrono::steady_clock::now() < end && (track_mmsi.empty() || valid_nav < 20 || next_gyro < gyro_lines.size())) {
    if (next_gyro < gyro_lines.size()) gyro.send(gyro_lines[next_gyro++] + "\r\n");
    for (const auto& s : nav.take()) {
      const auto& n = s.value;
      const uint32_t need = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID;
      if ((n.valid_mask & need) != need) {
        ++invalid_nav;
        EXPECT_FALSE((n.valid_mask & msg::NAV_POSITION_VALID) == 0 && std::isfinite(n.x)) << "invalid position not NaN";
        continue;
      }
      ++valid_nav;
      EXPECT_NEAR(geo::rad2deg(n.lat), 50.2132, 0.01);  // the log's position (off SW Ireland)
      EXPECT_NEAR(geo::rad2deg(n.lon), -8.1147, 0.01);
      const double hdg = std::fmod(geo::rad2deg(n.heading) + 360.0, 360.0);
      for (double h : hdt_values) heading_from_log += std::abs(hdg - h) < 1e-6;
      if (n.valid_mask & msg::NAV_RATE_VALID)
        for (double r : rot_values) rate_from_log += std::abs(geo::rad2deg(n.r) * 60.0 - r) < 1e-6;
    }
    for (const auto& s : ais.take()) ais_mmsi.insert(s.value.mmsi);
    for (const auto& s : tracks.take())
      for (const auto& t : s.value.tracks)
        if (t.mmsi != 0) track_mmsi.insert(t.mmsi);
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  std::printf("saab-r4 through the bridge: %d valid / %d invalid NavState, %d headings and %d rates equal to the log's, "
              "%zu AIS targets, %zu tracks with an MMSI\n", valid_nav, invalid_nav, heading_from_log, rate_from_log,
              ais_mmsi.size(), track_mmsi.size());
  EXPECT_GE(valid_nav, 20);
  EXPECT_EQ(heading_from_log, valid_nav) << "every valid heading is one of the log's $HEHDT values";
  EXPECT_GT(rate_from_log, 0);
  EXPECT_FALSE(ais_mmsi.empty()) << "no AIS target reports from the bridge";
  EXPECT_EQ(ais_mmsi.count(kOwnMmsi), 0u) << "the own ship's AIVDO became a target";
  EXPECT_FALSE(track_mmsi.empty()) << "situational_awareness built no track from the real AIS";
  EXPECT_EQ(track_mmsi.count(kOwnMmsi), 0u);
  for (uint32_t m : track_mmsi) EXPECT_TRUE(ais_mmsi.count(m)) << "track MMSI " << m << " never reported by the bridge";
  EXPECT_TRUE(bridge.running()) << "the bridge died";
  EXPECT_TRUE(sa.running()) << "situational_awareness died";
}

// The actuator wire of the real bridge process: control/actuators in, ROR/PRC orders out on UDP
// (saturated at the limits, never dropped), RSA/RPM feedback in, published in nav/own_state; the
// orders stop when the commands do (the steering gear's watchdog then takes over).
TEST(ShipBridgeProcess, ActuatorWireOrdersSaturationFeedbackAndTimeout) {
  const int domain = mpgc::testing::unique_domain();
  const int orders_port = free_udp_port();
  mpgc::net::UdpReceiver orders("127.0.0.1", orders_port);
  int feedback_port = orders_port + 1;
  while (!mpgc::hil::port_free(feedback_port, false)) ++feedback_port;
  const std::string bin = mpgc::testing::bin_dir();
  // No gpsd at all: the bridge keeps retrying it (and says so) while the actuator wire works.
  mpgc::testing::Process bridge({bin + "/mpgc_ship_bridge", "--domain", std::to_string(domain), "--set", "gpsd.port=1",
                                 "--set", "actuators.port=" + std::to_string(orders_port), "--set",
                                 "actuators.feedback_port=" + std::to_string(feedback_port), "--set",
                                 "actuators.command_timeout=1", "--set", "actuators.max_rudder=35", "--set",
                                 "actuators.max_rpm=120", "--log-level", "error"});
  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::ActuatorCommand> cmd_t(part, mpgc::topics::kActuators);
  dds::Topic<msg::NavState> nav_t(part, mpgc::topics::kOwnState);
  dds::Writer<msg::ActuatorCommand> cmd(part, cmd_t, dds::QosProfile::command(16));
  dds::Reader<msg::NavState> nav(part, nav_t, dds::QosProfile::state());
  mpgc::net::UdpSender feedback("127.0.0.1", feedback_port);

  // Sends `c` for a while and returns the last ROR and PRC values seen on the wire.
  const auto order_for = [&](double rudder, double rpm, double* ror, double* prc) {
    *ror = *prc = std::nan("");
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
    int seen = 0;
    while (std::chrono::steady_clock::now() < end && seen < 5) {
      msg::ActuatorCommand a{};
      a.header.stamp_ns = dds_time();
      a.rudder = rudder;
      a.propeller_rpm = rpm;
      cmd.write(a);
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      for (const auto& l : orders.receive_lines()) {
        std::string why;
        const auto s = mpgc::nmea::parse(l, &why);
        ASSERT_TRUE(s) << l << ": " << why;
        if (s->type == "ROR") *ror = mpgc::nmea::parse_ror(*s, &why)->rudder_deg, ++seen;
        if (s->type == "PRC") *prc = mpgc::nmea::parse_prc(*s, &why)->rpm;
      }
    }
  };
  double ror = 0, prc = 0;
  order_for(0.2, 80.0, &ror, &prc);
  EXPECT_NEAR(ror, geo::rad2deg(0.2), 0.005);
  EXPECT_NEAR(prc, 80.0, 0.005);
  order_for(-0.2, 80.0, &ror, &prc);
  EXPECT_NEAR(ror, -geo::rad2deg(0.2), 0.005) << "negative (port) rudder";
  order_for(1.0, 200.0, &ror, &prc);  // beyond both limits: saturated, not dropped
  EXPECT_NEAR(ror, 35.0, 0.005);
  EXPECT_NEAR(prc, 120.0, 0.005);
  order_for(-0.7, -5.0, &ror, &prc);
  EXPECT_NEAR(ror, -35.0, 0.005);
  EXPECT_NEAR(prc, 0.0, 0.005);

  // Commands stop: within command_timeout (+ a margin) the orders stop too.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  orders.receive_lines();
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  EXPECT_TRUE(orders.receive_lines().empty()) << "orders still sent 2.5 s after the last command";

  // Feedback: RSA and RPM become the NavState's rudder and rpm with NAV_ACTUATORS_VALID.
  bool got = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!got && std::chrono::steady_clock::now() < end) {
    feedback.send(mpgc::nmea::rsa("ER", -12.5) + mpgc::nmea::rpm("ER", 77.25));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (const auto& s : nav.take()) {
      if (!(s.value.valid_mask & msg::NAV_ACTUATORS_VALID)) continue;
      EXPECT_NEAR(geo::rad2deg(s.value.rudder), -12.5, 1e-9);
      EXPECT_NEAR(s.value.propeller_rpm, 77.25, 1e-9);
      EXPECT_EQ(s.value.valid_mask & msg::NAV_POSITION_VALID, 0u) << "no gpsd, yet a valid position";
      EXPECT_TRUE(std::isnan(s.value.x));
      got = true;
    }
  }
  EXPECT_TRUE(got) << "no NavState with the actuator feedback";
  EXPECT_TRUE(bridge.running());
}
