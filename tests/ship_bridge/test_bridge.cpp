// Unit tests of the hardware-in-the-loop path without processes: the bridge's NavFusion,
// AisAssembler and actuator wire (encode_orders, apply_nmea_line), and the simulator as the ship's
// devices (ship_simulator::Devices). Sentences are checked field by field with the shared codec's
// framing parser; AIS payloads are read back by mpgc/testing_ais.hpp, independently of the encoder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/testing_ais.hpp"

using namespace mpgc;
namespace sb = mpgc::ship_bridge;
namespace sim = mpgc::ship_simulator;

namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kKn = geo::kKnot;

int64_t sec(double s) { return std::llround(s * 1e9); }

const geo::LatLon kOrigin{geo::deg2rad(59.9), geo::deg2rad(10.7)};

sb::GnssFix fix_at(double lat_deg, double lon_deg, int mode = 3, double speed = 5.0, double track_deg = 90.0) {
  sb::GnssFix f;
  f.mode = mode;
  f.lat_deg = lat_deg;
  f.lon_deg = lon_deg;
  f.speed = speed;
  f.track_deg = track_deg;
  return f;
}

// A fix at local (x, y) about `frame`.
sb::GnssFix fix_ned(const geo::LocalNed& frame, double x, double y, double speed = 5.0, double track_deg = 90.0) {
  const geo::LatLon ll = frame.to_latlon({x, y});
  return fix_at(geo::rad2deg(ll.lat), geo::rad2deg(ll.lon), 3, speed, track_deg);
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

uint64_t count(const std::map<std::string, uint64_t>& m, const std::string& k) {
  const auto it = m.find(k);
  return it == m.end() ? 0 : it->second;
}

// Every field of the state that carries a value NaN?
void expect_position_nan(const sb::NavOutput& o) {
  EXPECT_TRUE(std::isnan(o.x));
  EXPECT_TRUE(std::isnan(o.y));
  EXPECT_TRUE(std::isnan(o.lat));
  EXPECT_TRUE(std::isnan(o.lon));
}

// "$A,$B\r\n" -> lines without CR/LF.
std::vector<std::string> split_lines(const std::string& s) {
  std::vector<std::string> out;
  size_t pos = 0;
  while (pos < s.size()) {
    const size_t e = s.find("\r\n", pos);
    if (e == std::string::npos) {
      out.push_back(s.substr(pos));
      break;
    }
    out.push_back(s.substr(pos, e - pos));
    pos = e + 2;
  }
  return out;
}

nmea::Sentence must_parse(const std::string& line) {
  std::string why;
  const auto s = nmea::parse(line, &why);
  EXPECT_TRUE(s.has_value()) << line << ": " << why;
  return s.value_or(nmea::Sentence{});
}

// "ddmm.mmmmmm" + hemisphere -> degrees.
double coord_deg(const std::string& v, const std::string& hemi, int deg_digits) {
  if (v.size() < static_cast<size_t>(deg_digits)) return kNan;
  const double d = std::stod(v.substr(0, deg_digits)) + std::stod(v.substr(deg_digits)) / 60.0;
  return hemi == "S" || hemi == "W" ? -d : d;
}

double angle_diff_deg(double a, double b) { return std::fabs(std::remainder(a - b, 360.0)); }

double deg360(double rad) {
  const double d = std::fmod(geo::rad2deg(rad), 360.0);
  return d < 0 ? d + 360.0 : d;
}

struct Vdm {
  bool own = false;
  int n = 0, k = 0;
  std::string seq;
  char channel = '?';
  std::string payload;
  int fill = 0;
};
Vdm parse_vdm(const std::string& line) {
  const nmea::Sentence s = must_parse(line);
  Vdm v;
  EXPECT_EQ(s.start, '!') << line;
  EXPECT_EQ(s.talker, "AI") << line;
  EXPECT_TRUE(s.type == "VDM" || s.type == "VDO") << line;
  v.own = s.type == "VDO";
  if (s.fields.size() != 6) {
    ADD_FAILURE() << "VDM with " << s.fields.size() << " fields: " << line;
    return v;
  }
  v.n = std::atoi(s.fields[0].c_str());
  v.k = std::atoi(s.fields[1].c_str());
  v.seq = s.fields[2];
  v.channel = s.fields[3].empty() ? '?' : s.fields[3][0];
  v.payload = s.fields[4];
  v.fill = std::atoi(s.fields[5].c_str());
  return v;
}

sb::AisMessage ais_msg(int type, uint32_t mmsi) {
  sb::AisMessage m;
  m.type = type;
  m.mmsi = mmsi;
  return m;
}

sb::AisMessage position_msg(int type, uint32_t mmsi) {
  sb::AisMessage m = ais_msg(type, mmsi);
  m.has_position = true;
  m.lat_deg = 59.5;
  m.lon_deg = 10.5;
  m.sog = 6.0;
  m.cog_deg = 45.0;
  m.heading_deg = 44.0;
  m.turn_raw = 0;
  m.nav_status = 0;
  return m;
}

sb::AisMessage static_msg(int type, uint32_t mmsi) {
  sb::AisMessage m = ais_msg(type, mmsi);
  m.has_static = true;
  return m;
}

}  // namespace

// =====================================================================================
// NavFusion
// =====================================================================================

