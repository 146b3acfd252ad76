// Bad navigation is marked explicitly, end to end: the real mpgc_ship_bridge process fed by a real
// gpsd (loopback, one UDP device), read back over DDS. The test plays the ship's GNSS receiver: it
// sends RMC+GGA+VTG (+HDT, so that health can be OK) datagrams encoded with the project's NMEA
// encoder, with current UTC times, and then breaks them: it stops sending (stale), reports no fix,
// jumps 5 km, sends 2-D fixes where 3-D is required, and takes gpsd away and brings it back.
// An invalid position must have its NAV_POSITION_VALID (and NAV_VELOCITY_VALID) bit clear and
// x, y, lat, lon (sog, cog) NaN: never zeros, never the last value as if fresh.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "gpsd_harness.hpp"
#include "mpgc/dds/dds.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/topics.hpp"

namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace geo = mpgc::geo;
namespace nmea = mpgc::nmea;

namespace {

constexpr double kLat0 = 59.40, kLon0 = 10.60;  // [deg] NED origin of the bridge and of the track (Oslofjord)
constexpr double kSpeed = 5.0;                  // [m/s] the track runs north at this speed
constexpr double kFixTimeout = 1.0;             // [s] nav.fix_timeout of every bridge here
constexpr double kCycle = 0.2;                  // [s] one GNSS cycle (5 Hz)

double secs(int64_t ns) { return static_cast<double>(ns) * 1e-9; }
std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

bool pos_valid(const msg::NavState& s) { return (s.valid_mask & msg::NAV_POSITION_VALID) != 0; }
bool vel_valid(const msg::NavState& s) { return (s.valid_mask & msg::NAV_VELOCITY_VALID) != 0; }

std::string describe(const msg::NavState& s) {
  char b[256];
  std::snprintf(b, sizeof b, "mask=0x%x x=%.3f y=%.3f lat=%.7f lon=%.7f sog=%.3f cog=%.3f", s.valid_mask, s.x, s.y,
                geo::rad2deg(s.lat), geo::rad2deg(s.lon), s.sog, s.cog);
  return b;
}

// Position and velocity invalid and said so: both bits clear, their values NaN.
::testing::AssertionResult marked_invalid(const msg::NavState& s) {
  if (pos_valid(s) || vel_valid(s)) return ::testing::AssertionFailure() << "position/velocity bit set: " << describe(s);
  if (!(std::isnan(s.x) && std::isnan(s.y) && std::isnan(s.lat) && std::isnan(s.lon)))
    return ::testing::AssertionFailure() << "invalid position is not NaN: " << describe(s);
  if (!(std::isnan(s.sog) && std::isnan(s.cog)))
    return ::testing::AssertionFailure() << "invalid velocity is not NaN: " << describe(s);
  return ::testing::AssertionSuccess();
}

// A valid position with finite values (and velocity valid too: every fix here has SOG and COG).
::testing::AssertionResult marked_valid(const msg::NavState& s) {
  if (!pos_valid(s)) return ::testing::AssertionFailure() << "position invalid: " << describe(s);
  if (!vel_valid(s)) return ::testing::AssertionFailure() << "velocity invalid: " << describe(s);
  if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.lat) && std::isfinite(s.lon) &&
        std::isfinite(s.sog) && std::isfinite(s.cog)))
    return ::testing::AssertionFailure() << "valid but not finite: " << describe(s);
  return ::testing::AssertionSuccess();
}

// The ship's GNSS receiver: one datagram per cycle to gpsd's UDP device.
class Receiver {
 public:
  explicit Receiver(int gpsd_udp_port) : port_(gpsd_udp_port), ned_({geo::deg2rad(kLat0), geo::deg2rad(kLon0)}) {}

  // RMC + GGA + VTG (+ GPHDT = COG) for the NED position (x, y) [m], moving north at kSpeed.
  // quality 0: RMC status V and GGA quality 0 (no fix). altitude NaN: GGA without altitude
  // (nmea::gga leaves the field empty), so gpsd has only a 2-D fix. Returns the send time [ns].
  int64_t send(double x, double y, int quality = 1, double altitude_m = 20.0) {
    const geo::LatLon ll = ned_.to_latlon({x, y});
    nmea::FixData f;
    f.utc_ns = dds_time();
    f.lat_deg = geo::rad2deg(ll.lat);
    f.lon_deg = geo::rad2deg(ll.lon);
    f.sog_kn = kSpeed / geo::kKnot;
    f.cog_deg = 0.0;
    f.quality = quality;
    f.altitude_m = altitude_m;
    const std::string d = nmea::rmc("GP", f) + nmea::gga("GP", f) + nmea::vtg("GP", f) + nmea::hdt("GP", f.cog_deg);
    tx_.send(port_, d);
    last_ns_ = f.utc_ns;
    ++sent_;
    return f.utc_ns;
  }
  // A no-fix cycle with every position and velocity field empty: the encoder with position, SOG
  // and COG NaN writes RMC status V, GGA quality 0 and VTG mode N with empty fields.
  int64_t send_no_fix_empty() {
    nmea::FixData f;
    f.utc_ns = dds_time();
    f.lat_deg = f.lon_deg = f.sog_kn = f.cog_deg = f.hdop = f.altitude_m = std::nan("");
    f.quality = 0;
    f.satellites = 0;
    tx_.send(port_, nmea::rmc("GP", f) + nmea::gga("GP", f) + nmea::vtg("GP", f));
    last_ns_ = f.utc_ns;
    ++sent_;
    return f.utc_ns;
  }
  int64_t last_send_ns() const { return last_ns_; }
  int sent() const { return sent_; }
  void set_port(int p) { port_ = p; }

