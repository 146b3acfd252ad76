// The bridge component's logic without DDS, sockets or a clock (node.hpp): what main.cpp used to
// do inline, tested here directly.
#include <gtest/gtest.h>

#include <cmath>

#include "mpgc/testing_params.hpp"
#include "mpgc/ship_bridge/node.hpp"

namespace sb = mpgc::ship_bridge;

namespace {

sb::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  return mpgc::testing::declared<sb::NodeParams>([](mpgc::rt::ParamSet& ps, sb::NodeParams& p) { p.declare(ps); }, overrides);
}

TEST(BridgeNode, ParametersAndTheirChecks) {
  const sb::NodeParams p = declared();
  EXPECT_EQ(p.gpsd_port, 2947);
  EXPECT_FALSE(p.origin());  // the first fix
  EXPECT_NEAR(p.limits().max_rudder, 35.0 * M_PI / 180.0, 1e-12);
  EXPECT_THROW(declared({"actuators.min_rpm=200"}).validate(), std::invalid_argument);
  const auto o = declared({"origin.source=param", "origin.lat=10", "origin.lon=20"}).origin();
  ASSERT_TRUE(o);
  EXPECT_NEAR(o->lat, 10.0 * M_PI / 180.0, 1e-12);
}

TEST(BridgeNode, OnlyTheRawSentencesGpsdDoesNotDecodeAreTaken) {
  EXPECT_TRUE(sb::gpsd_nmea_used("$TIROT,1.0,A*00"));
  EXPECT_TRUE(sb::gpsd_nmea_used("$GPRMC,..."));
  EXPECT_FALSE(sb::gpsd_nmea_used("$GPVTG,..."));
  EXPECT_FALSE(sb::gpsd_nmea_used("$GPGGA"));  // too short to be a sentence
}

TEST(BridgeNode, WaterVelocityNeedsVelocityAndHeading) {
  sb::NavOutput o;
  o.sog = 5;
  o.cog = 0.1;
  o.heading = 0.0;
  EXPECT_TRUE(std::isnan(sb::water_velocity(o).u));
  o.velocity_valid = o.heading_valid = true;
  const auto w = sb::water_velocity(o);
  EXPECT_NEAR(w.u, 5 * std::cos(0.1), 1e-12);
  EXPECT_NEAR(w.v, 5 * std::sin(0.1), 1e-12);
}

TEST(BridgeNode, OrdersAreRepeatedWhileCommandsAreFreshAndStopOnce) {
  sb::OrderPacer pacer(declared({"actuators.period=0.2", "actuators.command_timeout=1"}));
  const int64_t ms = 1'000'000;
  EXPECT_FALSE(pacer.at(0, false, -1).send);  // no command yet
  EXPECT_TRUE(pacer.at(100 * ms, true, 100 * ms).send);
  EXPECT_FALSE(pacer.at(200 * ms, true, 100 * ms).send);  // within the period
  EXPECT_TRUE(pacer.at(300 * ms, true, 100 * ms).send);
  const auto stale = pacer.at(1200 * ms, true, 100 * ms);
  EXPECT_FALSE(stale.fresh);
  EXPECT_FALSE(stale.send);
  EXPECT_TRUE(stale.stopped);
  EXPECT_FALSE(pacer.at(1300 * ms, true, 100 * ms).stopped);  // said once
}

TEST(BridgeNode, HealthNamesGpsdNavigationAndOrders) {
  const sb::NodeParams p = declared();
  sb::NavOutput o;
  o.position_valid = o.heading_valid = o.velocity_valid = true;
  EXPECT_EQ(sb::health_text(p, o, false, true), "");
  o.heading_valid = false;
  o.why_invalid = "no heading";
  EXPECT_EQ(sb::health_text(p, o, true, false),
            "gpsd 127.0.0.1:2947 not connected; navigation invalid: no heading; no fresh control/actuators: no orders sent");
}

}  // namespace