TEST(NavFusion, FirstGoodFixBecomesTheOrigin) {
  sb::NavFusion nav({}, std::nullopt);
  EXPECT_FALSE(nav.has_origin());
  EXPECT_EQ(nav.frame(), nullptr);
  const sb::NavOutput before = nav.state(sec(0.5));
  EXPECT_FALSE(before.position_valid);
  EXPECT_TRUE(contains(before.why_invalid, "no fix yet")) << before.why_invalid;
  expect_position_nan(before);

  EXPECT_EQ(nav.on_fix(fix_at(59.91, 10.72), sec(1)), "");
  ASSERT_TRUE(nav.has_origin());
  ASSERT_NE(nav.frame(), nullptr);
  EXPECT_DOUBLE_EQ(nav.frame()->origin().lat, geo::deg2rad(59.91));
  EXPECT_DOUBLE_EQ(nav.frame()->origin().lon, geo::deg2rad(10.72));
  const sb::NavOutput o = nav.state(sec(1));
  EXPECT_TRUE(o.position_valid) << o.why_invalid;
  EXPECT_EQ(o.x, 0.0);
  EXPECT_EQ(o.y, 0.0);
  EXPECT_DOUBLE_EQ(o.lat, geo::deg2rad(59.91));
  EXPECT_DOUBLE_EQ(o.lon, geo::deg2rad(10.72));

  // A second fix 50 m north of the first (inside 25 m/s * 1 s + 30 m) is in the first fix's frame.
  const geo::LocalNed f0({geo::deg2rad(59.91), geo::deg2rad(10.72)});
  EXPECT_EQ(nav.on_fix(fix_ned(f0, 50.0, 0.0), sec(2)), "");
  const sb::NavOutput o2 = nav.state(sec(2));
  EXPECT_NEAR(o2.x, 50.0, 1e-6);
  EXPECT_NEAR(o2.y, 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(nav.frame()->origin().lat, geo::deg2rad(59.91));  // the origin does not follow
}

TEST(NavFusion, ParameterOriginMatchesLocalNed) {
  sb::NavFusion nav({}, kOrigin);
  ASSERT_TRUE(nav.has_origin());
  const geo::LocalNed ref(kOrigin);
  EXPECT_EQ(nav.on_fix(fix_at(59.91, 10.72), sec(1)), "");
  const geo::NorthEast want = ref.to_ned({geo::deg2rad(59.91), geo::deg2rad(10.72)});
  ASSERT_GT(std::hypot(want.x, want.y), 1000.0);  // really away from the origin
  const sb::NavOutput o = nav.state(sec(1));
  ASSERT_TRUE(o.position_valid) << o.why_invalid;
  EXPECT_NEAR(o.x, want.x, 1e-6);
  EXPECT_NEAR(o.y, want.y, 1e-6);
  EXPECT_DOUBLE_EQ(nav.frame()->origin().lat, kOrigin.lat);
  EXPECT_DOUBLE_EQ(nav.frame()->origin().lon, kOrigin.lon);
}

TEST(NavFusion, NoFixMakesPositionInvalidAtOnce) {
  for (int mode : {0, 1}) {
    SCOPED_TRACE("mode " + std::to_string(mode));
    sb::NavFusion nav({}, kOrigin);
    const geo::LocalNed f(kOrigin);
    ASSERT_EQ(nav.on_fix(fix_ned(f, 100.0, 200.0), sec(1)), "");
    ASSERT_TRUE(nav.state(sec(1.5)).position_valid);
    sb::GnssFix nofix = fix_at(kNan, kNan, mode, kNan, kNan);
    const std::string why = nav.on_fix(nofix, sec(1.6));
    EXPECT_FALSE(why.empty());
    EXPECT_EQ(count(nav.rejected(), "fix.no_fix"), 1u);
    const sb::NavOutput o = nav.state(sec(1.6));  // well within fix_timeout of the good fix
    EXPECT_FALSE(o.position_valid);
    EXPECT_FALSE(o.velocity_valid);
    expect_position_nan(o);
    EXPECT_TRUE(std::isnan(o.sog));
    EXPECT_TRUE(std::isnan(o.cog));
    EXPECT_NE(o.x, 0.0);
    EXPECT_TRUE(contains(o.why_invalid, "no fix")) << o.why_invalid;
    // A no-fix report that carries the old coordinates is still no fix.
    sb::GnssFix nofix_with_values = fix_at(59.9, 10.7, mode);
    EXPECT_FALSE(nav.on_fix(nofix_with_values, sec(1.7)).empty());
    EXPECT_FALSE(nav.state(sec(1.7)).position_valid);
    // The next good fix is taken at once.
    EXPECT_EQ(nav.on_fix(fix_ned(f, 110.0, 200.0), sec(2.0)), "");
    const sb::NavOutput back = nav.state(sec(2.0));
    EXPECT_TRUE(back.position_valid);
    EXPECT_NEAR(back.x, 110.0, 1e-6);
  }
}

TEST(NavFusion, TwoDimensionalFix) {
  const geo::LocalNed f(kOrigin);
  {
    sb::NavParams p;
    p.require_3d = true;
    sb::NavFusion nav(p, kOrigin);
    sb::GnssFix two = fix_ned(f, 10.0, 10.0);
    two.mode = 2;
    EXPECT_FALSE(nav.on_fix(two, sec(1)).empty());
    EXPECT_EQ(count(nav.rejected(), "fix.2d"), 1u);
    sb::NavOutput o = nav.state(sec(1));
    EXPECT_FALSE(o.position_valid);
    expect_position_nan(o);
    EXPECT_TRUE(contains(o.why_invalid, "2-D")) << o.why_invalid;
    // A 3-D fix is valid; a 2-D one after it invalidates at once.
    EXPECT_EQ(nav.on_fix(fix_ned(f, 10.0, 10.0), sec(2)), "");
    EXPECT_TRUE(nav.state(sec(2)).position_valid);
    EXPECT_FALSE(nav.on_fix(two, sec(2.5)).empty());
    o = nav.state(sec(2.5));
    EXPECT_FALSE(o.position_valid);
    expect_position_nan(o);
  }
  {
    sb::NavParams p;
    p.require_3d = false;
    sb::NavFusion nav(p, kOrigin);
    sb::GnssFix two = fix_ned(f, 10.0, 20.0);
    two.mode = 2;
    EXPECT_EQ(nav.on_fix(two, sec(1)), "");
    const sb::NavOutput o = nav.state(sec(1));
    EXPECT_TRUE(o.position_valid) << o.why_invalid;
    EXPECT_NEAR(o.x, 10.0, 1e-6);
    EXPECT_NEAR(o.y, 20.0, 1e-6);
    EXPECT_EQ(count(nav.rejected(), "fix.2d"), 0u);
  }
  {
    // A rejected 2-D fix never becomes the origin either.
    sb::NavParams p;
    p.require_3d = true;
    sb::NavFusion nav(p, std::nullopt);
    sb::GnssFix two = fix_at(59.91, 10.72, 2);
    EXPECT_FALSE(nav.on_fix(two, sec(1)).empty());
    EXPECT_FALSE(nav.has_origin());
    EXPECT_FALSE(nav.on_fix(fix_at(59.91, 10.72, 1), sec(2)).empty());
    EXPECT_FALSE(nav.has_origin());
  }
}

TEST(NavFusion, StaleAfterFixTimeout) {
  sb::NavParams p;
  p.fix_timeout = 3.0;
  sb::NavFusion nav(p, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, -30.0, 40.0), sec(10)), "");
  const sb::NavOutput just_before = nav.state(sec(10) + sec(3.0) - sec(0.001));
  EXPECT_TRUE(just_before.position_valid);
  EXPECT_TRUE(just_before.velocity_valid);
  EXPECT_NEAR(just_before.x, -30.0, 1e-6);
  EXPECT_NEAR(just_before.y, 40.0, 1e-6);
  const sb::NavOutput just_after = nav.state(sec(10) + sec(3.0) + sec(0.001));
  EXPECT_FALSE(just_after.position_valid);
  EXPECT_FALSE(just_after.velocity_valid);
  expect_position_nan(just_after);
  EXPECT_TRUE(std::isnan(just_after.sog));
  EXPECT_TRUE(contains(just_after.why_invalid, "stale")) << just_after.why_invalid;
}

TEST(NavFusion, JumpRejectedUntilTheOldFixIsStale) {
  sb::NavParams p;  // max_speed 25 m/s, jump_margin 30 m, fix_timeout 3 s
  sb::NavFusion nav(p, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0), sec(0)), "");
  // 1 s later 1 km away: at most 25 + 30 = 55 m is possible.
  const std::string why = nav.on_fix(fix_ned(f, 1000.0, 0.0), sec(1));
  EXPECT_TRUE(contains(why, "jump")) << why;
  EXPECT_EQ(count(nav.rejected(), "fix.jump"), 1u);
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_TRUE(o.position_valid);
  EXPECT_NEAR(o.x, 0.0, 1e-6);  // the old position stays
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 1000.0, 0.0), sec(2)).empty());
  EXPECT_EQ(count(nav.rejected(), "fix.jump"), 2u);
  o = nav.state(sec(2.9));
  EXPECT_TRUE(o.position_valid);
  EXPECT_NEAR(o.x, 0.0, 1e-6);
  o = nav.state(sec(3.1));
  EXPECT_FALSE(o.position_valid);  // the last good fix went stale
  expect_position_nan(o);
  // The relocated position is taken only when a second fix agrees with it, so that the position
  // is invalid in between even when the old fix goes stale just as a far fix arrives.
  EXPECT_TRUE(contains(nav.on_fix(fix_ned(f, 1000.0, 0.0), sec(3.1)), "second fix"));
  o = nav.state(sec(3.1));
  EXPECT_FALSE(o.position_valid);
  EXPECT_TRUE(contains(o.why_invalid, "jumped")) << o.why_invalid;
  EXPECT_EQ(count(nav.rejected(), "fix.unconfirmed"), 1u);
  EXPECT_EQ(nav.on_fix(fix_ned(f, 1002.0, 0.0), sec(3.3)), "");
  o = nav.state(sec(3.3));
  EXPECT_TRUE(o.position_valid) << o.why_invalid;
  EXPECT_NEAR(o.x, 1002.0, 1e-6);
  EXPECT_EQ(count(nav.rejected(), "fix.jump"), 2u);
}

// A spurious far fix after a jump does not confirm the candidate: each disagreeing fix starts over.
TEST(NavFusion, JumpCandidateNeedsAnAgreeingSecondFix) {
  sb::NavParams p;
  sb::NavFusion nav(p, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0), sec(0)), "");
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 5000.0, 0.0), sec(1)).empty());
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 5000.0, 0.0), sec(3.5)).empty());   // candidate
  EXPECT_FALSE(nav.on_fix(fix_ned(f, -5000.0, 0.0), sec(3.7)).empty());  // disagrees: new candidate
  EXPECT_FALSE(nav.state(sec(3.7)).position_valid);
  EXPECT_FALSE(nav.on_fix(fix_ned(f, -5000.0, 0.0), sec(3.7)).empty()) << "a fix of the same poll is no confirmation";
  EXPECT_FALSE(nav.state(sec(3.7)).position_valid);
  EXPECT_EQ(nav.on_fix(fix_ned(f, -4999.0, 0.0), sec(3.9)), "");
  EXPECT_TRUE(nav.state(sec(3.9)).position_valid);
  EXPECT_NEAR(nav.state(sec(3.9)).x, -4999.0, 1e-6);
}

// The receiver's own verdict (RMC V / GGA quality 0 from gpsd's raw NMEA) makes the position invalid
// at once although gpsd still reports a 3-D fix with a position, until a valid verdict comes.
TEST(NavFusion, ReceiverInvalidVerdictOverridesGpsdMode) {
  sb::NavParams p;
  sb::NavFusion nav(p, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0), sec(0)), "");
  ASSERT_TRUE(nav.state(sec(0)).position_valid);
  std::string kind;
  EXPECT_EQ(sb::apply_nmea_line(nmea::rmc("GP", nmea::FixData{0, 59.0, 10.0, 5.0, 90.0, 0}), nav, sec(0.2), &kind), "");
  EXPECT_EQ(kind, "RMC");
  sb::NavOutput o = nav.state(sec(0.2));
  EXPECT_FALSE(o.position_valid);
  expect_position_nan(o);
  EXPECT_TRUE(contains(o.why_invalid, "no fix")) << o.why_invalid;
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 1.0, 0.0), sec(0.2)).empty()) << "a TPV after the V verdict";
  EXPECT_FALSE(nav.state(sec(0.2)).position_valid);
  EXPECT_GE(count(nav.rejected(), "fix.no_fix"), 1u);
  // A valid GGA clears it; the next TPV is taken.
  EXPECT_EQ(sb::apply_nmea_line(nmea::gga("GP", nmea::FixData{0, 59.0, 10.0, 5.0, 90.0, 1}), nav, sec(0.4), &kind), "");
  EXPECT_EQ(nav.on_fix(fix_ned(f, 2.0, 0.0), sec(0.4)), "");
  EXPECT_TRUE(nav.state(sec(0.4)).position_valid);
  // GGA quality 0 alone is enough too.
  sb::apply_nmea_line(nmea::gga("GP", nmea::FixData{0, 59.0, 10.0, 5.0, 90.0, 0}), nav, sec(0.6), &kind);
  EXPECT_FALSE(nav.state(sec(0.6)).position_valid);
}