 private:
  int port_;
  geo::LocalNed ned_;
  mpgc::hil::UdpSender tx_;
  int64_t last_ns_ = 0;
  int sent_ = 0;
};

// The track: north at kSpeed from the origin, starting when constructed (wall time).
struct Track {
  int64_t t0 = dds_time();
  double x(int64_t at_ns) const { return kSpeed * secs(at_ns - t0); }
  double x_now() const { return x(dds_time()); }
};

struct NavRec {
  int64_t t;  // header stamp [ns] (the bridge's wall clock)
  msg::NavState s;
};
struct HealthRec {
  int64_t t;
  msg::HealthState state;
  std::string detail;
  std::map<std::string, uint64_t> counters;
};

// The real bridge process on a DDS domain of its own, and what it published.
class Bridge {
 public:
  Bridge(int gpsd_port, const std::vector<std::string>& sets)
      : part_(static_cast<uint32_t>(mpgc::testing::unique_domain())),
        nav_t_(part_, mpgc::topics::kOwnState),
        health_t_(part_, mpgc::topics::kHealth),
        nav_(part_, nav_t_, deep_state()),
        health_(part_, health_t_, dds::QosProfile::latched(32)) {
    std::vector<std::string> args = {mpgc::testing::bin_dir() + "/mpgc_ship_bridge",
                                     "--domain", std::to_string(mpgc::testing::unique_domain()),
                                     "--log-level", "warn"};
    std::vector<std::string> all = {"gpsd.port=" + std::to_string(gpsd_port), "gpsd.reconnect=0.5", "period=0.1",
                                    "health.period=0.2", "nav.fix_timeout=" + fmt("%.3f", kFixTimeout),
                                    "origin.source=param", "origin.lat=" + fmt("%.9f", kLat0),
                                    "origin.lon=" + fmt("%.9f", kLon0)};
    all.insert(all.end(), sets.begin(), sets.end());
    for (const auto& s : all) args.insert(args.end(), {"--set", s});
    proc_ = std::make_unique<mpgc::testing::Process>(args);
  }

  bool running() const { return proc_->running(); }

  void pump() {
    for (const auto& s : nav_.take()) navs.push_back({s.value.header.stamp_ns, s.value});
    for (const auto& s : health_.take()) {
      if (s.value.component != "ship_bridge") continue;
      HealthRec h{s.value.header.stamp_ns, s.value.state, s.value.detail, {}};
      for (const auto& c : s.value.counters) h.counters[c.name] = c.value;
      healths.push_back(std::move(h));
    }
  }

  // Runs for `seconds`: `tick` every tick_period (first at once), DDS taken every 5 ms; returns early
  // with true once `until` holds.
  bool run(double seconds, const std::function<void()>& tick, const std::function<bool()>& until = {},
           double tick_period = kCycle) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(static_cast<int64_t>(seconds * 1e6));
    auto next = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() < end) {
      if (tick && std::chrono::steady_clock::now() >= next) {
        tick();
        next += std::chrono::microseconds(static_cast<int64_t>(tick_period * 1e6));
      }
      pump();
      if (until && until()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    pump();
    return until && until();
  }

  // The bridge has published health after its first cycle and is connected to gpsd.
  bool connected() const {
    return !healths.empty() && healths.back().state != msg::HealthState::HEALTH_STARTING &&
           healths.back().detail.find("not connected") == std::string::npos;
  }
  const HealthRec* last_health() const { return healths.empty() ? nullptr : &healths.back(); }
  std::string last_detail() const { return healths.empty() ? "(no health sample)" : healths.back().detail; }
  uint64_t counter(const std::string& name) const {
    if (healths.empty()) return 0;
    const auto it = healths.back().counters.find(name);
    return it == healths.back().counters.end() ? 0 : it->second;
  }
  // The first NavState stamped at or after t with a valid position; nullptr if none.
  const NavRec* first_valid_after(int64_t t) const {
    for (const auto& n : navs)
      if (n.t >= t && pos_valid(n.s)) return &n;
    return nullptr;
  }
  const NavRec* first_invalid_after(int64_t t) const {
    for (const auto& n : navs)
      if (n.t >= t && !pos_valid(n.s)) return &n;
    return nullptr;
  }

  // deques: what pointers the tests keep to a record stay valid while more arrive.
  std::deque<NavRec> navs;
  std::deque<HealthRec> healths;

 private:
  // The state profile with history, so that no NavState is overwritten between two takes.
  static dds::QosProfile deep_state() {
    auto q = dds::QosProfile::state();
    q.depth = 64;
    return q;
  }
  dds::Participant part_;
  dds::Topic<msg::NavState> nav_t_;
  dds::Topic<msg::ComponentHealth> health_t_;
  dds::Reader<msg::NavState> nav_;
  dds::Reader<msg::ComponentHealth> health_;
  std::unique_ptr<mpgc::testing::Process> proc_;
};

