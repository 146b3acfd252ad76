// HIL replay: real NMEA/AIS logs played through gpsfake (a real gpsd 3.22) into GpsdClient, and
// compared with gpsd's own decoded truth (the .chk files of gpsd's regression tests), and the
// no-fix stretch of mtk-3301.log fed through NavFusion. Each test starts its own gpsfake on
// loopback (shared/notes/gpsd.md §1); gpsfake and JSON fields from tests/hil/gpsd_harness.hpp.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_bridge/gpsd_client.hpp"
#include "mpgc/testing.hpp"
#include "gpsd_harness.hpp"

namespace {

using namespace mpgc::ship_bridge;
using mpgc::testing::shared_data;

// ---------------------------------------------------------------------------------------------
// Everything GpsdClient gave for one replay, in order.
struct Replay {
  std::vector<GpsdEvent> events;
  std::vector<GnssFix> fixes;
  std::vector<AttitudeHeading> headings;
  std::vector<AisMessage> ais;
  std::vector<RawNmea> raw;
  int device_ends = 0;
  bool closed = false;  // poll returned false (gpsd closed the connection)
  uint64_t unparsed = 0;
  int gpsfake_rc = -1;
  double max_poll_s = 0;  // [s] longest poll(200 ms) call
};

Replay replay(const std::string& rel, bool nmea = false) {
  Replay r;
  const std::string log = shared_data(rel);
  // gpsfake -1 -p: the feed starts after our client has connected, and gpsfake exits (with its
  // gpsd) at the end of the log (gpsd_harness.hpp, notes §1).
  auto fake = mpgc::hil::GpsdProcess::gpsfake(log);
  if (!fake.ok()) {
    ADD_FAILURE() << "gpsfake did not start on " << log << ": " << fake.error();
    return r;
  }
  GpsdClient client("127.0.0.1", fake.port(), nmea);
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (std::chrono::steady_clock::now() < end) {
    const auto t0 = std::chrono::steady_clock::now();
    const bool open = client.poll(200000, &r.events);
    r.max_poll_s = std::max(r.max_poll_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (!open) {
      r.closed = true;
      break;
    }
  }
  // poll waits at most its timeout and then only reads what has arrived (slack for a loaded host).
  EXPECT_LT(r.max_poll_s, 1.2) << rel;
  EXPECT_FALSE(client.connected());
  r.unparsed = client.unparsed();
  r.gpsfake_rc = fake.wait_exit(10000).value_or(-1);
  for (const auto& e : r.events) {
    if (auto* f = std::get_if<GnssFix>(&e)) r.fixes.push_back(*f);
    if (auto* h = std::get_if<AttitudeHeading>(&e)) r.headings.push_back(*h);
    if (auto* a = std::get_if<AisMessage>(&e)) r.ais.push_back(*a);
    if (auto* n = std::get_if<RawNmea>(&e)) r.raw.push_back(*n);
    if (std::holds_alternative<DeviceEnd>(e)) ++r.device_ends;
  }
  std::printf("[ replay   ] %s%s: %zu events: %zu TPV, %zu ATT, %zu AIS, %zu raw NMEA, %d device ends, "
              "%llu unparsed, gpsfake rc %d, longest poll %.3f s\n",
              rel.c_str(), nmea ? " (nmea)" : "", r.events.size(), r.fixes.size(), r.headings.size(),
              r.ais.size(), r.raw.size(), r.device_ends, static_cast<unsigned long long>(r.unparsed),
              r.gpsfake_rc, r.max_poll_s);
  return r;
}

// ---------------------------------------------------------------------------------------------
// The truth: JSON lines of gpsd's .chk files. They are flat objects for the classes compared
// here, so a value is found by its key.
struct Json {
  std::string line;
  std::optional<std::string> raw(const std::string& key) const { return mpgc::hil::json_raw(line, key); }
  double num(const std::string& key) const {  // NaN when absent or not a number
    return mpgc::hil::json_number(line, key).value_or(std::nan(""));
  }
  std::string str(const std::string& key) const { return raw(key).value_or(""); }
};

std::vector<Json> chk_lines(const std::string& rel, const std::string& cls) {
  std::ifstream f(shared_data(rel));
  EXPECT_TRUE(f.good()) << shared_data(rel);
  std::vector<Json> out;
  std::string line;
  const std::string tag = "{\"class\":\"" + cls + "\"";
  while (std::getline(f, line)) {
    if (line.rfind(tag, 0) == 0) out.push_back(Json{line});
  }
  return out;
}

// Both absent (NaN), or equal within tol.
bool same(double ours, double truth, double tol) {
  if (std::isnan(truth)) return std::isnan(ours);
  return std::isfinite(ours) && std::fabs(ours - truth) <= tol;
}

// gpsd prints lat/lon with 9 decimals, speed (m/s) with 3, track with 4: the tolerances are
// those resolutions (the test asks for positions within 1e-6 deg).
std::string fix_mismatch(const GnssFix& f, const Json& t) {
  std::ostringstream why;
  const int mode = static_cast<int>(t.num("mode"));
  if (f.mode != mode) why << " mode " << f.mode << " vs " << mode;
  if (!same(f.lat_deg, t.num("lat"), 1e-6)) why << " lat " << f.lat_deg << " vs " << t.str("lat");
  if (!same(f.lon_deg, t.num("lon"), 1e-6)) why << " lon " << f.lon_deg << " vs " << t.str("lon");
  if (!same(f.speed, t.num("speed"), 0.0005 + 1e-9)) why << " speed " << f.speed << " vs " << t.str("speed");
  if (!same(f.track_deg, t.num("track"), 0.00005 + 1e-9)) why << " track " << f.track_deg << " vs " << t.str("track");
  return why.str();
}

// Every TPV against the .chk's, in order; prints and returns n matched.
int compare_tpv(const std::string& rel, const Replay& r) {
  const auto truth = chk_lines(rel + ".chk", "TPV");
  int n = 0;
  for (size_t i = 0; i < truth.size(); ++i) {
    if (i >= r.fixes.size()) {
      ADD_FAILURE() << rel << " TPV " << i << " missing: " << truth[i].line;
      continue;
    }
    const std::string why = fix_mismatch(r.fixes[i], truth[i]);
    if (why.empty()) ++n;
    else ADD_FAILURE() << rel << " TPV " << i << ":" << why << "\n  truth: " << truth[i].line;
  }
  std::printf("[ agree    ] %s: %d of %zu TPV agree with the .chk (%zu received)\n", rel.c_str(), n,
              truth.size(), r.fixes.size());
  EXPECT_EQ(r.fixes.size(), truth.size()) << rel;
  return n;
}

void expect_clean_end(const Replay& r, const std::string& rel) {
  EXPECT_TRUE(r.closed) << rel << ": the connection did not close after the replay";
  EXPECT_GE(r.device_ends, 1) << rel;
  ASSERT_FALSE(r.events.empty());
  EXPECT_TRUE(std::holds_alternative<DeviceEnd>(r.events.back())) << rel << ": last event is not DeviceEnd";
  // gpsd's {"class":"DEVICE","path":"/dev/pts/N","activated":0} names the pty gpsfake fed.
  for (const auto& e : r.events) {
    const auto* d = std::get_if<DeviceEnd>(&e);
    if (d != nullptr && &e != &r.events.back()) {
      EXPECT_EQ(d->device.rfind("/dev/pts/", 0), 0u) << d->device;
    }
  }
  EXPECT_EQ(r.gpsfake_rc, 0) << rel;
}

// A replay of rel that ended cleanly and whose TPV agree with the .chk's: tpv_agree of them.
Replay checked_replay(const std::string& rel, int tpv_agree, bool nmea = false) {
  Replay r = replay(rel, nmea);
  expect_clean_end(r, rel);
  EXPECT_EQ(compare_tpv(rel, r), tpv_agree) << rel;
  return r;
}

// ---------------------------------------------------------------------------------------------
// AIS truth (sample.aivdm.js.chk is scaled: degrees, knots, "turn" as "nan"/"fastleft"/
// "fastright" or (raw/4.733)^2 rounded and unsigned: gpsd_json.c prints rot1*rot1).
std::string ais_mismatch_scaled(const AisMessage& m, const Json& t) {
  std::ostringstream why;
  const double kn = mpgc::geo::kKnot;
  if (!m.has_position) why << " no position";
  if (!same(m.lat_deg, t.num("lat"), 1e-6)) why << " lat " << m.lat_deg << " vs " << t.str("lat");
  if (!same(m.lon_deg, t.num("lon"), 1e-6)) why << " lon " << m.lon_deg << " vs " << t.str("lon");
  if (!same(m.sog / kn, t.num("speed"), 1e-6)) why << " sog " << m.sog / kn << " kn vs " << t.str("speed");
  const double cog = t.str("course") == "360.0" ? std::nan("") : t.num("course");
  if (!same(m.cog_deg, cog, 1e-6)) why << " cog " << m.cog_deg << " vs " << t.str("course");
  const double hdg = t.num("heading") == 511 ? std::nan("") : t.num("heading");
  if (!same(m.heading_deg, hdg, 0.0)) why << " heading " << m.heading_deg << " vs " << t.str("heading");
  const int second = static_cast<int>(t.num("second"));
  if (m.second != second) why << " second " << m.second << " vs " << second;
  if (m.type >= 1 && m.type <= 3) {
    const int status = static_cast<int>(t.num("status"));
    if (m.nav_status != status) why << " status " << m.nav_status << " vs " << status;
    const std::string turn = t.str("turn");
    bool ok;
    if (turn == "nan") ok = m.turn_raw == -128;
    else if (turn == "fastleft") ok = m.turn_raw == -127;
    else if (turn == "fastright") ok = m.turn_raw == 127;
    else {
      const double rot1 = m.turn_raw / 4.733;
      ok = m.turn_raw > -127 && m.turn_raw < 127 && std::lround(rot1 * rot1) == std::lround(t.num("turn"));
    }
    if (!ok) why << " turn raw " << m.turn_raw << " vs " << turn;
  } else {
    if (m.nav_status != 15) why << " class B status " << m.nav_status;
    if (m.turn_raw != -128) why << " class B turn " << m.turn_raw;
  }
  return why.str();
}

// Dimensions: all four 0 means "not available" (NaN in AisMessage).
std::string static_mismatch(const AisMessage& m, const Json& t) {
  std::ostringstream why;
  if (!m.has_static) why << " no static data";
  if (m.name != t.str("shipname")) why << " name '" << m.name << "' vs '" << t.str("shipname") << "'";
  const double b = t.num("to_bow"), s = t.num("to_stern"), p = t.num("to_port"), sb = t.num("to_starboard");
  const bool none = b == 0 && s == 0 && p == 0 && sb == 0;
  const double nan = std::nan("");
  if (!same(m.to_bow, none ? nan : b, 0.0)) why << " to_bow " << m.to_bow << " vs " << b;
  if (!same(m.to_stern, none ? nan : s, 0.0)) why << " to_stern " << m.to_stern << " vs " << s;
  if (!same(m.to_port, none ? nan : p, 0.0)) why << " to_port " << m.to_port << " vs " << p;
  if (!same(m.to_starboard, none ? nan : sb, 0.0)) why << " to_starboard " << m.to_starboard << " vs " << sb;
  const int st = static_cast<int>(t.num("shiptype"));
  if (m.ship_type != (st == 0 ? -1 : st)) why << " ship_type " << m.ship_type << " vs " << st;
  if (t.raw("callsign") && m.callsign != t.str("callsign"))
    why << " callsign '" << m.callsign << "' vs '" << t.str("callsign") << "'";
  return why.str();
}

// The next received message of the same type and MMSI at or after *k (gpsd's order is the log's).
const AisMessage* next_match(const std::vector<AisMessage>& got, size_t* k, int type, uint32_t mmsi) {
  for (size_t j = *k; j < got.size(); ++j) {
    if (got[j].type == type && got[j].mmsi == mmsi) {
      *k = j + 1;
      return &got[j];
    }
  }
  return nullptr;
}

// =============================================================================================

TEST(HilReplay, SaabR4TpvAndOwnShipAis) {
  const std::string rel = "nmea/gpsd/saab-r4.log";
  const Replay r = checked_replay(rel, 14);

  // AIS: the .chk is unscaled, as our watch: the raw integers, converted.
  const auto truth = chk_lines(rel + ".chk", "AIS");
  ASSERT_EQ(r.ais.size(), truth.size());
  size_t own_truth = 0, own_got = 0, k = 0;
  for (const auto& t : truth) {
    const auto mmsi = static_cast<uint32_t>(t.num("mmsi"));
    const AisMessage* m = next_match(r.ais, &k, static_cast<int>(t.num("type")), mmsi);
    ASSERT_NE(m, nullptr) << t.line;
    EXPECT_TRUE(same(m->lat_deg, t.num("lat") / 600000.0, 1e-9)) << t.line;
    EXPECT_TRUE(same(m->lon_deg, t.num("lon") / 600000.0, 1e-9)) << t.line;
    EXPECT_TRUE(same(m->sog, t.num("speed") / 10.0 * mpgc::geo::kKnot, 1e-9)) << t.line;
    EXPECT_TRUE(same(m->cog_deg, t.num("course") / 10.0, 1e-9)) << t.line;
    EXPECT_TRUE(same(m->heading_deg, t.num("heading"), 0.0)) << t.line;
    EXPECT_EQ(m->turn_raw, static_cast<int>(t.num("turn"))) << t.line;
    EXPECT_EQ(m->nav_status, static_cast<int>(t.num("status"))) << t.line;
    if (mmsi == 244121341) ++own_truth;
  }
  // The own ship's !AIVDO comes out of gpsd as a plain AIS message (nothing marks it): only its
  // MMSI tells it apart, which is what the bridge filters on (AisAssembler's own_mmsi).
  for (const auto& m : r.ais) own_got += m.mmsi == 244121341;
  std::printf("[ own ship ] saab-r4: %zu AIS messages from own MMSI 244121341 (%zu in the .chk)\n", own_got,
              own_truth);
  EXPECT_EQ(own_truth, 12u);
  EXPECT_EQ(own_got, own_truth);
  // $HEHDT is dropped by gpsd 3.22's lexer (talker HE): no heading at all from this log.
  EXPECT_TRUE(r.headings.empty());
  EXPECT_EQ(r.unparsed, 0u);
}

TEST(HilReplay, SaabR4WithNmeaPassThrough) {
  // With nmea = true gpsd passes the sentences through as well: the !AIVDO lines arrive raw (the
  // only place own-ship AIS is marked as such), the JSON reports are unchanged.
  const std::string rel = "nmea/gpsd/saab-r4.log";
  const Replay r = checked_replay(rel, 14, true);
  size_t aivdo = 0, aivdm = 0, dollar = 0;
  for (const auto& n : r.raw) {
    EXPECT_EQ(n.line.find_first_of("\r\n"), std::string::npos) << n.line;
    aivdo += n.line.rfind("!AIVDO", 0) == 0;
    aivdm += n.line.rfind("!AIVDM", 0) == 0;
    dollar += n.line[0] == '$';
  }
  std::printf("[ raw nmea ] saab-r4: %zu lines: %zu !AIVDO, %zu !AIVDM, %zu $-sentences\n", r.raw.size(),
              aivdo, aivdm, dollar);
  EXPECT_EQ(aivdo, 12u);
  EXPECT_EQ(aivdm, 2u);
  EXPECT_GT(dollar, 0u);
  size_t own = 0;
  for (const auto& m : r.ais) own += m.mmsi == 244121341;
  EXPECT_EQ(own, 12u);
  EXPECT_EQ(r.unparsed, 0u);
}

TEST(HilReplay, HemiTpvAndHeadings) {
  const std::string rel = "nmea/gpsd/hemi.log";
  const Replay r = checked_replay(rel, 215);

  // ATT headings = the log's non-empty $GPHDT values, in order.
  std::ifstream f(shared_data(rel));
  std::vector<double> hdt;
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("$GPHDT,", 0) != 0) continue;
    const std::string v = line.substr(7, line.find(',', 7) - 7);
    if (!v.empty()) hdt.push_back(std::stod(v));
  }
  ASSERT_EQ(hdt.size(), 4u);
  ASSERT_EQ(r.headings.size(), hdt.size());
  int n = 0;
  for (size_t i = 0; i < hdt.size(); ++i) {
    EXPECT_NEAR(r.headings[i].heading_deg, hdt[i], 1e-9) << i;
    n += std::fabs(r.headings[i].heading_deg - hdt[i]) <= 1e-9;
    EXPECT_FALSE(r.headings[i].device.empty());
  }
  std::printf("[ agree    ] hemi.log: %d of %zu ATT headings equal the log's $GPHDT\n", n, hdt.size());
  EXPECT_EQ(r.unparsed, 0u);
}