TEST(NavFusion, JumpLimitScalesWithTime) {
  sb::NavFusion nav({}, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0), sec(0)), "");
  EXPECT_EQ(nav.on_fix(fix_ned(f, 54.0, 0.0), sec(1)), "");  // 54 m <= 25*1 + 30
  EXPECT_NEAR(nav.state(sec(1)).x, 54.0, 1e-6);
  EXPECT_EQ(nav.on_fix(fix_ned(f, 54.0, 75.0), sec(3)), "");  // 75 m <= 25*2 + 30 = 80
  EXPECT_NEAR(nav.state(sec(3)).y, 75.0, 1e-6);
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 54.0, 75.0 + 60.0), sec(4)).empty());  // 60 m > 55
  EXPECT_NEAR(nav.state(sec(4)).y, 75.0, 1e-6);
  EXPECT_EQ(count(nav.rejected(), "fix.jump"), 1u);
}

TEST(NavFusion, BadLatitudeLongitudeRejected) {
  sb::NavFusion nav({}, std::nullopt);
  struct Case {
    double lat, lon;
    const char* key;
  };
  const std::vector<Case> cases = {{kNan, 10.0, "fix.not_finite"}, {59.0, kNan, "fix.not_finite"},
                                   {kInf, 10.0, "fix.not_finite"}, {59.0, -kInf, "fix.not_finite"},
                                   {91.0, 10.0, "fix.out_of_range"}, {-90.5, 10.0, "fix.out_of_range"},
                                   {59.0, 181.0, "fix.out_of_range"}, {59.0, -180.5, "fix.out_of_range"}};
  for (const Case& c : cases) EXPECT_FALSE(nav.on_fix(fix_at(c.lat, c.lon), sec(1)).empty()) << c.lat << " " << c.lon;
  EXPECT_EQ(count(nav.rejected(), "fix.not_finite"), 4u);
  EXPECT_EQ(count(nav.rejected(), "fix.out_of_range"), 4u);
  EXPECT_FALSE(nav.has_origin());  // a bad fix never becomes the origin
  EXPECT_FALSE(nav.state(sec(1)).position_valid);
  // After a good fix, a bad one leaves the position alone.
  ASSERT_EQ(nav.on_fix(fix_at(59.9, 10.7), sec(2)), "");
  EXPECT_FALSE(nav.on_fix(fix_at(kNan, 10.7), sec(2.5)).empty());
  EXPECT_FALSE(nav.on_fix(fix_at(95.0, 10.7), sec(2.6)).empty());
  const sb::NavOutput o = nav.state(sec(2.6));
  EXPECT_TRUE(o.position_valid);
  EXPECT_EQ(o.x, 0.0);
  EXPECT_DOUBLE_EQ(o.lat, geo::deg2rad(59.9));
}

TEST(NavFusion, SogAndCogOutOfRangeRejected) {
  sb::NavFusion nav({}, kOrigin);  // max_sog 40 m/s
  const geo::LocalNed f(kOrigin);
  std::string why = nav.on_fix(fix_ned(f, 0.0, 0.0, 50.0, 90.0), sec(1));
  EXPECT_TRUE(contains(why, "SOG")) << why;
  EXPECT_EQ(count(nav.rejected(), "fix.sog"), 1u);
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_TRUE(o.position_valid);   // the position itself was fine
  EXPECT_FALSE(o.velocity_valid);  // no SOG ever taken
  EXPECT_TRUE(std::isnan(o.sog));
  why = nav.on_fix(fix_ned(f, 0.0, 0.0, -1.0, 90.0), sec(1.1));
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(count(nav.rejected(), "fix.sog"), 2u);
  why = nav.on_fix(fix_ned(f, 0.0, 0.0, kInf, 90.0), sec(1.2));
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(count(nav.rejected(), "fix.sog"), 3u);
  why = nav.on_fix(fix_ned(f, 0.0, 0.0, 5.0, 400.0), sec(1.3));
  EXPECT_TRUE(contains(why, "COG")) << why;
  EXPECT_EQ(count(nav.rejected(), "fix.cog"), 1u);
  o = nav.state(sec(1.3));  // the 400 deg never replaced the 90 deg COG of 1 s
  EXPECT_NEAR(o.cog, geo::kPi / 2, 1e-12);
  EXPECT_DOUBLE_EQ(o.sog, 5.0);
  // A good one after them.
  EXPECT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0, 40.0, 90.0), sec(1.4)), "");
  o = nav.state(sec(1.4));
  EXPECT_TRUE(o.velocity_valid) << o.why_invalid;
  EXPECT_DOUBLE_EQ(o.sog, 40.0);
  // An out-of-range SOG never replaces the last good one.
  EXPECT_FALSE(nav.on_fix(fix_ned(f, 0.0, 0.0, 45.0, 90.0), sec(1.5)).empty());
  EXPECT_DOUBLE_EQ(nav.state(sec(1.5)).sog, 40.0);
}

TEST(NavFusion, VelocityNeedsSogAndCog) {
  sb::NavFusion nav({}, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 0.0, 0.0, kNan, kNan), sec(1)), "");
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_TRUE(o.position_valid);
  EXPECT_FALSE(o.velocity_valid);
  EXPECT_TRUE(std::isnan(o.sog));
  EXPECT_TRUE(std::isnan(o.cog));
  EXPECT_TRUE(contains(o.why_invalid, "SOG/COG")) << o.why_invalid;

  sb::NavFusion nav2({}, kOrigin);
  ASSERT_EQ(nav2.on_fix(fix_ned(f, 0.0, 0.0, 3.0, kNan), sec(1)), "");  // SOG only
  EXPECT_FALSE(nav2.state(sec(1)).velocity_valid);
  EXPECT_TRUE(std::isnan(nav2.state(sec(1)).sog));

  sb::NavFusion nav3({}, kOrigin);
  ASSERT_EQ(nav3.on_fix(fix_ned(f, 0.0, 0.0, 3.0, 270.0), sec(1)), "");
  o = nav3.state(sec(1));
  EXPECT_TRUE(o.velocity_valid) << o.why_invalid;
  EXPECT_DOUBLE_EQ(o.sog, 3.0);
  EXPECT_NEAR(o.cog, -geo::kPi / 2, 1e-12);  // 270 deg -> (-pi, pi]
}

TEST(NavFusion, HeadingWrapsToMinusPiPi) {
  sb::NavFusion nav({}, kOrigin);
  struct Case {
    double deg, want_rad;
  };
  const std::vector<Case> cases = {{0.0, 0.0},
                                   {90.0, geo::kPi / 2},
                                   {180.0, geo::kPi},
                                   {270.0, -geo::kPi / 2},
                                   {359.99, geo::deg2rad(-0.01)},
                                   {360.0, 0.0},
                                   {45.5, geo::deg2rad(45.5)}};
  int64_t t = sec(1);
  for (const Case& c : cases) {
    SCOPED_TRACE(c.deg);
    ASSERT_EQ(nav.on_heading(c.deg, t), "");
    const sb::NavOutput o = nav.state(t);
    EXPECT_TRUE(o.heading_valid);
    EXPECT_NEAR(o.heading, c.want_rad, 1e-12);
    EXPECT_GT(o.heading, -geo::kPi);
    EXPECT_LE(o.heading, geo::kPi);
    t += sec(0.1);
  }
}

TEST(NavFusion, HeadingValidityAndTimeout) {
  sb::NavParams p;
  p.heading_timeout = 1.0;
  sb::NavFusion nav(p, kOrigin);
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_FALSE(o.heading_valid);
  EXPECT_TRUE(std::isnan(o.heading));
  EXPECT_TRUE(contains(o.why_invalid, "no heading yet")) << o.why_invalid;
  ASSERT_EQ(nav.on_heading(123.0, sec(5)), "");
  EXPECT_TRUE(nav.state(sec(6) - sec(0.001)).heading_valid);
  EXPECT_NEAR(nav.state(sec(6) - sec(0.001)).heading, geo::deg2rad(123.0), 1e-12);
  o = nav.state(sec(6) + sec(0.001));
  EXPECT_FALSE(o.heading_valid);
  EXPECT_TRUE(std::isnan(o.heading));
  EXPECT_TRUE(contains(o.why_invalid, "heading stale")) << o.why_invalid;
  // Bad headings are rejected and counted, the last good one kept.
  ASSERT_EQ(nav.on_heading(10.0, sec(7)), "");
  for (double bad : {kNan, kInf, -0.5, 360.5, 720.0}) EXPECT_FALSE(nav.on_heading(bad, sec(7.1)).empty()) << bad;
  EXPECT_EQ(count(nav.rejected(), "heading.bad"), 5u);
  EXPECT_NEAR(nav.state(sec(7.1)).heading, geo::deg2rad(10.0), 1e-12);
}