std::string health_trace(const Bridge& b, int64_t t0) {
  std::string out;
  std::string last;
  for (const auto& h : b.healths) {
    const std::string line = std::to_string(static_cast<int>(h.state)) + " '" + h.detail + "'";
    if (line == last) continue;
    last = line;
    out += "  " + fmt("%+.2f s ", secs(h.t - t0)) + line + "\n";
  }
  return out;
}

}  // namespace

#define MPGC_START_GPSD(var)                                                                                   \
  ASSERT_FALSE(::mpgc::hil::find_exe("gpsd").empty()) << "gpsd is not installed: apt-get install gpsd gpsd-clients"; \
  auto var = ::mpgc::hil::GpsdProcess::udp(1);                                                                 \
  ASSERT_TRUE(var.ok()) << "gpsd did not start: " << var.error()

// 1. Fixes at 5 Hz for 3 s: valid (health OK). They stop: within fix_timeout + 0.5 s every NavState
// has the position invalid and NaN, and health is DEGRADED naming "position stale".
TEST(ShipBridgeFaults, StalePositionIsInvalidNaNAndDegraded) {
  MPGC_START_GPSD(gpsd);
  Bridge b(gpsd.port(), {});
  ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
  Receiver rx(gpsd.udp_port(0));
  Track tr;
  const auto good = [&] { rx.send(tr.x_now(), 0.0); };
  ASSERT_TRUE(b.run(10, good, [&] { return b.first_valid_after(tr.t0) != nullptr; }))
      << "no valid position from good fixes; health: " << b.last_detail();
  const int64_t t_valid = b.first_valid_after(tr.t0)->t;
  b.run(3.0, good);
  const int64_t t_last = rx.last_send_ns();
  ASSERT_NE(b.last_health(), nullptr);
  EXPECT_EQ(b.last_health()->state, msg::HealthState::HEALTH_OK) << "with good fixes and heading: " << b.last_detail();

  int n_valid = 0;
  for (const auto& n : b.navs)
    if (n.t >= t_valid && n.t <= t_last) {
      EXPECT_TRUE(marked_valid(n.s)) << fmt("%+.2f s", secs(n.t - t_last));
      EXPECT_NEAR(n.s.x, tr.x(n.t), 10.0) << "valid position off the track";
      EXPECT_NEAR(n.s.y, 0.0, 1.0);
      ++n_valid;
    }
  EXPECT_GE(n_valid, 20) << "3 s of good fixes at period 0.1";

  // The fixes stop.
  b.run(kFixTimeout + 2.5, {});
  const NavRec* first_inv = b.first_invalid_after(t_last);
  ASSERT_NE(first_inv, nullptr) << "still valid " << kFixTimeout + 2.5 << " s after the last fix";
  int n_after = 0;
  for (const auto& n : b.navs) {
    if (n.t <= t_last) continue;
    if (!pos_valid(n.s)) {
      EXPECT_TRUE(marked_invalid(n.s)) << fmt("%+.2f s after the last fix", secs(n.t - t_last));
    }
    if (n.t > t_last + static_cast<int64_t>((kFixTimeout + 0.5) * 1e9)) {
      EXPECT_TRUE(marked_invalid(n.s)) << fmt("%+.2f s after the last fix", secs(n.t - t_last));
      ++n_after;
    }
  }
  EXPECT_GE(n_after, 15) << "NavStates after fix_timeout + 0.5 s (2 s at period 0.1)";
  EXPECT_GE(first_inv->t, t_last + static_cast<int64_t>((kFixTimeout - 0.25) * 1e9))
      << "position invalid before fix_timeout";
  const HealthRec* stale = nullptr;
  for (const auto& h : b.healths)
    if (h.t > t_last && h.state == msg::HealthState::HEALTH_DEGRADED && h.detail.find("position stale") != std::string::npos) {
      stale = &h;
      break;
    }
  ASSERT_NE(stale, nullptr) << "no DEGRADED health naming 'position stale':\n" << health_trace(b, t_last);
  EXPECT_LE(stale->t, t_last + static_cast<int64_t>((kFixTimeout + 0.7) * 1e9)) << health_trace(b, t_last);
  EXPECT_EQ(b.last_health()->state, msg::HealthState::HEALTH_DEGRADED);
  EXPECT_NE(b.last_detail().find("position stale"), std::string::npos) << b.last_detail();
  std::printf("stale: %d valid NavStates over 3 s; after the last fix: first invalid %+.3f s, DEGRADED '%s' %+.3f s, "
              "%d NavStates after fix_timeout+0.5 s, all NaN\n",
              n_valid, secs(first_inv->t - t_last), stale->detail.c_str(), secs(stale->t - t_last), n_after);
  EXPECT_TRUE(b.running()) << "the bridge died";
}

