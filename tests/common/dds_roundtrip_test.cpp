// Every IDL type round-trips through Cyclone DDS (serialised and deserialised between two
// participants) with non-trivial strings and sequences, filled by a seeded generator.
#include <gtest/gtest.h>

#include <chrono>
#include <random>
#include <string>
#include <thread>
#include <type_traits>

#include "mpgc/dds/dds.hpp"
#include "mpgc/filler.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/testing.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;

namespace {

using mpgc::testing::Filler;

template <class Pred>
bool wait_for(Pred pred, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (pred()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return pred();
}

class RoundTrip : public ::testing::Test {
 protected:
  dds::Participant pub_{static_cast<uint32_t>(mpgc::testing::unique_domain())};
  dds::Participant sub_{static_cast<uint32_t>(mpgc::testing::unique_domain())};

  template <class T>
  void check_type(int samples) {
    SCOPED_TRACE(T::type_name);
    const std::string name = std::string("test/") + T::descriptor().m_typename;
    std::string topic_name;
    for (char ch : name) topic_name += (std::isalnum(static_cast<unsigned char>(ch)) || ch == '/') ? ch : '_';
    dds::Topic<T> tp(pub_, topic_name), ts(sub_, topic_name);
    dds::Writer<T> w(pub_, tp, dds::QosProfile::command(64));
    dds::Reader<T> r(sub_, ts, dds::QosProfile::command(64));
    ASSERT_TRUE(wait_for([&] { return w.matched() == 1 && r.matched() == 1; }, 10.0));
    std::mt19937_64 rng(std::hash<std::string>{}(T::type_name));
    std::vector<T> sent(samples);
    for (auto& s : sent) {
      Filler{rng}.fill(s);
      w.write(s);
    }
    std::vector<T> got;
    ASSERT_TRUE(wait_for([&] {
      for (auto& s : r.take()) got.push_back(s.value);
      return got.size() >= sent.size();
    }, 10.0)) << "received " << got.size() << " of " << sent.size();
    // Keyed types are delivered per instance; compare as multisets by searching.
    for (const auto& s : sent) EXPECT_NE(std::find(got.begin(), got.end(), s), got.end());
  }

  template <class... T>
  void check_all(dds::TypeList<T...>) {
    (check_type<T>(8), ...);
  }
};

}  // namespace

TEST_F(RoundTrip, CoreTypes) { check_all(msg::core_types{}); }
TEST_F(RoundTrip, NavTypes) { check_all(msg::nav_types{}); }
TEST_F(RoundTrip, SensorTypes) { check_all(msg::sensors_types{}); }
TEST_F(RoundTrip, TrackTypes) { check_all(msg::tracks_types{}); }
TEST_F(RoundTrip, ObstacleTypes) { check_all(msg::obstacles_types{}); }
TEST_F(RoundTrip, PlanTypes) { check_all(msg::plan_types{}); }
TEST_F(RoundTrip, ControlTypes) { check_all(msg::control_types{}); }

// A fixed-obstacle set of 1e5 points (~1.6 MB) crosses intact (fragmented, reliable).
TEST_F(RoundTrip, HundredThousandObstaclePoints) {
  dds::Topic<msg::FixedObstacles> tp(pub_, "test/big"), ts(sub_, "test/big");
  dds::Writer<msg::FixedObstacles> w(pub_, tp, dds::QosProfile::latched());
  dds::Reader<msg::FixedObstacles> r(sub_, ts, dds::QosProfile::latched());
  ASSERT_TRUE(wait_for([&] { return w.matched() == 1; }, 10.0));
  msg::FixedObstacles big;
  big.version = 42;
  big.chart = "US4MD81M";
  for (int i = 0; i < 100000; ++i) big.points.push_back({i * 0.5, -i * 0.25});
  big.polygons.push_back({7, {{0, 0}, {1, 0}, {1, 1}}});
  w.write(big);
  std::vector<msg::FixedObstacles> got;
  ASSERT_TRUE(wait_for([&] {
    for (auto& s : r.take()) got.push_back(s.value);
    return !got.empty();
  }, 20.0));
  EXPECT_TRUE(got.front() == big);
}

// Conversion alone: empty sequences and NULL strings from C come back as empty values.
TEST(Convert, NullStringsAndEmptySequences) {
  ::mpgc_msg_Path c{};
  msg::Path p;
  p.reason = "stale";
  p.waypoints.push_back({1, 2, 3, 4});
  from_c(c, p);
  EXPECT_EQ(p.reason, "");
  EXPECT_TRUE(p.waypoints.empty());
}