TEST(NavFusion, RateOfTurnUnitsSignAndTimeout) {
  sb::NavFusion nav({}, kOrigin);
  EXPECT_FALSE(nav.state(sec(1)).rate_valid);
  EXPECT_TRUE(contains(nav.state(sec(1)).why_invalid, "no rate of turn yet"));
  ASSERT_EQ(nav.on_rate_of_turn(30.0, sec(1)), "");  // 30 deg/min to starboard
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_TRUE(o.rate_valid);
  EXPECT_NEAR(o.r, 30.0 * geo::kPi / 180.0 / 60.0, 1e-15);
  EXPECT_GT(o.r, 0.0);
  ASSERT_EQ(nav.on_rate_of_turn(-12.5, sec(2)), "");  // to port
  o = nav.state(sec(2));
  EXPECT_NEAR(o.r, -12.5 * geo::kPi / 180.0 / 60.0, 1e-15);
  EXPECT_LT(o.r, 0.0);
  EXPECT_TRUE(nav.state(sec(3) - sec(0.001)).rate_valid);  // heading_timeout 1 s
  o = nav.state(sec(3) + sec(0.001));
  EXPECT_FALSE(o.rate_valid);
  EXPECT_TRUE(std::isnan(o.r));
  EXPECT_TRUE(contains(o.why_invalid, "rate of turn stale")) << o.why_invalid;
  for (double bad : {kNan, kInf, 800.0, -721.0}) EXPECT_FALSE(nav.on_rate_of_turn(bad, sec(3.5)).empty()) << bad;
  EXPECT_EQ(count(nav.rejected(), "rot.bad"), 4u);
  EXPECT_FALSE(nav.state(sec(3.5)).rate_valid);
}

TEST(NavFusion, RudderAndRpmFeedback) {
  sb::NavParams p;
  p.feedback_timeout = 2.0;
  sb::NavFusion nav(p, kOrigin);
  ASSERT_EQ(nav.on_rudder(-10.0, sec(1)), "");
  sb::NavOutput o = nav.state(sec(1));
  EXPECT_FALSE(o.actuators_valid);  // rpm missing
  EXPECT_TRUE(std::isnan(o.rudder));
  EXPECT_TRUE(std::isnan(o.rpm));
  EXPECT_TRUE(contains(o.why_invalid, "actuator")) << o.why_invalid;
  ASSERT_EQ(nav.on_rpm(80.0, sec(1.5)), "");
  o = nav.state(sec(1.5));
  EXPECT_TRUE(o.actuators_valid);
  EXPECT_NEAR(o.rudder, geo::deg2rad(-10.0), 1e-15);
  EXPECT_DOUBLE_EQ(o.rpm, 80.0);
  EXPECT_TRUE(nav.state(sec(3) - sec(0.001)).actuators_valid);  // rudder 2 s old
  o = nav.state(sec(3) + sec(0.001));
  EXPECT_FALSE(o.actuators_valid);  // the rudder went stale first
  EXPECT_TRUE(std::isnan(o.rudder));
  EXPECT_TRUE(std::isnan(o.rpm));
  for (double bad : {kNan, 95.0, -90.5}) EXPECT_FALSE(nav.on_rudder(bad, sec(4)).empty()) << bad;
  for (double bad : {kNan, kInf, 10001.0}) EXPECT_FALSE(nav.on_rpm(bad, sec(4)).empty()) << bad;
  EXPECT_EQ(count(nav.rejected(), "rudder.bad"), 3u);
  EXPECT_EQ(count(nav.rejected(), "rpm.bad"), 3u);
}

TEST(NavFusion, WhyInvalidEmptyWhenAllValid) {
  sb::NavFusion nav({}, kOrigin);
  const geo::LocalNed f(kOrigin);
  ASSERT_EQ(nav.on_fix(fix_ned(f, 1.0, 2.0, 4.0, 10.0), sec(1)), "");
  ASSERT_EQ(nav.on_heading(11.0, sec(1)), "");
  ASSERT_EQ(nav.on_rate_of_turn(1.0, sec(1)), "");
  ASSERT_EQ(nav.on_rudder(2.0, sec(1)), "");
  ASSERT_EQ(nav.on_rpm(70.0, sec(1)), "");
  sb::NavOutput o = nav.state(sec(1.2));
  EXPECT_TRUE(o.position_valid && o.velocity_valid && o.heading_valid && o.rate_valid && o.actuators_valid);
  EXPECT_EQ(o.why_invalid, "");
  // Heading and rate of turn stale (1 s), position and feedback fresh: the text names only those.
  o = nav.state(sec(2.5));
  EXPECT_TRUE(o.position_valid);
  EXPECT_FALSE(o.heading_valid);
  EXPECT_TRUE(contains(o.why_invalid, "heading stale")) << o.why_invalid;
  EXPECT_FALSE(contains(o.why_invalid, "position")) << o.why_invalid;
  EXPECT_FALSE(contains(o.why_invalid, "actuator")) << o.why_invalid;
  EXPECT_TRUE(contains(o.why_invalid, "rate of turn stale")) << o.why_invalid;
}

TEST(NavFusion, InvalidParametersThrow) {
  sb::NavParams p;
  p.fix_timeout = 0.0;
  EXPECT_THROW((void)sb::NavFusion(p, kOrigin), std::invalid_argument);
  p = {};
  p.jump_margin = -1.0;
  EXPECT_THROW((void)sb::NavFusion(p, kOrigin), std::invalid_argument);
  EXPECT_THROW((void)sb::NavFusion({}, geo::LatLon{geo::deg2rad(95.0), 0.0}), std::invalid_argument);
}

// =====================================================================================
// AisAssembler
// =====================================================================================

