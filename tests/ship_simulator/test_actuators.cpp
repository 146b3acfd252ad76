// The ship's actuators: the one description of their limits (mpgc/ship/actuator_limits.hpp) and
// the models that obey it; saturation instead of refusal; the actuator watchdog (rudder amidships,
// engine to the safe order after a silence, back with the next order; never in a normal run).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/ship/actuator_limits.hpp"
#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/ship_simulator/mmg_model.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/testing.hpp"

namespace sim = mpgc::ship_simulator;
namespace ship = mpgc::ship;
using mpgc::geo::deg2rad;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int64_t kS = 1'000'000'000;
std::string data_dir() { return mpgc::testing::shared_data("ship_models"); }

void expect_equal(const ship::ActuatorLimits& a, const ship::ActuatorLimits& b, const char* what) {
  EXPECT_EQ(a.max_rudder, b.max_rudder) << what;
  EXPECT_EQ(a.max_rudder_rate, b.max_rudder_rate) << what;
  EXPECT_EQ(a.min_rpm, b.min_rpm) << what;
  EXPECT_EQ(a.max_rpm, b.max_rpm) << what;
}
}  // namespace

TEST(ActuatorLimits, Kvlcc2DescriptionAndValidation) {
  const auto k = ship::kvlcc2_actuator_limits();
  EXPECT_DOUBLE_EQ(k.max_rudder, deg2rad(35.0));
  EXPECT_LT(k.max_rudder, 0.6109) << "the old guidance_control limit that the ship refused";
  EXPECT_DOUBLE_EQ(k.max_rudder_rate, deg2rad(2.32));
  EXPECT_EQ(k.min_rpm, 0.0);
  EXPECT_EQ(k.max_rpm, 150.0);
  EXPECT_NO_THROW(k.validate());
  auto bad = [&](auto change, const char* field) {
    ship::ActuatorLimits l = k;
    change(l);
    try {
      l.validate("ship");
      ADD_FAILURE() << "accepted a bad " << field;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("ship.") + field), std::string::npos) << e.what();
    }
  };
  bad([](auto& l) { l.max_rudder = 0.0; }, "max_rudder");
  bad([](auto& l) { l.max_rudder = kNaN; }, "max_rudder");
  bad([](auto& l) { l.max_rudder = 2.0; }, "max_rudder");
  bad([](auto& l) { l.max_rudder_rate = -0.1; }, "max_rudder_rate");
  bad([](auto& l) { l.max_rudder_rate = std::numeric_limits<double>::infinity(); }, "max_rudder_rate");
  bad([](auto& l) { l.min_rpm = 200.0; }, "min_rpm/max_rpm");
  bad([](auto& l) { l.max_rpm = kNaN; }, "min_rpm/max_rpm");
}

TEST(ActuatorLimits, SaturateClipsAndSaysWhat) {
  const auto k = ship::kvlcc2_actuator_limits();
  auto o = ship::saturate(k, k.max_rudder, k.max_rpm);  // exactly at the limits: not saturated
  EXPECT_FALSE(o.rudder_saturated);
  EXPECT_FALSE(o.rpm_saturated);
  o = ship::saturate(k, 0.6109, 160.0);  // the old GC hard-over order
  EXPECT_TRUE(o.rudder_saturated);
  EXPECT_TRUE(o.rpm_saturated);
  EXPECT_EQ(o.rudder, k.max_rudder);
  EXPECT_EQ(o.rpm, k.max_rpm);
  o = ship::saturate(k, -1.0, -5.0);
  EXPECT_EQ(o.rudder, -k.max_rudder);
  EXPECT_EQ(o.rpm, k.min_rpm);
  EXPECT_TRUE(o.rudder_saturated && o.rpm_saturated);
  o = ship::saturate(k, 0.1, 80.0);
  EXPECT_EQ(o.rudder, 0.1);
  EXPECT_EQ(o.rpm, 80.0);
  EXPECT_FALSE(o.rudder_saturated || o.rpm_saturated);
}

// The default ship's models expose the description's limits (and the CSV's steering gear rate is
// the description's), so guidance_control's defaults are what the simulated ship obeys.
TEST(ActuatorLimits, ModelsObeyTheOneDescription) {
  const auto k = ship::kvlcc2_actuator_limits();
  expect_equal(sim::MmgModel(sim::kvlcc2_params()).actuator_limits(), k, "compiled-in MMG");
  EXPECT_EQ(sim::load_kvlcc2_csv(data_dir() + "/kvlcc2_mmg_parameters.csv").rudder_rate, k.max_rudder_rate)
      << "kvlcc2_mmg_parameters.csv delta_rate";
  expect_equal(sim::make_model({"mmg", data_dir(), "Mariner"})->actuator_limits(), k, "mmg from the CSV");
  expect_equal(sim::make_model({"nomoto", data_dir(), "Mariner"})->actuator_limits(), k, "nomoto");
  auto p = sim::kvlcc2_params();
  p.max_rudder = 2.0;  // no rudder turns beyond 90 deg
  EXPECT_THROW(sim::MmgModel{p}, std::invalid_argument);
}