TEST(HilReplay, Mtk3301NoFixStretchAndNavFusion) {
  const std::string rel = "nmea/gpsd/mtk-3301.log";
  const Replay r = checked_replay(rel, 15);

  // The power-up stretch: gpsd says mode 1, and the receiver's placeholder position (8960.0000 N
  // = 90 N, 0 E) never comes out as coordinates.
  const auto truth = chk_lines(rel + ".chk", "TPV");
  size_t no_fix = 0;
  for (size_t i = 0; i < std::min(truth.size(), r.fixes.size()); ++i) {
    if (truth[i].num("mode") >= 2) continue;
    ++no_fix;
    EXPECT_LT(r.fixes[i].mode, 2) << i;
    EXPECT_TRUE(std::isnan(r.fixes[i].lat_deg) && std::isnan(r.fixes[i].lon_deg)) << i;
  }
  EXPECT_EQ(no_fix, 7u);
  for (const auto& fx : r.fixes) {
    if (fx.mode >= 2) {
      EXPECT_TRUE(std::isfinite(fx.lat_deg) && std::isfinite(fx.lon_deg));
      EXPECT_FALSE(fx.lat_deg == 0.0 && fx.lon_deg == 0.0);
    }
  }

  // Every event through NavFusion, at a monotonic "now": +100 ms per event, or the TPV's own
  // time when it has one and that is later.
  NavFusion nav(NavParams{}, std::nullopt);
  int64_t now = 1'000'000'000;
  size_t checked_no_fix = 0, valid_states = 0;
  bool seen_good_fix = false;
  for (const auto& e : r.events) {
    now += 100'000'000;
    if (const auto* fx = std::get_if<GnssFix>(&e)) {
      if (fx->time_ns > now) now = fx->time_ns;
      nav.on_fix(*fx, now);
      const NavOutput s = nav.state(now);
      if (fx->mode < 2) {
        ++checked_no_fix;
        EXPECT_FALSE(s.position_valid) << "no-fix TPV #" << checked_no_fix << ": " << s.why_invalid;
        EXPECT_FALSE(seen_good_fix && s.position_valid);
      } else {
        seen_good_fix = true;
      }
    } else if (const auto* h = std::get_if<AttitudeHeading>(&e)) {
      nav.on_heading(h->heading_deg, now);
    }
    const NavOutput s = nav.state(now);
    if (s.position_valid) {
      ++valid_states;
      EXPECT_FALSE(s.lat == 0.0 && s.lon == 0.0) << "0,0 published as valid";
      EXPECT_LT(std::fabs(mpgc::geo::rad2deg(s.lat) - 52.2164), 0.01);  // Enschede, not the placeholder
      EXPECT_LT(std::fabs(mpgc::geo::rad2deg(s.lon) - 6.8850), 0.01);
    } else {
      EXPECT_TRUE(std::isnan(s.lat) && std::isnan(s.lon));
    }
  }
  EXPECT_EQ(checked_no_fix, 7u);
  EXPECT_GT(valid_states, 0u);  // the later fixes do make the position valid
  std::printf("[ navfusion] mtk-3301: %zu no-fix TPVs all invalid; %zu valid states after the first fix\n",
              checked_no_fix, valid_states);
}