TEST(AisAssembler, OwnShipNeverATarget) {
  sb::AisAssembler a(257999999);
  std::string why;
  EXPECT_FALSE(a.on_message(position_msg(1, 257999999), &why).has_value());
  EXPECT_EQ(why, "own ship");
  sb::AisMessage st = static_msg(5, 257999999);
  st.name = "OWN";
  EXPECT_FALSE(a.on_message(st, &why).has_value());
  EXPECT_FALSE(a.on_message(position_msg(18, 257999999), &why).has_value());
  EXPECT_EQ(a.own_ship_messages(), 3u);
  // Another ship is a target.
  const auto r = a.on_message(position_msg(1, 257000001), &why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_EQ(r->mmsi, 257000001u);
  EXPECT_EQ(a.own_ship_messages(), 3u);
  // Without an own MMSI nothing is dropped as own.
  sb::AisAssembler none(0);
  EXPECT_TRUE(none.on_message(position_msg(1, 257999999), &why).has_value());
  EXPECT_EQ(none.own_ship_messages(), 0u);
}

TEST(AisAssembler, MmsiZeroRejected) {
  sb::AisAssembler a(257999999);
  std::string why;
  EXPECT_FALSE(a.on_message(position_msg(1, 0), &why).has_value());
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(count(a.rejected(), "ais.mmsi"), 1u);
  EXPECT_FALSE(a.on_message(position_msg(1, 1000000000u), &why).has_value());
  EXPECT_EQ(count(a.rejected(), "ais.mmsi"), 2u);
}

TEST(AisAssembler, Type5ThenType1JoinsStaticData) {
  sb::AisAssembler a(0);
  sb::AisMessage s = static_msg(5, 257000002);
  s.name = "MPGC TEST VESSEL";
  s.ship_type = 70;
  s.to_bow = 150;
  s.to_stern = 45;
  s.to_port = 12;
  s.to_starboard = 20;
  std::string why;
  EXPECT_FALSE(a.on_message(s, &why).has_value());
  EXPECT_TRUE(contains(why, "static")) << why;
  sb::AisMessage p = position_msg(1, 257000002);
  p.lat_deg = -33.5;
  p.lon_deg = 151.25;
  p.sog = 7.5;
  p.cog_deg = 350.0;
  p.heading_deg = 349.0;
  p.nav_status = 3;
  const auto r = a.on_message(p, &why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_EQ(r->mmsi, 257000002u);
  EXPECT_FALSE(r->class_b);
  EXPECT_EQ(r->name, "MPGC TEST VESSEL");
  EXPECT_DOUBLE_EQ(r->length, 195.0);
  EXPECT_DOUBLE_EQ(r->beam, 32.0);
  EXPECT_EQ(r->ship_type, 70);
  EXPECT_DOUBLE_EQ(r->lat, geo::deg2rad(-33.5));
  EXPECT_DOUBLE_EQ(r->lon, geo::deg2rad(151.25));
  EXPECT_DOUBLE_EQ(r->sog, 7.5);
  EXPECT_NEAR(r->cog, geo::deg2rad(-10.0), 1e-12);
  EXPECT_NEAR(r->heading, geo::deg2rad(-11.0), 1e-12);
  EXPECT_EQ(r->nav_status, 3);
  // Another ship has no static data yet.
  const auto other = a.on_message(position_msg(1, 257000003), &why);
  ASSERT_TRUE(other.has_value());
  EXPECT_TRUE(other->name.empty());
  EXPECT_TRUE(std::isnan(other->length));
  EXPECT_TRUE(std::isnan(other->beam));
  EXPECT_EQ(other->ship_type, -1);
}

TEST(AisAssembler, Type24PartsMerged) {
  sb::AisAssembler a(0);
  sb::AisMessage partA = static_msg(24, 338000001);
  partA.name = "SAILING FRIEND";  // part A: name only, dimensions n/a
  sb::AisMessage partB = static_msg(24, 338000001);
  partB.ship_type = 37;
  partB.to_bow = 8;
  partB.to_stern = 4;
  partB.to_port = 2;
  partB.to_starboard = 2;
  std::string why;
  EXPECT_FALSE(a.on_message(partA, &why).has_value());
  EXPECT_FALSE(a.on_message(partB, &why).has_value());
  const auto r = a.on_message(position_msg(18, 338000001), &why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_TRUE(r->class_b);
  EXPECT_EQ(r->name, "SAILING FRIEND");
  EXPECT_EQ(r->ship_type, 37);
  EXPECT_DOUBLE_EQ(r->length, 12.0);
  EXPECT_DOUBLE_EQ(r->beam, 4.0);
  // Part A again later (new name) keeps the dimensions of part B.
  partA.name = "SAILING FRIEND II";
  EXPECT_FALSE(a.on_message(partA, &why).has_value());
  const auto r2 = a.on_message(position_msg(18, 338000001), &why);
  ASSERT_TRUE(r2.has_value());
  EXPECT_EQ(r2->name, "SAILING FRIEND II");
  EXPECT_DOUBLE_EQ(r2->length, 12.0);
  EXPECT_EQ(r2->ship_type, 37);
}

TEST(AisAssembler, ClassBTypes) {
  sb::AisAssembler a(0);
  std::string why;
  for (int type : {1, 2, 3, 18, 19}) {
    sb::AisMessage m = position_msg(type, 257000010 + static_cast<uint32_t>(type));
    if (type == 19) {
      m.has_static = true;
      m.name = "EXTENDED B";
      m.to_bow = 10, m.to_stern = 5, m.to_port = 2, m.to_starboard = 3;
    }
    const auto r = a.on_message(m, &why);
    ASSERT_TRUE(r.has_value()) << type << ": " << why;
    EXPECT_EQ(r->class_b, type == 18 || type == 19) << type;
    if (type == 19) {
      EXPECT_EQ(r->name, "EXTENDED B");
      EXPECT_DOUBLE_EQ(r->length, 15.0);
      EXPECT_DOUBLE_EQ(r->beam, 5.0);
    }
  }
}

TEST(AisAssembler, PositionNotAvailableRejected) {
  sb::AisAssembler a(0);
  std::string why;
  struct Case {
    double lat, lon;
  };
  for (const Case& c : std::vector<Case>{{91.0, 10.0}, {59.0, 181.0}, {kNan, 10.0}, {59.0, kNan}}) {
    sb::AisMessage m = position_msg(1, 257000020);
    m.lat_deg = c.lat;
    m.lon_deg = c.lon;
    EXPECT_FALSE(a.on_message(m, &why).has_value()) << c.lat << " " << c.lon;
    EXPECT_FALSE(why.empty());
  }
  EXPECT_EQ(count(a.rejected(), "ais.position"), 4u);
  // A message without position at all is no report, and not a rejection.
  const sb::AisMessage none = ais_msg(27, 257000020);
  EXPECT_FALSE(a.on_message(none, &why).has_value());
  EXPECT_EQ(count(a.rejected(), "ais.position"), 4u);
}

TEST(AisAssembler, RateOfTurnFromRawTurn) {
  sb::AisAssembler a(0);
  std::string why;
  const auto rot_of = [&](int raw) {
    sb::AisMessage m = position_msg(1, 257000030);
    m.turn_raw = raw;
    const auto r = a.on_message(m, &why);
    EXPECT_TRUE(r.has_value()) << why;
    return r ? r->rot : -999.0;
  };
  const auto want = [](int raw) {
    const double q = raw / 4.733;
    return std::copysign(q * q, raw) * geo::kPi / 180.0 / 60.0;  // deg/min -> rad/s
  };
  EXPECT_TRUE(std::isnan(rot_of(-128)));
  EXPECT_TRUE(std::isnan(rot_of(127)));
  EXPECT_TRUE(std::isnan(rot_of(-127)));
  EXPECT_EQ(rot_of(0), 0.0);
  EXPECT_NEAR(rot_of(20), want(20), 1e-15);
  EXPECT_NEAR(rot_of(20), (20 / 4.733) * (20 / 4.733) / 60.0 * geo::kPi / 180.0, 1e-15);
  EXPECT_GT(rot_of(20), 0.0);
  EXPECT_NEAR(rot_of(-20), -want(20), 1e-15);
  EXPECT_NEAR(rot_of(126), want(126), 1e-15);
  EXPECT_NEAR(rot_of(-1), -want(1), 1e-15);
}

TEST(AisAssembler, NotAvailableValuesStayNaN) {
  sb::AisAssembler a(0);
  std::string why;
  sb::AisMessage m = position_msg(1, 257000040);
  m.heading_deg = kNan;
  m.cog_deg = kNan;
  m.sog = kNan;
  const auto r = a.on_message(m, &why);
  ASSERT_TRUE(r.has_value()) << why;
  EXPECT_TRUE(std::isnan(r->heading));
  EXPECT_TRUE(std::isnan(r->cog));
  EXPECT_TRUE(std::isnan(r->sog));
  EXPECT_FALSE(std::isnan(r->lat));
  // nav_status outside 0..15 becomes 15 (not defined).
  m.nav_status = 42;
  const auto r2 = a.on_message(m, &why);
  ASSERT_TRUE(r2.has_value());
  EXPECT_EQ(r2->nav_status, 15);
}

// =====================================================================================
// encode_orders
// =====================================================================================

namespace {

struct Orders {
  double rudder_deg = kNan, rpm = kNan;
  std::string rudder_field;
  int lines = 0;
};
Orders parse_orders(const std::string& text) {
  Orders o;
  for (const std::string& l : split_lines(text)) {
    ++o.lines;
    const nmea::Sentence s = must_parse(l);
    EXPECT_EQ(s.talker, "AG") << l;
    std::string why;
    if (s.type == "ROR") {
      const auto r = nmea::parse_ror(s, &why);
      EXPECT_TRUE(r.has_value()) << l << ": " << why;
      if (r) o.rudder_deg = r->rudder_deg;
      o.rudder_field = s.fields.at(0);
    } else if (s.type == "PRC") {
      const auto n = nmea::parse_prc(s, &why);
      EXPECT_TRUE(n.has_value()) << l << ": " << why;
      if (n) {
        o.rpm = n->rpm;
        EXPECT_EQ(n->shaft, 1);
      }
    } else {
      ADD_FAILURE() << "unexpected sentence " << l;
    }
  }
  return o;
}

}  // namespace

TEST(EncodeOrders, WithinLimitsNotSaturated) {
  const sb::ActuatorLimits lim;  // 35 deg, 0..150 rpm
  bool sat = true;
  const std::string out = sb::encode_orders(geo::deg2rad(10.0), 80.0, lim, &sat);
  EXPECT_FALSE(sat);
  const Orders o = parse_orders(out);
  EXPECT_EQ(o.lines, 2);
  EXPECT_NEAR(o.rudder_deg, 10.0, 0.005);
  EXPECT_NEAR(o.rpm, 80.0, 0.005);
  sat = true;
  const Orders edge = parse_orders(sb::encode_orders(-lim.max_rudder, lim.max_rpm, lim, &sat));
  EXPECT_FALSE(sat);
  EXPECT_NEAR(edge.rudder_deg, -35.0, 0.005);
  EXPECT_NEAR(edge.rpm, 150.0, 0.005);
}

TEST(EncodeOrders, BeyondLimitsClippedAndSaturated) {
  sb::ActuatorLimits lim;
  lim.max_rudder = geo::deg2rad(30.0);
  lim.min_rpm = 20.0;
  lim.max_rpm = 120.0;
  struct Case {
    double rudder_deg, rpm, want_rudder, want_rpm;
  };
  for (const Case& c : std::vector<Case>{{40.0, 80.0, 30.0, 80.0},
                                         {-50.0, 80.0, -30.0, 80.0},
                                         {10.0, 200.0, 10.0, 120.0},
                                         {10.0, 5.0, 10.0, 20.0},
                                         {-90.0, -10.0, -30.0, 20.0}}) {
    SCOPED_TRACE(std::to_string(c.rudder_deg) + " deg, " + std::to_string(c.rpm) + " rpm");
    bool sat = false;
    const std::string out = sb::encode_orders(geo::deg2rad(c.rudder_deg), c.rpm, lim, &sat);
    EXPECT_TRUE(sat);
    const Orders o = parse_orders(out);
    EXPECT_NEAR(o.rudder_deg, c.want_rudder, 0.005);
    EXPECT_NEAR(o.rpm, c.want_rpm, 0.005);
  }
}

TEST(EncodeOrders, NonFiniteGivesNothing) {
  const sb::ActuatorLimits lim;
  for (const auto& [r, n] : std::vector<std::pair<double, double>>{{kNan, 80.0}, {0.1, kNan}, {kInf, 80.0}, {0.1, -kInf}}) {
    bool sat = true;
    EXPECT_EQ(sb::encode_orders(r, n, lim, &sat), "") << r << " " << n;
    EXPECT_FALSE(sat);
  }
  EXPECT_EQ(sb::encode_orders(kNan, kNan, lim, nullptr), "");
}

TEST(EncodeOrders, RudderSign) {
  const sb::ActuatorLimits lim;
  const Orders stbd = parse_orders(sb::encode_orders(geo::deg2rad(12.34), 60.0, lim, nullptr));
  EXPECT_NEAR(stbd.rudder_deg, 12.34, 0.005);
  EXPECT_EQ(stbd.rudder_field, "12.34");
  const Orders port = parse_orders(sb::encode_orders(geo::deg2rad(-12.34), 60.0, lim, nullptr));
  EXPECT_NEAR(port.rudder_deg, -12.34, 0.005);
  EXPECT_EQ(port.rudder_field, "-12.34");
  const Orders mid = parse_orders(sb::encode_orders(0.0, 60.0, lim, nullptr));
  EXPECT_EQ(mid.rudder_deg, 0.0);
  EXPECT_EQ(mid.rudder_field.find('-'), std::string::npos);
}

// =====================================================================================
// apply_nmea_line
// =====================================================================================

TEST(ApplyNmeaLine, GyroAndFeedbackSentencesFeedNavFusion) {
  sb::NavFusion nav({}, kOrigin);
  std::string kind;
  const int64_t t = sec(5);

  EXPECT_EQ(sb::apply_nmea_line(nmea::frame('$', "HEHDT,123.45,T"), nav, t, &kind), "");
  EXPECT_EQ(kind, "HDT");
  EXPECT_NEAR(nav.state(t).heading, geo::deg2rad(123.45), 1e-12);

  EXPECT_EQ(sb::apply_nmea_line(nmea::ths("HE", 200.0, 'A'), nav, t, &kind), "");
  EXPECT_EQ(kind, "THS");
  EXPECT_NEAR(nav.state(t).heading, geo::deg2rad(200.0) - 2 * geo::kPi, 1e-12);
  // THS mode V: rejected, heading unchanged.
  EXPECT_FALSE(sb::apply_nmea_line(nmea::frame('$', "HETHS,10.00,V"), nav, t, &kind).empty());
  EXPECT_EQ(kind, "THS");
  EXPECT_NEAR(nav.state(t).heading, geo::deg2rad(200.0) - 2 * geo::kPi, 1e-12);

  EXPECT_EQ(sb::apply_nmea_line(nmea::frame('$', "HEROT,-12.5,A"), nav, t, &kind), "");
  EXPECT_EQ(kind, "ROT");
  EXPECT_NEAR(nav.state(t).r, geo::deg2rad(-12.5) / 60.0, 1e-15);
  // ROT status V: rejected, rate unchanged.
  EXPECT_FALSE(sb::apply_nmea_line(nmea::frame('$', "HEROT,30.0,V"), nav, t, &kind).empty());
  EXPECT_NEAR(nav.state(t).r, geo::deg2rad(-12.5) / 60.0, 1e-15);

  EXPECT_EQ(sb::apply_nmea_line(nmea::frame('$', "ERRSA,-5.50,A,,V"), nav, t, &kind), "");
  EXPECT_EQ(kind, "RSA");
  EXPECT_FALSE(nav.state(t).actuators_valid);  // rpm not yet
  EXPECT_EQ(sb::apply_nmea_line(nmea::frame('$', "ERRPM,S,1,85.00,,A"), nav, t, &kind), "");
  EXPECT_EQ(kind, "RPM");
  const sb::NavOutput o = nav.state(t);
  ASSERT_TRUE(o.actuators_valid);
  EXPECT_NEAR(o.rudder, geo::deg2rad(-5.5), 1e-15);
  EXPECT_DOUBLE_EQ(o.rpm, 85.0);
  EXPECT_TRUE(o.heading_valid);
  EXPECT_TRUE(o.rate_valid);
}

TEST(ApplyNmeaLine, DevicesOutputRoundTrip) {
  // The simulator's gyro and feedback lines, read by the bridge.
  const sim::Devices dev(geo::LocalNed(kOrigin), 1733011200LL * 1'000'000'000);
  sim::NavMeasurement m{0, 0, geo::deg2rad(-100.0), 0, 0, geo::deg2rad(-0.2)};
  sb::NavFusion nav({}, kOrigin);
  std::string kind;
  for (const std::string& l : split_lines(dev.gyro(m) + dev.feedback(geo::deg2rad(7.5), 66.6)))
    EXPECT_EQ(sb::apply_nmea_line(l, nav, sec(1), &kind), "") << l;
  const sb::NavOutput o = nav.state(sec(1));
  EXPECT_NEAR(o.heading, geo::deg2rad(-100.0), geo::deg2rad(0.005));
  EXPECT_NEAR(o.r, geo::deg2rad(-0.2), geo::deg2rad(0.005) / 60.0);
  EXPECT_NEAR(o.rudder, geo::deg2rad(7.5), geo::deg2rad(0.005));
  EXPECT_NEAR(o.rpm, 66.6, 0.005);
}

TEST(ApplyNmeaLine, BadChecksumLeavesStateUnchanged) {
  sb::NavFusion nav({}, kOrigin);
  std::string kind = "junk";
  ASSERT_EQ(sb::apply_nmea_line(nmea::frame('$', "HEHDT,10.00,T"), nav, sec(1), &kind), "");
  std::string line = nmea::frame('$', "HEHDT,99.00,T");
  const size_t star = line.find('*');
  ASSERT_NE(star, std::string::npos);
  line[star + 1] = line[star + 1] == '0' ? '1' : '0';
  kind = "junk";
  const std::string why = sb::apply_nmea_line(line, nav, sec(1.5), &kind);
  EXPECT_TRUE(contains(why, "checksum")) << why;
  EXPECT_EQ(kind, "");
  EXPECT_NEAR(nav.state(sec(1.5)).heading, geo::deg2rad(10.0), 1e-12);
  EXPECT_FALSE(nav.state(sec(2.1)).heading_valid);  // and the 10 deg was not refreshed at 1.5 s
  // Not a sentence at all.
  EXPECT_FALSE(sb::apply_nmea_line("hello", nav, sec(1.5), &kind).empty());
  EXPECT_EQ(kind, "");
}

TEST(ApplyNmeaLine, UnknownSentenceTypeReported) {
  sb::NavFusion nav({}, kOrigin);
  std::string kind;
  nmea::FixData f;
  f.utc_ns = 1733011200LL * 1'000'000'000;
  f.lat_deg = 59.9;
  f.lon_deg = 10.7;
  // VTG is gpsd's (merged into TPV), not this path's. (GGA and RMC are used here: their quality and
  // status are the receiver's verdict, ReceiverInvalidVerdictOverridesGpsdMode.)
  const std::string why = sb::apply_nmea_line(nmea::vtg("GP", f), nav, sec(1), &kind);
  EXPECT_FALSE(why.empty());
  EXPECT_EQ(kind, "VTG");
  EXPECT_FALSE(nav.state(sec(1)).position_valid);
  const std::string why2 = sb::apply_nmea_line(nmea::frame('$', "IIXDR,C,19.5,C,AIR"), nav, sec(1), &kind);
  EXPECT_FALSE(why2.empty());
  EXPECT_EQ(kind, "XDR");
}

// =====================================================================================
// ship_simulator::Devices
// =====================================================================================

namespace {

constexpr int64_t kUtc0 = 1733011200LL * 1'000'000'000;  // 2024-12-01T00:00:00Z

}  // namespace

TEST(Devices, GnssSentencesGiveBackTheMeasurement) {
  struct Case {
    geo::LatLon origin;
    sim::NavMeasurement m;
  };
  const std::vector<Case> cases = {
      {kOrigin, {1234.5, -678.9, 0.3, geo::deg2rad(-28.65), 7.3, 0.001}},
      {{geo::deg2rad(-33.86), geo::deg2rad(151.2)}, {-5000.0, 3000.0, -3.0, geo::deg2rad(179.995), 0.0, -0.002}},
      {{geo::deg2rad(40.6), geo::deg2rad(-74.04)}, {10.0, -20000.0, 1.0, geo::deg2rad(0.004), 12.861, 0.0}}};
  const int64_t t = sec(3723.45);  // 01:02:03.45
  for (const Case& c : cases) {
    const geo::LocalNed frame(c.origin);
    const sim::Devices dev(frame, kUtc0);
    const std::string text = dev.gnss(c.m, t);
    SCOPED_TRACE(text);
    const std::vector<std::string> lines = split_lines(text);
    ASSERT_EQ(lines.size(), 3u);
    const geo::LatLon ll = frame.to_latlon({c.m.x, c.m.y});
    const double want_lat = geo::rad2deg(ll.lat), want_lon = geo::rad2deg(ll.lon);
    const double want_kn = c.m.sog / kKn, want_cog = deg360(c.m.cog);

    const nmea::Sentence rmc = must_parse(lines[0]);
    ASSERT_EQ(rmc.type, "RMC");
    EXPECT_EQ(rmc.talker, "GP");
    ASSERT_GE(rmc.fields.size(), 9u);
    EXPECT_EQ(rmc.fields[0], "010203.45");
    EXPECT_EQ(rmc.fields[1], "A");
    EXPECT_NEAR(coord_deg(rmc.fields[2], rmc.fields[3], 2), want_lat, 1e-7);
    EXPECT_NEAR(coord_deg(rmc.fields[4], rmc.fields[5], 3), want_lon, 1e-7);
    EXPECT_NEAR(std::stod(rmc.fields[6]), want_kn, 0.005 + 1e-9);
    EXPECT_LE(angle_diff_deg(std::stod(rmc.fields[7]), want_cog), 0.005 + 1e-9);
    EXPECT_LT(std::stod(rmc.fields[7]), 360.0);
    EXPECT_EQ(rmc.fields[8], "011224");

    const nmea::Sentence gga = must_parse(lines[1]);
    ASSERT_EQ(gga.type, "GGA");
    ASSERT_GE(gga.fields.size(), 9u);
    EXPECT_EQ(gga.fields[0], "010203.45");
    EXPECT_NEAR(coord_deg(gga.fields[1], gga.fields[2], 2), want_lat, 1e-7);
    EXPECT_NEAR(coord_deg(gga.fields[3], gga.fields[4], 3), want_lon, 1e-7);
    EXPECT_EQ(gga.fields[5], "1");
    EXPECT_FALSE(gga.fields[8].empty());  // altitude: a 3-D fix for gpsd

    const nmea::Sentence vtg = must_parse(lines[2]);
    ASSERT_EQ(vtg.type, "VTG");
    ASSERT_GE(vtg.fields.size(), 8u);
    EXPECT_LE(angle_diff_deg(std::stod(vtg.fields[0]), want_cog), 0.005 + 1e-9);
    EXPECT_EQ(vtg.fields[1], "T");
    EXPECT_NEAR(std::stod(vtg.fields[4]), want_kn, 0.005 + 1e-9);
    EXPECT_EQ(vtg.fields[5], "N");
    EXPECT_NEAR(std::stod(vtg.fields[6]), c.m.sog * 3.6, 0.005 + 1e-9);
  }
}

TEST(Devices, GyroSentences) {
  const sim::Devices dev(geo::LocalNed(kOrigin), kUtc0);
  struct Case {
    double heading_rad, rot_rad_s, want_hdt, want_rot_deg_min;
  };
  for (const Case& c : std::vector<Case>{{geo::deg2rad(-28.65), -0.002, 331.35, -0.002 * 180 / geo::kPi * 60},
                                         {0.0, 0.0, 0.0, 0.0},
                                         {geo::kPi, 0.01, 180.0, 0.01 * 180 / geo::kPi * 60},
                                         {geo::deg2rad(-0.001), 0.0, 0.0, 0.0},
                                         {geo::deg2rad(123.456), 0.0005, 123.456, 0.0005 * 180 / geo::kPi * 60}}) {
    const sim::NavMeasurement m{0, 0, c.heading_rad, 0, 0, c.rot_rad_s};
    const std::string text = dev.gyro(m);
    SCOPED_TRACE(text);
    const auto lines = split_lines(text);
    ASSERT_EQ(lines.size(), 2u);
    const nmea::Sentence hdt = must_parse(lines[0]);
    const nmea::Sentence rot = must_parse(lines[1]);
    EXPECT_EQ(hdt.talker, "HE");
    EXPECT_EQ(rot.talker, "HE");
    std::string why;
    const auto h = nmea::parse_hdt(hdt, &why);
    ASSERT_TRUE(h.has_value()) << why;
    EXPECT_LE(angle_diff_deg(h->heading_deg, c.want_hdt), 0.005 + 1e-9);
    EXPECT_LT(std::stod(hdt.fields[0]), 360.0);
    const auto r = nmea::parse_rot(rot, &why);
    ASSERT_TRUE(r.has_value()) << why;
    EXPECT_NEAR(r->rot_deg_min, c.want_rot_deg_min, 0.005 + 1e-9);
    if (c.want_rot_deg_min < -0.005) {
      EXPECT_EQ(rot.fields[0][0], '-');  // bow to port
    }
  }
}

TEST(Devices, FeedbackSentences) {
  const sim::Devices dev(geo::LocalNed(kOrigin), kUtc0);
  for (const auto& [rudder_deg, rpm] : std::vector<std::pair<double, double>>{{-12.34, 87.65}, {35.0, 0.0}, {0.004, 150.0}}) {
    const std::string text = dev.feedback(geo::deg2rad(rudder_deg), rpm);
    SCOPED_TRACE(text);
    const auto lines = split_lines(text);
    ASSERT_EQ(lines.size(), 2u);
    const nmea::Sentence rsa = must_parse(lines[0]);
    const nmea::Sentence rpm_s = must_parse(lines[1]);
    EXPECT_EQ(rsa.talker, "ER");
    std::string why;
    const auto a = nmea::parse_rsa(rsa, &why);
    ASSERT_TRUE(a.has_value()) << why;
    EXPECT_NEAR(a->rudder_deg, rudder_deg, 0.005 + 1e-9);
    if (rudder_deg < 0) {
      EXPECT_EQ(rsa.fields[0][0], '-');
    }
    const auto n = nmea::parse_rpm(rpm_s, &why);
    ASSERT_TRUE(n.has_value()) << why;
    EXPECT_NEAR(n->rpm, rpm, 0.005 + 1e-9);
    EXPECT_EQ(n->shaft, 1);
  }
}

TEST(Devices, AisTargetType1AndType5Every6Minutes) {
  const geo::LocalNed frame(kOrigin);
  sim::Devices dev(frame, kUtc0);
  sim::TargetConfig tc;
  tc.mmsi = 257000002;
  tc.name = "Port side";
  tc.length = 101.0;
  tc.beam = 21.0;
  sim::AisMeasurement m{};
  m.mmsi = tc.mmsi;
  m.x = 3200.0;
  m.y = -800.0;
  m.cog = geo::deg2rad(-45.04);
  m.sog = 7.2;
  m.heading = geo::deg2rad(-45.4);
  m.rot = geo::deg2rad(10.0) / 60.0;  // 10 deg/min
  m.nav_status = 0;

  const int64_t t0 = sec(5.0);
  std::vector<std::string> lines = dev.ais_target(m, tc, t0);
  ASSERT_EQ(lines.size(), 3u);  // type 1 + type 5 in 2 fragments at the first report
  {
    const Vdm v = parse_vdm(lines[0]);
    EXPECT_FALSE(v.own);
    EXPECT_EQ(v.n, 1);
    const mpgc::testing::AisBits b(v.payload, v.fill);
    ASSERT_EQ(b.size(), 168u);
    const mpgc::testing::AisType1 d = mpgc::testing::ais_type1(b);
    EXPECT_EQ(d.type, 1u);
    EXPECT_EQ(d.mmsi, tc.mmsi);
    EXPECT_EQ(d.status, 0u);
    const int want_turn = static_cast<int>(std::lround(4.733 * std::sqrt(10.0)));
    EXPECT_EQ(d.rot, want_turn);
    EXPECT_NEAR(d.sog / 10.0, m.sog / kKn, 0.05 + 1e-9);
    const geo::LatLon ll = frame.to_latlon({m.x, m.y});
    EXPECT_NEAR(d.lon / 600000.0, geo::rad2deg(ll.lon), 0.5 / 600000 + 1e-12);
    EXPECT_NEAR(d.lat / 600000.0, geo::rad2deg(ll.lat), 0.5 / 600000 + 1e-12);
    EXPECT_LE(angle_diff_deg(d.cog / 10.0, 314.96), 0.05 + 1e-9);
    EXPECT_EQ(d.hdg, 315u);     // -45.4 deg -> 314.6 -> 315, whole degrees
    EXPECT_EQ(d.second, 5u);    // UTC second of 00:00:05
  }
  {
    const Vdm f1 = parse_vdm(lines[1]), f2 = parse_vdm(lines[2]);
    EXPECT_EQ(f1.n, 2);
    EXPECT_EQ(f1.k, 1);
    EXPECT_EQ(f2.n, 2);
    EXPECT_EQ(f2.k, 2);
    EXPECT_FALSE(f1.seq.empty());
    EXPECT_EQ(f1.seq, f2.seq);
    EXPECT_EQ(f1.channel, f2.channel);
    EXPECT_EQ(f1.fill, 0);
    mpgc::testing::AisBits b(f1.payload, f1.fill);
    b.append(f2.payload, f2.fill);
    ASSERT_EQ(b.size(), 424u);
    const mpgc::testing::AisType5 d = mpgc::testing::ais_type5(b);
    EXPECT_EQ(d.type, 5u);
    EXPECT_EQ(d.mmsi, tc.mmsi);
    EXPECT_EQ(mpgc::testing::ais_trimmed(d.name), "PORT SIDE");
    EXPECT_EQ(d.ship_type, 70u);
    EXPECT_EQ(d.bow + d.stern, 101u);  // to_bow + to_stern = length
    EXPECT_EQ(d.port + d.stbd, 21u);   // to_port + to_starboard = beam
  }
  // Later reports: type 1 only, until 6 min after the last type 5.
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(10)).size(), 1u);
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(359.9)).size(), 1u);
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(360.0)).size(), 3u);
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(370.0)).size(), 1u);
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(719.9)).size(), 1u);
  EXPECT_EQ(dev.ais_target(m, tc, t0 + sec(720.0)).size(), 3u);
  // A second target has its own schedule: its first report carries its type 5.
  sim::TargetConfig tc2 = tc;
  tc2.mmsi = 257000003;
  sim::AisMeasurement m2 = m;
  m2.mmsi = tc2.mmsi;
  EXPECT_EQ(dev.ais_target(m2, tc2, t0 + sec(730.0)).size(), 3u);
  EXPECT_EQ(dev.ais_target(m2, tc2, t0 + sec(740.0)).size(), 1u);
}