// 2. A no-fix report after good fixes: position invalid at once (not after fix_timeout), counted
// as rejected.fix.no_fix, health DEGRADED "no fix"; good fixes again: valid again at once.
// with_position: the project's encoder with FixData.quality = 0 (RMC status V and GGA quality 0,
// the position fields still filled in, as receivers that keep their last or a dead-reckoned
// position send it); else the same with every position and velocity field empty (NaN in FixData).
static void no_fix_case(bool with_position) {
  MPGC_START_GPSD(gpsd);
  // A long fix_timeout: only the no-fix report itself can make the position invalid within 0.5 s.
  Bridge b(gpsd.port(), {"nav.fix_timeout=5"});
  ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
  mpgc::hil::GpsdWatch watch(gpsd.port());
  ASSERT_TRUE(watch.ok() && watch.await_watch(5000)) << watch.error();
  const auto tpv_modes = [&] {
    std::map<int, int> m;
    while (auto l = watch.line(50))
      if (mpgc::hil::json_class(*l) == "TPV") ++m[static_cast<int>(mpgc::hil::json_number(*l, "mode").value_or(-1))];
    return m;
  };
  Receiver rx(gpsd.udp_port(0));
  Track tr;
  const auto good = [&] { rx.send(tr.x_now(), 0.0); };
  ASSERT_TRUE(b.run(10, good, [&] { return b.first_valid_after(tr.t0) != nullptr; }))
      << "no valid position from good fixes; health: " << b.last_detail();
  b.run(1.5, good);
  EXPECT_EQ(b.counter("rejected.fix.no_fix"), 0u);
  tpv_modes();  // drop the good ones

  int64_t t_nofix = 0;
  const auto bad = [&] {
    const int64_t t = with_position ? rx.send(tr.x_now(), 0.0, /*quality=*/0) : rx.send_no_fix_empty();
    if (t_nofix == 0) t_nofix = t;
  };
  b.run(2.5, bad);
  const int64_t t_bad_end = rx.last_send_ns();
  const std::map<int, int> modes = tpv_modes();
  std::string modes_txt;
  for (const auto& [k, v] : modes) modes_txt += " mode " + std::to_string(k) + ": " + std::to_string(v);
  const NavRec* inv = b.first_invalid_after(t_nofix);
  int n_valid = 0, n_bad = 0;
  for (const auto& n : b.navs) {
    if (n.t < t_nofix || n.t > t_bad_end) continue;
    if (!pos_valid(n.s)) {
      EXPECT_TRUE(marked_invalid(n.s)) << fmt("%+.2f s after the first no-fix report", secs(n.t - t_nofix));
      ++n_bad;
    } else if (n.t > t_nofix + 500000000) {
      ++n_valid;
    }
  }
  b.run(1.0, {}, [&] { return b.counter("rejected.fix.no_fix") > 0; });
  const uint64_t no_fix = b.counter("rejected.fix.no_fix");
  std::printf("no fix (%s): gpsd TPVs%s; NavStates: first invalid %s, %d invalid, %d valid later than 0.5 s; "
              "rejected.fix.no_fix=%llu\n",
              with_position ? "RMC V + GGA quality 0 with position" : "empty fields", modes_txt.c_str(),
              inv ? fmt("%+.3f s", secs(inv->t - t_nofix)).c_str() : "never", n_bad, n_valid,
              static_cast<unsigned long long>(no_fix));
  EXPECT_EQ(n_valid, 0) << "position still valid during no-fix reports (RMC status V, GGA quality 0); gpsd TPVs"
                        << modes_txt << "; health: " << b.last_detail();
  ASSERT_NE(inv, nullptr) << "position valid throughout 2.5 s of no-fix reports";
  EXPECT_LE(inv->t, t_nofix + 500000000) << "invalid only " << secs(inv->t - t_nofix) << " s after the first no-fix report";
  EXPECT_GE(n_bad, 15);
  EXPECT_GT(no_fix, 0u) << "counter rejected.fix.no_fix on health";
  bool said_no_fix = false;
  for (const auto& h : b.healths)
    if (h.t > t_nofix && h.state == msg::HealthState::HEALTH_DEGRADED && h.detail.find("no fix") != std::string::npos)
      said_no_fix = true;
  EXPECT_TRUE(said_no_fix) << "health never DEGRADED naming 'no fix':\n" << health_trace(b, t_nofix);

  // Good fixes again: valid again at once (no stale wait).
  int64_t t_good = 0;
  const auto good2 = [&] {
    const int64_t t = rx.send(tr.x_now(), 0.0);
    if (t_good == 0) t_good = t;
  };
  b.run(3.0, good2, [&] { return t_good != 0 && b.first_valid_after(t_good) != nullptr; });
  const NavRec* back = t_good ? b.first_valid_after(t_good) : nullptr;
  ASSERT_NE(back, nullptr) << "no valid position after good fixes came back";
  EXPECT_TRUE(marked_valid(back->s));
  EXPECT_LE(back->t, t_good + 700000000);
  std::printf("no fix (%s): valid again %+.3f s after good fixes\n", with_position ? "with position" : "empty fields",
              secs(back->t - t_good));
  EXPECT_TRUE(b.running()) << "the bridge died";
}