TEST(HilReplay, SampleAivdmEqualsChk) {
  const std::string rel = "nmea/gpsd/sample.aivdm";
  const Replay r = replay(rel);
  expect_clean_end(r, rel);
  const auto truth = chk_lines(rel + ".js.chk", "AIS");
  ASSERT_EQ(truth.size(), 97u);
  EXPECT_EQ(r.ais.size(), truth.size());
  std::map<int, int> got_types;
  for (const auto& m : r.ais) ++got_types[m.type];

  int pos_n = 0, pos_N = 0, stat_n = 0, stat_N = 0;
  size_t k = 0;
  for (const auto& t : truth) {
    const int type = static_cast<int>(t.num("type"));
    const auto mmsi = static_cast<uint32_t>(t.num("mmsi"));
    const bool position = (type >= 1 && type <= 3) || type == 18 || type == 19;
    const bool stat = type == 5 || type == 24 || type == 19;
    if (!position && !stat) continue;
    const AisMessage* m = next_match(r.ais, &k, type, mmsi);
    if (position) ++pos_N;
    if (stat) ++stat_N;
    if (m == nullptr) {
      ADD_FAILURE() << "not received: " << t.line;
      continue;
    }
    if (position) {
      const std::string why = ais_mismatch_scaled(*m, t);
      if (why.empty()) ++pos_n;
      else ADD_FAILURE() << "type " << type << " mmsi " << mmsi << ":" << why << "\n  truth: " << t.line;
    }
    if (stat) {
      const std::string why = static_mismatch(*m, t);
      if (why.empty()) ++stat_n;
      else ADD_FAILURE() << "type " << type << " mmsi " << mmsi << ":" << why << "\n  truth: " << t.line;
    }
  }
  std::printf("[ agree    ] sample.aivdm: %d of %d position reports (1/2/3/18/19), %d of %d static "
              "(5/19/24) agree with the .js.chk\n", pos_n, pos_N, stat_n, stat_N);
  EXPECT_EQ(pos_n, pos_N);
  EXPECT_EQ(stat_n, stat_N);
  EXPECT_EQ(pos_N, 10);  // in the .chk: 6 of type 1/2/3, 3 of type 18, 1 of type 19
  EXPECT_EQ(stat_N, 6);  // 3 type 5, 2 merged type 24, 1 type 19
}