TEST(Devices, AisTargetNotAvailableValues) {
  sim::Devices dev(geo::LocalNed(kOrigin), kUtc0);
  sim::TargetConfig tc;
  tc.mmsi = 257000004;
  tc.length = 50, tc.beam = 10;
  sim::AisMeasurement m{};
  m.mmsi = tc.mmsi;
  m.sog = 3.0;
  m.heading = kNan;
  m.rot = kNan;
  m.nav_status = 5;
  const auto lines = dev.ais_target(m, tc, sec(1));
  ASSERT_FALSE(lines.empty());
  const Vdm v = parse_vdm(lines[0]);
  const mpgc::testing::AisBits b(v.payload, v.fill);
  ASSERT_EQ(b.size(), 168u);
  const mpgc::testing::AisType1 d = mpgc::testing::ais_type1(b);
  EXPECT_EQ(d.rot, -128);     // rot n/a
  EXPECT_EQ(d.hdg, 511u);     // heading n/a
  EXPECT_EQ(d.status, 5u);    // moored
  // Heading 359.6 deg rounds to 0 (never 360), COG -0.01 deg is 359.99 -> 0.0 (never 360.0).
  m.heading = geo::deg2rad(-0.4);
  m.cog = geo::deg2rad(-0.01);
  m.rot = geo::deg2rad(-720.0) / 60.0;  // beyond the scale: ROT_AIS saturates at -126
  const auto l2 = dev.ais_target(m, tc, sec(2));
  ASSERT_EQ(l2.size(), 1u);
  const Vdm v2 = parse_vdm(l2[0]);
  const mpgc::testing::AisBits b2(v2.payload, v2.fill);
  EXPECT_EQ(b2.u(128, 9), 0u);
  EXPECT_EQ(b2.u(116, 12), 0u);
  EXPECT_EQ(b2.s(42, 8), -126);
}