TEST(ShipBridgeFaults, NoFixReportIsInvalidAtOnce) { no_fix_case(/*with_position=*/true); }
TEST(ShipBridgeFaults, NoFixReportWithEmptyFieldsIsInvalidAtOnce) { no_fix_case(/*with_position=*/false); }

// 3. One fix 5 km off a 5 m/s track: rejected (rejected.fix.jump), the position stays on the track.
// Then the far position persists: the old position goes stale (invalid, NaN) and after that the new
// position is taken (valid near the new place): old -> invalid -> new, never old -> new.
TEST(ShipBridgeFaults, JumpRejectedThenRelocationAfterStale) {
  MPGC_START_GPSD(gpsd);
  Bridge b(gpsd.port(), {});
  ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
  Receiver rx(gpsd.udp_port(0));
  Track tr;
  constexpr double kFar = 5000.0;  // [m] east
  const auto good = [&] { rx.send(tr.x_now(), 0.0); };
  ASSERT_TRUE(b.run(10, good, [&] { return b.first_valid_after(tr.t0) != nullptr; }))
      << "no valid position from good fixes; health: " << b.last_detail();
  const int64_t t_valid = b.first_valid_after(tr.t0)->t;
  b.run(1.5, good);

  // One fix 5 km away within the track, then the track again.
  const int64_t t_jump = rx.send(tr.x_now(), kFar);
  std::this_thread::sleep_for(std::chrono::milliseconds(static_cast<int>(kCycle * 1000)));
  b.run(2.0, good);
  b.run(1.0, good, [&] { return b.counter("rejected.fix.jump") >= 1; });
  const int64_t t_a_end = rx.last_send_ns();
  EXPECT_GE(b.counter("rejected.fix.jump"), 1u) << "the 5 km jump was not counted";
  const NavRec* prev = nullptr;
  int n_a = 0;
  for (const auto& n : b.navs) {
    if (n.t < t_valid || n.t > t_a_end) continue;
    ++n_a;
    EXPECT_TRUE(marked_valid(n.s)) << fmt("%+.2f s from the jump fix", secs(n.t - t_jump));
    if (!pos_valid(n.s)) continue;
    EXPECT_NEAR(n.s.y, 0.0, 1.0) << "the jump fix was taken: " << fmt("%+.2f s ", secs(n.t - t_jump)) << describe(n.s);
    EXPECT_NEAR(n.s.x, tr.x(n.t), 10.0) << "off the track " << fmt("%+.2f s ", secs(n.t - t_jump)) << describe(n.s);
    if (prev != nullptr) {
      const double d = std::hypot(n.s.x - prev->s.x, n.s.y - prev->s.y);
      EXPECT_LE(d, kSpeed * secs(n.t - prev->t) + 5.0)
          << "position not continuous " << fmt("%+.2f s", secs(n.t - t_jump)) << ": " << describe(prev->s) << " -> "
          << describe(n.s);
    }
    prev = &n;
  }
  ASSERT_NE(prev, nullptr);
  const uint64_t jumps_a = b.counter("rejected.fix.jump");

  // The far position persists (a real relocation, or a receiver that stays wrong).
  int64_t t_far = 0;
  const auto far = [&] {
    const int64_t t = rx.send(tr.x_now(), kFar);
    if (t_far == 0) t_far = t;
  };
  // At 20 Hz, faster than the bridge's period, so that a far fix is waiting in every bridge cycle,
  // also in the one in which the old fix expires. (At 5 Hz that depends on the phase of the two.)
  b.run(kFixTimeout + 3.0, far, {}, 0.05);
  const int64_t t_b_end = rx.last_send_ns();
  const double old_x = prev->s.x;  // the last valid position on the track
  // 0 old (on the pre-jump track), 1 invalid and NaN, 2 new (near the far place), -1 anything else.
  int phase = 0, n_old = 0, n_inv = 0, n_new = 0;
  int64_t t_last_old = 0, t_first_inv = 0, t_first_new = 0;
  for (const auto& n : b.navs) {
    if (n.t <= t_a_end || n.t > t_b_end) continue;
    int k = -1;
    if (!pos_valid(n.s) && marked_invalid(n.s)) k = 1;
    else if (pos_valid(n.s) && std::abs(n.s.y) < 1.0 && std::abs(n.s.x - old_x) < 10.0) k = 0;
    else if (pos_valid(n.s) && std::abs(n.s.y - kFar) < 1.0 && std::abs(n.s.x - tr.x(n.t)) < 10.0) k = 2;
    ASSERT_NE(k, -1) << "neither the old track, nor invalid, nor the new place " << fmt("%+.2f s ", secs(n.t - t_far))
                     << describe(n.s);
    EXPECT_GE(k, phase) << "after " << (phase == 1 ? "invalid" : "the new position") << " came "
                        << (k == 0 ? "the old position" : "invalid") << fmt(" at %+.2f s", secs(n.t - t_far));
    phase = std::max(phase, k);
    if (k == 0) ++n_old, t_last_old = n.t;
    if (k == 1 && n_inv++ == 0) t_first_inv = n.t;
    if (k == 2 && n_new++ == 0) t_first_new = n.t;
  }
  std::printf("jump: %d valid NavStates on the track around the one 5 km fix (rejected.fix.jump=%llu); far position "
              "persisting: %d old (last %+.3f s), %d invalid (first %+.3f s), %d new (first %+.3f s), "
              "rejected.fix.jump=%llu\n",
              n_a, static_cast<unsigned long long>(jumps_a), n_old, t_last_old ? secs(t_last_old - t_far) : 0.0, n_inv,
              t_first_inv ? secs(t_first_inv - t_far) : 0.0, n_new, t_first_new ? secs(t_first_new - t_far) : 0.0,
              static_cast<unsigned long long>(b.counter("rejected.fix.jump")));
  EXPECT_GE(n_inv, 1) << "the bridge went from the old position straight to one 5 km away: no invalid NavState between "
                         "(the old fix never showed stale before the far position was taken)";
  EXPECT_GE(n_new, 5) << "the persisting far position was never taken";
  if (n_new > 0) {
    EXPECT_LE(t_first_new, t_far + static_cast<int64_t>((kFixTimeout + 1.0) * 1e9)) << "far position taken late";
  }
  if (n_old > 0) {
    EXPECT_LE(t_last_old, t_far + static_cast<int64_t>((kFixTimeout + 0.3) * 1e9)) << "old position kept past fix_timeout";
  }
  EXPECT_GT(b.counter("rejected.fix.jump"), jumps_a) << "the far fixes before the timeout were not rejected as jumps";
  EXPECT_TRUE(b.running()) << "the bridge died";
}