TEST(HilReplay, PyaisSampleAndMixed) {
  {
    const std::string rel = "nmea/pyais/nmea_data_sample.txt";
    const Replay r = replay(rel);
    expect_clean_end(r, rel);
    std::map<int, int> types;
    size_t reports = 0, with_pos = 0;
    for (const auto& m : r.ais) {
      ++types[m.type];
      if (m.type == 1 || m.type == 3 || m.type == 18) {
        ++reports;
        with_pos += m.has_position;
      }
    }
    std::printf("[ count    ] nmea_data_sample.txt: %zu AIS messages, %zu type 1/3/18 reports (%zu with a "
                "position), %llu unparsed\n", r.ais.size(), reports, with_pos,
                static_cast<unsigned long long>(r.unparsed));
    std::string hist;
    for (const auto& [t, c] : types) hist += " " + std::to_string(t) + ":" + std::to_string(c);
    std::printf("[ count    ] types:%s\n", hist.c_str());
    EXPECT_GE(r.ais.size(), 776u);  // notes §7: 776 AIS JSON from the 898 lines
    EXPECT_GE(reports, 761u);       // notes §7: all 761 type 1/3/18 reports
    for (const auto& m : r.ais) {
      if (m.has_position) {
        EXPECT_LE(std::fabs(m.lat_deg), 90.0);
        EXPECT_LE(std::fabs(m.lon_deg), 180.0);
      }
      EXPECT_TRUE(std::isnan(m.sog) || (m.sog >= 0 && m.sog <= 102.3 * mpgc::geo::kKnot));
      EXPECT_TRUE(std::isnan(m.cog_deg) || (m.cog_deg >= 0 && m.cog_deg < 360));
      EXPECT_TRUE(std::isnan(m.heading_deg) || (m.heading_deg >= 0 && m.heading_deg < 360));
    }
  }
  {
    const std::string rel = "nmea/pyais/mixed.txt";
    const Replay r = replay(rel);
    expect_clean_end(r, rel);
    std::printf("[ count    ] mixed.txt: %zu AIS messages, %zu TPV, %llu unparsed\n", r.ais.size(),
                r.fixes.size(), static_cast<unsigned long long>(r.unparsed));
    EXPECT_GE(r.ais.size(), 12u);  // notes §7: 12 AIS + 1 TPV
    EXPECT_GE(r.fixes.size(), 1u);
  }
}