TEST(Devices, AisOwnShip) {
  const geo::LocalNed frame(kOrigin);
  sim::Devices dev(frame, kUtc0);
  const sim::NavMeasurement m{100.0, 200.0, geo::deg2rad(10.0), geo::deg2rad(12.0), 5.0, 0.0};
  EXPECT_TRUE(dev.ais_own(0, m, sec(1)).empty());
  const auto lines = dev.ais_own(257999999, m, sec(1));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("!AIVDO,", 0), 0u) << lines[0];
  const Vdm v = parse_vdm(lines[0]);
  EXPECT_TRUE(v.own);
  const mpgc::testing::AisBits b(v.payload, v.fill);
  ASSERT_EQ(b.size(), 168u);
  const mpgc::testing::AisType1 d = mpgc::testing::ais_type1(b);
  EXPECT_EQ(d.type, 1u);
  EXPECT_EQ(d.mmsi, 257999999u);
  const geo::LatLon ll = frame.to_latlon({m.x, m.y});
  EXPECT_NEAR(d.lat / 600000.0, geo::rad2deg(ll.lat), 0.5 / 600000 + 1e-12);
  EXPECT_NEAR(d.lon / 600000.0, geo::rad2deg(ll.lon), 0.5 / 600000 + 1e-12);
  EXPECT_EQ(d.hdg, 10u);
  EXPECT_EQ(d.cog, 120u);
}