// 4. GGA without altitude: gpsd has a 2-D fix (TPV mode 2). With nav.require_3d the position is
// invalid (rejected.fix.2d, health "2-D fix"); 3-D fixes on the same bridge are valid; the same 2-D
// stream to a bridge without require_3d is valid.
TEST(ShipBridgeFaults, TwoDimensionalFixWhereThreeDimensionalIsRequired) {
  MPGC_START_GPSD(gpsd);
  mpgc::hil::GpsdWatch watch(gpsd.port());
  ASSERT_TRUE(watch.ok() && watch.await_watch(5000)) << watch.error();
  const auto tpv_modes = [&] {
    std::map<int, int> m;
    while (auto l = watch.line(50))
      if (mpgc::hil::json_class(*l) == "TPV") ++m[static_cast<int>(mpgc::hil::json_number(*l, "mode").value_or(-1))];
    return m;
  };
  const auto modes_str = [](const std::map<int, int>& m) {
    std::string s;
    for (const auto& [k, v] : m) s += " mode " + std::to_string(k) + ": " + std::to_string(v);
    return s;
  };
  Receiver rx(gpsd.udp_port(0));
  Track tr;
  const auto two_d = [&] { rx.send(tr.x_now(), 0.0, 1, std::nan("")); };
  const auto three_d = [&] { rx.send(tr.x_now(), 0.0); };
  int64_t t_3d = 0;
  {
    Bridge b(gpsd.port(), {"nav.require_3d=true"});
    ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
    tpv_modes();  // drop what came before
    const int64_t t0 = dds_time();
    b.run(4.0, two_d);
    const auto m2 = tpv_modes();
    EXPECT_GT(m2.count(2) ? m2.at(2) : 0, 10) << "gpsd TPVs for GGA without altitude:" << modes_str(m2);
    EXPECT_EQ(m2.count(3), 0u) << "gpsd reported 3-D for GGA without altitude:" << modes_str(m2);
    int n = 0;
    for (const auto& r : b.navs)
      if (r.t >= t0) {
        EXPECT_TRUE(marked_invalid(r.s)) << "2-D fix with require_3d " << fmt("%+.2f s", secs(r.t - t0));
        ++n;
      }
    EXPECT_GE(n, 30);
    b.run(1.0, two_d, [&] { return b.counter("rejected.fix.2d") > 0; });
    EXPECT_GT(b.counter("rejected.fix.2d"), 0u) << "counter rejected.fix.2d on health";
    EXPECT_EQ(b.last_health()->state, msg::HealthState::HEALTH_DEGRADED);
    EXPECT_NE(b.last_detail().find("2-D fix"), std::string::npos) << b.last_detail();
    const uint64_t n2d = b.counter("rejected.fix.2d");

    // Control: 3-D fixes on the same bridge are taken.
    const auto first = [&](const std::function<void()>& send) {
      int64_t t = 0;
      b.run(3.0, [&] {
        send();
        if (t == 0) t = rx.last_send_ns();
      }, [&] { return t != 0 && b.first_valid_after(t) != nullptr; });
      return t;
    };
    t_3d = first(three_d);
    const NavRec* v = b.first_valid_after(t_3d);
    ASSERT_NE(v, nullptr) << "3-D fixes not taken with require_3d: " << b.last_detail();
    b.run(2.0, three_d);
    const auto m3 = tpv_modes();
    EXPECT_GT(m3.count(3) ? m3.at(3) : 0, 5) << modes_str(m3);
    int flicker = 0;
    for (const auto& r : b.navs)
      if (r.t >= v->t && !pos_valid(r.s)) ++flicker;
    EXPECT_EQ(flicker, 0) << "3-D stream under require_3d: invalid NavStates after the first valid one (gpsd TPVs:"
                          << modes_str(m3) << ")";
    // Back to 2-D: invalid at once (no fix_timeout wait).
    int64_t t_back = 0;
    b.run(1.5, [&] {
      two_d();
      if (t_back == 0) t_back = rx.last_send_ns();
    });
    const NavRec* inv = b.first_invalid_after(t_back);
    ASSERT_NE(inv, nullptr);
    EXPECT_LE(inv->t, t_back + 500000000) << "2-D fix after 3-D ones made the position invalid only after "
                                          << secs(inv->t - t_back) << " s";
    EXPECT_GT(b.counter("rejected.fix.2d"), n2d);
    std::printf("2-D, require_3d: %d NavStates all invalid, rejected.fix.2d=%llu, gpsd%s; 3-D valid %+.3f s after "
                "the first 3-D fix (gpsd%s); 2-D again: invalid %+.3f s after\n",
                n, static_cast<unsigned long long>(b.counter("rejected.fix.2d")), modes_str(m2).c_str(),
                secs(v->t - t_3d), modes_str(m3).c_str(), secs(inv->t - t_back));
    EXPECT_TRUE(b.running()) << "the bridge died";
  }
  {
    // The same 2-D stream without require_3d: valid.
    Bridge b(gpsd.port(), {});
    ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
    tpv_modes();
    const int64_t t0 = dds_time();
    ASSERT_TRUE(b.run(5.0, two_d, [&] { return b.first_valid_after(t0) != nullptr; }))
        << "2-D fixes without require_3d not taken: " << b.last_detail();
    const NavRec* v = b.first_valid_after(t0);
    const int64_t t_v = v->t;
    b.run(2.0, two_d);
    const auto m2 = tpv_modes();
    EXPECT_EQ(m2.count(3), 0u) << modes_str(m2);
    int n = 0;
    for (const auto& r : b.navs)
      if (r.t >= t_v) {
        EXPECT_TRUE(marked_valid(r.s)) << "2-D fix without require_3d " << fmt("%+.2f s", secs(r.t - t_v));
        ++n;
      }
    EXPECT_GE(n, 15);
    EXPECT_EQ(b.counter("rejected.fix.2d"), 0u);
    std::printf("2-D without require_3d: valid %+.3f s after the first fix, %d valid NavStates\n", secs(t_v - t0), n);
    EXPECT_TRUE(b.running()) << "the bridge died";
  }
}