// Not gpsd but a loopback server speaking its protocol, for what the logs do not contain: a line
// split across writes (poll must not block on the rest), lines libgps cannot parse (gpsd 3.22's
// broken ATT, an ERROR, garbage), AIS "not available" values, type 24 parts A and B alone, stale
// TPV fields after a no-fix TPV, set bits left over from an AIS before a DEVICE line, and the end.
TEST(HilReplay, FakeGpsdEdgeCases) {
  const int ls = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(ls, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = 0;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(bind(ls, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(listen(ls, 1), 0);
  socklen_t len = sizeof a;
  ASSERT_EQ(getsockname(ls, reinterpret_cast<sockaddr*>(&a), &len), 0);
  const int port = ntohs(a.sin_port);

  std::thread server([ls] {
    const int c = accept(ls, nullptr, nullptr);
    if (c < 0) return;
    const auto put = [c](const std::string& s) { (void)send(c, s.data(), s.size(), MSG_NOSIGNAL); };
    const auto pause = [](int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); };
    // A whole line and the start of the next in one write (libgps then holds a partial line
    // behind a complete one), the rest of that line a second later, then a partial line alone.
    put("{\"class\":\"VERSION\",\"release\":\"3.22\",\"rev\":\"3.22\",\"proto_major\":3,\"proto_minor\":14}\r\n"
        "{\"class\":\"TPV\",\"device\":\"/dev/x\",\"mode\":3,\"lat\":59.9,");
    pause(1000);
    put("\"lon\":10.7,");
    pause(1000);
    put("\"speed\":2.5,\"track\":45.0}\r\n");
    put("{\"class\":\"ATT\",\"device\":\"/dev/x\",,\"time\":\"1970-01-01T00:00:01.257Z\"\"heading\":21.000}\r\n");
    put("{\"class\":\"ERROR\",\"message\":\"unrecognized request\"}\r\n");
    put("garbage\r\n");
    put("$GPHDT,47.5,T*03\r\n");
    put("{\"class\":\"ATT\",\"device\":\"/dev/x\",\"heading\":47.5}\r\n");
    put("{\"class\":\"AIS\",\"device\":\"/dev/x\",\"type\":1,\"repeat\":0,\"mmsi\":123456789,\"scaled\":false,"
        "\"status\":15,\"turn\":-128,\"speed\":1023,\"accuracy\":false,\"lon\":108600000,\"lat\":54600000,"
        "\"course\":3600,\"heading\":511,\"second\":60,\"maneuver\":0,\"raim\":false,\"radio\":0}\r\n");
    put("{\"class\":\"DEVICE\",\"path\":\"/dev/x\",\"driver\":\"NMEA0183\",\"activated\":\"2024-12-01T00:00:00.000Z\"}\r\n");
    put("{\"class\":\"AIS\",\"device\":\"/dev/x\",\"type\":24,\"repeat\":0,\"mmsi\":271041815,\"scaled\":false,"
        "\"shipname\":\"PROGUY@@\"}\r\n");
    put("{\"class\":\"AIS\",\"device\":\"/dev/x\",\"type\":24,\"repeat\":0,\"mmsi\":271041815,\"scaled\":false,"
        "\"shiptype\":60,\"vendorid\":\"1D00014\",\"model\":12,\"serial\":199796,\"callsign\":\"TC6163\","
        "\"to_bow\":0,\"to_stern\":15,\"to_port\":0,\"to_starboard\":5}\r\n");
    // Lines on which libgps 3.22's gps_unpack loops for ever (fuzz_gpsd_json): the client must
    // refuse them and go on. A DEVICES list is well-formed gpsd output, ignored.
    put("{\"class\":\"AIS\",\"type\":24,\"callsign\":\"TC616false3\",\"class\":\"TPV\"}\r\n");
    put("{\"class\":\"TPV\",\"mode\":\"x\",\"class\":\"TPV\"}\r\n");
    put("{\"classppp\":\"TPV\",\"mode\":\"x\",\"class\":\"TPV\"}\r\n");
    put("{\"class\":\"DEVICES\",\"devices\":[{\"class\":\"DEVICE\",\"path\":\"/dev/" + std::string(300, 'p') +
        "\"},{\"class\":\"DEVICE\",\"path\":\"/dev/y\"}]}\r\n");
    put("{\"class\":\"TPV\",\"mode\":3}{\"class\":\"TPV\",\"mode\":3}\r\n");
    put("{\"class\":\"TPV\",\"device\":\"" + std::string(40000, 'd') + "\"}\r\n");  // > 16 KiB: dropped
    put("{\"class\":\"TPV\",\"device\":\"/dev/x\",\"mode\":1}\r\n");
    put("{\"class\":\"DEVICE\",\"path\":\"/dev/x\",\"activated\":0}\r\n");
    pause(200);
    close(c);
  });

  GpsdClient client("127.0.0.1", port);
  EXPECT_TRUE(client.connected());
  std::vector<GpsdEvent> ev;
  double max_poll = 0;
  int polls = 0;
  bool closed = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!closed && std::chrono::steady_clock::now() < end) {
    const auto t0 = std::chrono::steady_clock::now();
    closed = !client.poll(50000, &ev);
    ++polls;
    max_poll = std::max(max_poll, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  server.join();
  close(ls);
  ASSERT_TRUE(closed);
  EXPECT_FALSE(client.connected());
  EXPECT_FALSE(client.poll(0, &ev));
  // A poll(50 ms) that blocked on the split TPV would have taken ~1 s.
  EXPECT_LT(max_poll, 0.6);
  // ... and one that returned at once while a partial line was buffered would spin: ~2.2 s of
  // 50 ms polls are ~45 calls.
  EXPECT_LT(polls, 200);
  // broken ATT, ERROR, garbage; four lines that would hang libgps, one line longer than 16 KiB
  EXPECT_EQ(client.unparsed(), 8u);

  ASSERT_EQ(ev.size(), 9u);
  const auto& f3 = std::get<GnssFix>(ev[0]);
  EXPECT_EQ(f3.mode, 3);
  EXPECT_DOUBLE_EQ(f3.lat_deg, 59.9);
  EXPECT_DOUBLE_EQ(f3.lon_deg, 10.7);
  EXPECT_DOUBLE_EQ(f3.speed, 2.5);
  EXPECT_DOUBLE_EQ(f3.track_deg, 45.0);
  EXPECT_EQ(f3.time_ns, 0);
  EXPECT_EQ(f3.device, "/dev/x");
  EXPECT_EQ(std::get<RawNmea>(ev[1]).line, "$GPHDT,47.5,T*03");
  EXPECT_DOUBLE_EQ(std::get<AttitudeHeading>(ev[2]).heading_deg, 47.5);
  const auto& na = std::get<AisMessage>(ev[3]);
  EXPECT_EQ(na.mmsi, 123456789u);
  EXPECT_FALSE(na.has_position);
  EXPECT_TRUE(std::isnan(na.lat_deg) && std::isnan(na.lon_deg) && std::isnan(na.sog) && std::isnan(na.cog_deg) &&
              std::isnan(na.heading_deg));
  EXPECT_EQ(na.turn_raw, -128);
  EXPECT_EQ(na.second, 60);
  const auto& pa = std::get<AisMessage>(ev[4]);  // the DEVICE line before it did not repeat the AIS
  EXPECT_EQ(pa.type, 24);
  EXPECT_TRUE(pa.has_static);
  EXPECT_EQ(pa.name, "PROGUY");
  EXPECT_EQ(pa.ship_type, -1);
  EXPECT_TRUE(std::isnan(pa.to_bow));
  const auto& pb = std::get<AisMessage>(ev[5]);
  EXPECT_EQ(pb.name, "");
  EXPECT_EQ(pb.ship_type, 60);
  EXPECT_EQ(pb.callsign, "TC6163");
  EXPECT_DOUBLE_EQ(pb.to_bow, 0.0);
  EXPECT_DOUBLE_EQ(pb.to_stern, 15.0);
  EXPECT_DOUBLE_EQ(pb.to_port, 0.0);
  EXPECT_DOUBLE_EQ(pb.to_starboard, 5.0);
  const auto& f1 = std::get<GnssFix>(ev[6]);  // nothing of the earlier 3-D fix carried over
  EXPECT_EQ(f1.mode, 1);
  EXPECT_TRUE(std::isnan(f1.lat_deg) && std::isnan(f1.lon_deg) && std::isnan(f1.speed) && std::isnan(f1.track_deg));
  EXPECT_EQ(std::get<DeviceEnd>(ev[7]).device, "/dev/x");
  EXPECT_TRUE(std::holds_alternative<DeviceEnd>(ev[8]));  // the connection closed
}

TEST(HilReplay, LinesThatWouldHangLibgpsAreNamed) {
  EXPECT_EQ(gpsd_json_problem(R"({"class":"TPV","device":"/dev/x","mode":3,"lat":59.9,"lon":10.7})"), "");
  EXPECT_EQ(gpsd_json_problem(R"({"class":"ATT","heading":47.5,"a":[1,-2.5e3,true,null,{"b":"\"q\""}]} )"), "");
  EXPECT_EQ(gpsd_json_problem(R"({"class":"TPV","mode":"x","class":"TPV"})"), "more than one \"class\": key");
  EXPECT_EQ(gpsd_json_problem(R"({"classp":"TPV","mode":"x","class":"TPV"})"), "\"class\" is not the first key");
  EXPECT_EQ(gpsd_json_problem(R"( {"class":"TPV"})"), "\"class\" is not the first key");
  EXPECT_EQ(gpsd_json_problem(R"({"class":"TPV"}{"class":"TPV"})"), "not one well-formed JSON object");
  for (const char* bad : {R"({"class":"ATT",,"heading":1})", R"({"class":"TPV","mode":01.})", R"({"class":"TPV")",
                          R"({"class":"TPV","x":1e})", R"({"class":"TPV","x":"a\q"})", R"([{"class":"TPV"}])", ""})
    EXPECT_EQ(gpsd_json_problem(bad), "not one well-formed JSON object") << bad;
  // Deeper than 32 levels is refused, not recursed into.
  std::string deep = R"({"class":"TPV","x":)";
  for (int i = 0; i < 40; ++i) deep += "[";
  for (int i = 0; i < 40; ++i) deep += "]";
  EXPECT_EQ(gpsd_json_problem(deep + "}"), "not one well-formed JSON object");
}

TEST(HilReplay, NoGpsdThrowsNamingHostAndPort) {
  // Nothing listens on port 1 of loopback.
  try {
    GpsdClient c("127.0.0.1", 1);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("127.0.0.1:1"), std::string::npos) << e.what();
    std::printf("[ message  ] %s\n", e.what());
  }
}

}  // namespace