TEST(Devices, OrderLinesSaturatedCountedAndFiltered) {
  sim::Devices dev(geo::LocalNed(kOrigin), kUtc0);
  const double max_rudder = geo::deg2rad(35.0), max_rpm = 100.0;
  const auto c = [&](const std::string& k) { return count(dev.counters(), k); };
  sim::DeviceOrders o;
  dev.on_order_lines({nmea::ror("AG", 10.0), nmea::prc("AG", 80.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_TRUE(o.rudder_seen);
  EXPECT_TRUE(o.rpm_seen);
  EXPECT_NEAR(o.rudder, geo::deg2rad(10.0), 1e-12);
  EXPECT_DOUBLE_EQ(o.rpm, 80.0);
  EXPECT_EQ(c("orders.saturated"), 0u);
  EXPECT_EQ(c("orders.ror"), 1u);
  EXPECT_EQ(c("orders.prc"), 1u);
  // Exactly at the limit: not saturated.
  dev.on_order_lines({nmea::ror("AG", 35.0), nmea::prc("AG", 100.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_EQ(c("orders.saturated"), 0u);
  EXPECT_NEAR(o.rudder, max_rudder, 1e-12);
  // Beyond: clipped and counted.
  dev.on_order_lines({nmea::ror("AG", -40.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_DOUBLE_EQ(o.rudder, -max_rudder);
  EXPECT_EQ(c("orders.saturated"), 1u);
  dev.on_order_lines({nmea::prc("AG", 120.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_DOUBLE_EQ(o.rpm, max_rpm);
  EXPECT_EQ(c("orders.saturated"), 2u);
  dev.on_order_lines({nmea::prc("AG", -5.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_DOUBLE_EQ(o.rpm, 0.0);
  EXPECT_EQ(c("orders.saturated"), 3u);
  // A bad checksum: counted, not used.
  std::string bad = nmea::ror("AG", 5.0);
  bad[bad.find('*') + 1] = bad[bad.find('*') + 1] == '0' ? '1' : '0';
  dev.on_order_lines({bad, "garbage"}, 0, max_rudder, max_rpm, &o);
  EXPECT_EQ(c("orders.bad_sentence"), 2u);
  EXPECT_DOUBLE_EQ(o.rudder, -max_rudder);
  // Invalid ROR/PRC (status V): counted by type, not used.
  dev.on_order_lines({nmea::ror("AG", kNan), nmea::prc("AG", kNan)}, 0, max_rudder, max_rpm, &o);
  EXPECT_EQ(c("orders.bad_ror"), 1u);
  EXPECT_EQ(c("orders.bad_prc"), 1u);
  EXPECT_DOUBLE_EQ(o.rudder, -max_rudder);
  EXPECT_DOUBLE_EQ(o.rpm, 0.0);
  // Other sentence types are ignored.
  dev.on_order_lines({nmea::hdt("HE", 10.0), nmea::rsa("ER", 3.0)}, 0, max_rudder, max_rpm, &o);
  EXPECT_EQ(c("orders.ignored"), 2u);
  EXPECT_DOUBLE_EQ(o.rudder, -max_rudder);
  EXPECT_EQ(c("orders.ror"), 3u);
  EXPECT_EQ(c("orders.prc"), 4u);
  // The bridge's saturated orders are taken as they are by the simulator (same 35 deg limit).
  bool sat = false;
  const std::string orders = sb::encode_orders(geo::deg2rad(50.0), 90.0, sb::ActuatorLimits{max_rudder, 0.0, 150.0}, &sat);
  EXPECT_TRUE(sat);
  dev.on_order_lines(split_lines(orders), 0, max_rudder, max_rpm, &o);
  EXPECT_NEAR(o.rudder, max_rudder, 1e-12);
  EXPECT_DOUBLE_EQ(o.rpm, 90.0);
  EXPECT_EQ(c("orders.saturated"), 3u);
}

// The steering gear's watchdog: orders are followed while they come; after the timeout without a
// rudder order the rudder goes amidships and the engine order is held; a new order resumes.
TEST(Devices, ActuatorWatchdogRudderAmidshipsEngineHeld) {
  sim::Devices dev(geo::LocalNed({geo::deg2rad(59.0), geo::deg2rad(10.0)}), 0);
  sim::DeviceOrders o;
  sim::ShipCommand cmd{0.1, 95.0};
  EXPECT_FALSE(sim::follow_orders(o, 5'000'000'000, 2.0, &cmd)) << "no order yet: nothing to watch";
  EXPECT_DOUBLE_EQ(cmd.rudder, 0.1);
  EXPECT_DOUBLE_EQ(cmd.rpm, 95.0);
  const double lim = geo::deg2rad(35.0);
  dev.on_order_lines({nmea::ror("AG", 20.0), nmea::prc("AG", 80.0)}, 10'000'000'000, lim, 150.0, &o);
  EXPECT_FALSE(sim::follow_orders(o, 11'900'000'000, 2.0, &cmd));
  EXPECT_NEAR(cmd.rudder, geo::deg2rad(20.0), 1e-12);
  EXPECT_DOUBLE_EQ(cmd.rpm, 80.0);
  EXPECT_TRUE(sim::follow_orders(o, 12'100'000'000, 2.0, &cmd)) << "2.1 s without an order";
  EXPECT_DOUBLE_EQ(cmd.rudder, 0.0);
  EXPECT_DOUBLE_EQ(cmd.rpm, 80.0) << "the engine order is held";
  dev.on_order_lines({nmea::ror("AG", -5.0)}, 13'000'000'000, lim, 150.0, &o);
  EXPECT_FALSE(sim::follow_orders(o, 13'100'000'000, 2.0, &cmd));
  EXPECT_NEAR(cmd.rudder, geo::deg2rad(-5.0), 1e-12);
}