// 5. gpsd goes away: the bridge says "gpsd ... not connected" (DEGRADED), counts gpsd.disconnects,
// the position goes stale (NaN); gpsd comes back on the same port: the bridge reconnects by itself,
// fixes are valid again and health is OK again.
TEST(ShipBridgeFaults, GpsdGoesAwayAndComesBack) {
  MPGC_START_GPSD(gpsd);
  const int port = gpsd.port(), udp = gpsd.udp_port(0);
  Bridge b(port, {});
  ASSERT_TRUE(b.run(15, {}, [&] { return b.connected(); })) << "bridge not connected to gpsd: " << b.last_detail();
  Receiver rx(udp);
  Track tr;
  const auto good = [&] { rx.send(tr.x_now(), 0.0); };
  ASSERT_TRUE(b.run(10, good, [&] {
    return b.first_valid_after(tr.t0) != nullptr && b.last_health()->state == msg::HealthState::HEALTH_OK;
  })) << "no valid position / health OK from good fixes; health: " << b.last_detail();
  b.run(1.0, good);
  EXPECT_EQ(b.counter("gpsd.disconnects"), 0u);

  // gpsd goes away (the receiver keeps sending into the void).
  gpsd.stop();
  const int64_t t_kill = dds_time();
  const std::string not_connected = "gpsd 127.0.0.1:" + std::to_string(port) + " not connected";
  b.run(kFixTimeout + 2.0, good);
  const HealthRec* gone = nullptr;
  for (const auto& h : b.healths)
    if (h.t >= t_kill && h.detail.find(not_connected) != std::string::npos) {
      gone = &h;
      break;
    }
  ASSERT_NE(gone, nullptr) << "health never said '" << not_connected << "':\n" << health_trace(b, t_kill);
  EXPECT_EQ(gone->state, msg::HealthState::HEALTH_DEGRADED);
  EXPECT_LE(gone->t, t_kill + 700000000) << "gpsd's going away noticed only after " << secs(gone->t - t_kill) << " s";
  EXPECT_GE(b.counter("gpsd.disconnects"), 1u);
  EXPECT_GE(b.counter("gpsd.connect_failures"), 1u) << "no reconnection attempt while gpsd was away";
  int n_stale = 0;
  for (const auto& r : b.navs)
    if (r.t > t_kill + static_cast<int64_t>((kFixTimeout + 0.5) * 1e9)) {
      EXPECT_TRUE(marked_invalid(r.s)) << fmt("%+.2f s after gpsd went away", secs(r.t - t_kill));
      ++n_stale;
    }
  EXPECT_GE(n_stale, 5) << "NavStates while gpsd is away";

  // gpsd comes back on the same ports.
  auto again = mpgc::hil::GpsdProcess::udp_on(port, {udp});
  ASSERT_TRUE(again.ok()) << "gpsd did not start again on " << port << ": " << again.error();
  const int64_t t_back = dds_time();
  const bool back = b.run(10.0, good, [&] {
    return b.first_valid_after(t_back) != nullptr && b.last_health()->state == msg::HealthState::HEALTH_OK;
  });
  const NavRec* v = b.first_valid_after(t_back);
  ASSERT_TRUE(back) << "no valid position / health OK after gpsd came back: " << b.last_detail() << "\n"
                    << health_trace(b, t_back);
  b.run(1.0, good);
  for (const auto& r : b.navs)
    if (r.t >= v->t) {
      EXPECT_TRUE(marked_valid(r.s)) << fmt("%+.2f s after gpsd came back", secs(r.t - t_back));
    }
  EXPECT_NEAR(v->s.x, tr.x(v->t), 10.0);
  EXPECT_EQ(b.counter("gpsd.disconnects"), 1u) << "one outage, one disconnect";
  EXPECT_EQ(b.last_detail(), "");
  std::printf("gpsd away: '%s' %+.3f s after the kill, gpsd.disconnects=%llu, gpsd.connect_failures=%llu; back: "
              "valid %+.3f s after gpsd restarted, health OK\n",
              gone->detail.c_str(), secs(gone->t - t_kill), static_cast<unsigned long long>(b.counter("gpsd.disconnects")),
              static_cast<unsigned long long>(b.counter("gpsd.connect_failures")), secs(v->t - t_back));
  EXPECT_TRUE(b.running()) << "the bridge died";
}