TEST(Watchdog, ParamsValidated) {
  sim::WatchdogParams w;
  EXPECT_NO_THROW(w.validate());  // default: hold
  w.safe_rpm = 40.0;
  EXPECT_NO_THROW(w.validate());
  w.safe_rpm = -1.0;
  EXPECT_THROW(w.validate(), std::invalid_argument);
  w.safe_rpm = std::numeric_limits<double>::infinity();
  EXPECT_THROW(w.validate(), std::invalid_argument);
  w.safe_rpm = 40.0;
  w.timeout_s = 0.0;
  EXPECT_THROW(w.validate(), std::invalid_argument);
  w.timeout_s = kNaN;
  EXPECT_THROW(w.validate(), std::invalid_argument);
}

TEST(Watchdog, TripsAfterTheTimeoutReducesTheEngineAndRecovers) {
  sim::WatchdogParams w;
  w.timeout_s = 2.0;
  w.safe_rpm = 40.0;
  sim::ShipCommand cmd{0.0, 92.0};  // the ship's initial setting
  sim::DeviceOrders o;
  EXPECT_FALSE(sim::follow_orders(o, 100 * kS, w, &cmd)) << "no order yet: nothing to watch";
  EXPECT_EQ(cmd.rpm, 92.0);
  o = {0.3, 100.0, true, true, 10 * kS};
  EXPECT_FALSE(sim::follow_orders(o, 12 * kS, w, &cmd));  // 2.0 s: not beyond the timeout
  EXPECT_EQ(cmd.rudder, 0.3);
  EXPECT_EQ(cmd.rpm, 100.0);
  EXPECT_TRUE(sim::follow_orders(o, 12 * kS + 1, w, &cmd));
  EXPECT_EQ(cmd.rudder, 0.0) << "rudder amidships";
  EXPECT_EQ(cmd.rpm, 40.0) << "engine reduced to the safe order";
  o.rpm = 20.0;  // an order below the safe rpm is not raised
  EXPECT_TRUE(sim::follow_orders(o, 20 * kS, w, &cmd));
  EXPECT_EQ(cmd.rpm, 20.0);
  o = {-0.2, 90.0, true, true, 21 * kS};  // the next order ends it
  EXPECT_FALSE(sim::follow_orders(o, 21 * kS, w, &cmd));
  EXPECT_EQ(cmd.rudder, -0.2);
  EXPECT_EQ(cmd.rpm, 90.0);
  w.safe_rpm = kNaN;  // hold
  EXPECT_TRUE(sim::follow_orders(o, 30 * kS, w, &cmd));
  EXPECT_EQ(cmd.rudder, 0.0);
  EXPECT_EQ(cmd.rpm, 90.0);
  // The old form holds the engine too.
  EXPECT_TRUE(sim::follow_orders(o, 30 * kS, 2.0, &cmd));
  EXPECT_EQ(cmd.rpm, 90.0);
}

// In a normal run the orders come every control period (0.5 s) and the watchdog never trips;
// when they stop, the ship's rudder goes amidships and it slows towards steerage speed.
TEST(Watchdog, NeverTripsWithOrdersEveryControlPeriodAndSlowsTheShipWhenTheyStop) {
  auto m = sim::make_model({"mmg", data_dir(), "Mariner"});
  sim::ShipState s;
  s.u = 7.0;
  s.rpm = sim::straight_rpm(*m, 7.0);
  m->set_state(s);
  sim::WatchdogParams w;
  w.safe_rpm = sim::straight_rpm(*m, 3.0);
  sim::DeviceOrders o;
  sim::ShipCommand cmd{0.0, s.rpm};
  const int64_t step = kS / 10;
  int trips = 0;
  bool was = false;
  for (int64_t t = 0; t < 1200 * kS; t += step) {
    if (t % (kS / 2) == 0) o = {deg2rad(20.0), s.rpm, true, true, t};  // GC at 2 Hz, hard turn
    const bool tripped = sim::follow_orders(o, t, w, &cmd);
    trips += tripped && !was;
    was = tripped;
    m->step(0.1, cmd);
  }
  EXPECT_EQ(trips, 0);
  EXPECT_NEAR(m->state().rudder, deg2rad(20.0), 1e-6);
  const double r_turning = std::abs(m->state().r);
  const int64_t last = 1200 * kS - step;  // orders stop: the guidance died
  for (int64_t t = 1200 * kS; t < 3000 * kS; t += step) {
    const bool tripped = sim::follow_orders(o, t, w, &cmd);
    trips += tripped && !was;
    was = tripped;
    if (t - last > 2 * kS + step) {
      EXPECT_TRUE(tripped);
    }
    m->step(0.1, cmd);
  }
  EXPECT_EQ(trips, 1);
  EXPECT_NEAR(m->state().rudder, 0.0, 1e-9);
  EXPECT_NEAR(m->state().rpm, w.safe_rpm, 0.01);
  EXPECT_LT(m->state().u, 3.6);
  // Not still turning (KVLCC2 is slightly course-unstable: amidships leaves a slow drift of yaw).
  EXPECT_LT(std::abs(m->state().r), 0.2 * r_turning) << r_turning;
}
