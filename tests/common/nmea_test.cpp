// NMEA 0183 framing/parser/encoders/decoders and the AIS encoder, against real logs (gpsd, pyais)
// and an AIS bit reader independent of the encoder (tests/support, mpgc/testing_ais.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "mpgc/nmea/ais.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/testing.hpp"
#include "mpgc/testing_ais.hpp"

using namespace mpgc;

namespace {

std::vector<std::string> read_lines(const std::string& rel) {
  std::ifstream in(mpgc::testing::shared_data(rel), std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot read " << mpgc::testing::shared_data(rel);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// Every non-blank line of a log: parsed, or rejected with a reason (counted per reason).
struct LogCount {
  int lines = 0, good = 0, bad = 0;
  std::map<std::string, int> reasons;  // first word(s) of the reason -> count
  std::vector<nmea::Sentence> sentences;
};
LogCount parse_log(const std::string& rel) {
  LogCount c;
  for (const auto& l : read_lines(rel)) {
    if (l.find_first_not_of(" \t\r\n") == std::string::npos) continue;
    ++c.lines;
    std::string why;
    auto s = nmea::parse(l, &why);
    if (s) {
      ++c.good;
      c.sentences.push_back(*s);
    } else {
      ++c.bad;
      EXPECT_FALSE(why.empty()) << l;
      ++c.reasons[why.substr(0, why.find_first_of(":("))];
    }
  }
  std::printf("%s: %d lines, %d sentences parsed, %d rejected\n", rel.c_str(), c.lines, c.good, c.bad);
  for (const auto& [r, n] : c.reasons) std::printf("    %4d  %s\n", n, r.c_str());
  return c;
}

// "ddmm.mmmm" + hemisphere -> degrees (test-local, independent of the encoder).
double to_deg(const std::string& v, const std::string& hemi, int deg_digits) {
  const double d = std::atof(v.substr(0, deg_digits).c_str());
  const double m = std::atof(v.substr(deg_digits).c_str());
  return (hemi == "S" || hemi == "W" ? -1 : 1) * (d + m / 60.0);
}

nmea::Sentence must_parse(const std::string& line) {
  std::string why;
  auto s = nmea::parse(line, &why);
  EXPECT_TRUE(s.has_value()) << line << ": " << why;
  return s.value_or(nmea::Sentence{});
}

// ---- AIS payloads read back by testing_ais.hpp, independently of the encoder ----

// Payload and fill of one or more framed !AIVDM sentences (checked by the parser).
mpgc::testing::AisBits bits_of(const std::vector<std::string>& sentences) {
  std::string payload;
  int fill = 0;
  for (const auto& l : sentences) {
    const auto s = must_parse(l);
    EXPECT_EQ(s.type, "VDM");
    if (s.fields.size() != 6) return mpgc::testing::AisBits("", 0);
    payload += s.fields[4];
    fill = std::atoi(s.fields[5].c_str());
  }
  return mpgc::testing::AisBits(payload, fill);
}

mpgc::testing::AisType1 decode1(const mpgc::testing::AisBits& b) {
  EXPECT_EQ(b.size(), 168u);
  return mpgc::testing::ais_type1(b);
}

mpgc::testing::AisType5 decode5(const mpgc::testing::AisBits& b) {
  EXPECT_EQ(b.size(), 424u);
  return mpgc::testing::ais_type5(b);
}

std::string strip_crlf(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

}  // namespace

// ---------------------------------------------------------------- framing and parser

TEST(NmeaFrame, ChecksumAndFrame) {
  EXPECT_EQ(nmea::frame('$', "GPHDT,47.5,T"), "$GPHDT,47.5,T*03\r\n");
  EXPECT_EQ(nmea::checksum("AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,0"), "4A");
  EXPECT_EQ(nmea::checksum("HEHDT,4.0,T"), "2B");
  EXPECT_EQ(nmea::checksum(""), "00");
  EXPECT_EQ(nmea::checksum("GPHDT,274.07,T"), "03");
}

TEST(NmeaParse, AcceptsAndSplits) {
  std::string why;
  auto s = nmea::parse("$GPRMC,081438.000,A,5212.982641,N,00653.105897,E,0.042,0.00,230808,,,A*59\r\n", &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->start, '$');
  EXPECT_EQ(s->talker, "GP");
  EXPECT_EQ(s->type, "RMC");
  ASSERT_EQ(s->fields.size(), 12u);
  EXPECT_EQ(s->fields[2], "5212.982641");
  EXPECT_EQ(s->fields[9], "");  // empty fields kept
  EXPECT_EQ(s->fields[11], "A");

  s = nmea::parse("!AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,0*4A  \t\n", &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->start, '!');
  EXPECT_EQ(s->talker, "AI");
  EXPECT_EQ(s->type, "VDM");
  EXPECT_EQ(s->fields.size(), 6u);

  // Proprietary: talker P, type = the rest of the address.
  s = nmea::parse("$PMTK010,001*2E", &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->talker, "P");
  EXPECT_EQ(s->type, "MTK010");
  s = nmea::parse("$PGHP,1,2008,5,9,0,0,0,10,338,2,,1,09*17", &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->type, "GHP");

  // Tag block skipped; lower-case checksum accepted.
  s = nmea::parse("\\g:1-2-73874*A\\!AIVDM,1,1,,A,15MrVH0000KH<:V:NtBLoqFP2H9:,0*2f", &why);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->fields[4], "15MrVH0000KH<:V:NtBLoqFP2H9:");

  // Without a checksum only when not required.
  EXPECT_FALSE(nmea::parse("$POLYN,EPH,0,00000000", &why));
  EXPECT_EQ(why, "no checksum");
  s = nmea::parse("$POLYN,EPH,0,00000000", &why, false);
  ASSERT_TRUE(s) << why;
  EXPECT_EQ(s->fields.size(), 3u);
}

TEST(NmeaParse, RejectsWithReason) {
  std::string why;
  EXPECT_FALSE(nmea::parse("$GPHDT,47.5,T*04", &why));
  EXPECT_EQ(why, "bad checksum: got 04, computed 03");
  EXPECT_FALSE(nmea::parse("$GPHDT,47.5,T*0", &why));
  EXPECT_EQ(why.rfind("bad checksum", 0), 0u) << why;
  EXPECT_FALSE(nmea::parse("!AIVDM,2,2,6,A,3OLc=UCRp,0*4A,b003660465", &why));  // trailing junk
  EXPECT_EQ(why.rfind("bad checksum", 0), 0u) << why;
  EXPECT_FALSE(nmea::parse("GPHDT,47.5,T*03", &why));
  EXPECT_EQ(why, "no '$' or '!'");
  EXPECT_FALSE(nmea::parse("", &why));
  EXPECT_EQ(why, "no '$' or '!'");
  EXPECT_FALSE(nmea::parse("# comment", &why));
  EXPECT_EQ(why, "no '$' or '!'");
  EXPECT_FALSE(nmea::parse("\\g:1-2-3*A!AIVDM", &why));
  EXPECT_EQ(why, "unterminated tag block");
  EXPECT_FALSE(nmea::parse(nmea::frame('$', "GPHDT,47.5\x01,T"), &why));
  EXPECT_EQ(why.rfind("non-printable character", 0), 0u) << why;
  // 82 characters (start, body of 78, '*', 2 hex digits) are accepted, 83 are not.
  EXPECT_TRUE(nmea::parse(nmea::frame('$', "GPTXT," + std::string(72, 'A')), &why)) << why;
  EXPECT_FALSE(nmea::parse(nmea::frame('$', "GPTXT," + std::string(73, 'A')), &why));
  EXPECT_EQ(why, "sentence longer than 82 characters (83)");
  EXPECT_FALSE(nmea::parse(nmea::frame('$', "GPHD,1,T"), &why));
  EXPECT_EQ(why, "address field 'GPHD' is not talker (2) + type (3)");
  EXPECT_FALSE(nmea::parse(nmea::frame('$', "GPHDTX,1,T"), &why));
  EXPECT_FALSE(nmea::parse(nmea::frame('$', "gphdt,1,T"), &why));
  EXPECT_FALSE(nmea::parse(nmea::frame('!', "P,1"), &why));
  EXPECT_FALSE(nmea::parse(nmea::frame('$', ",1"), &why));
  // why may be null.
  EXPECT_FALSE(nmea::parse("junk", nullptr));
}

// ---------------------------------------------------------------- real logs

TEST(NmeaLogs, SaabR4EveryLine) {
  const auto c = parse_log("nmea/gpsd/saab-r4.log");
  EXPECT_EQ(c.good, 122);  // every '$'/'!' line (python check of the checksums: 122 of 122)
  EXPECT_EQ(c.bad, 4);     // the 4 '#' header lines
  EXPECT_EQ(c.reasons.at("no '$' or '!'"), 4);
  // Every $HEHDT / $HEROT gives the value written in it.
  int hdt = 0, rot = 0;
  for (const auto& l : read_lines("nmea/gpsd/saab-r4.log")) {
    const double written = l.size() > 7 ? std::atof(l.c_str() + 7) : NAN;
    std::string why;
    if (l.rfind("$HEHDT,", 0) == 0) {
      const auto h = nmea::parse_hdt(must_parse(l), &why);
      ASSERT_TRUE(h) << l << ": " << why;
      EXPECT_DOUBLE_EQ(h->heading_deg, written) << l;
      ++hdt;
    } else if (l.rfind("$HEROT,", 0) == 0) {
      const auto r = nmea::parse_rot(must_parse(l), &why);
      ASSERT_TRUE(r) << l << ": " << why;
      EXPECT_DOUBLE_EQ(r->rot_deg_min, written) << l;
      ++rot;
    }
  }
  EXPECT_EQ(hdt, 12);
  EXPECT_EQ(rot, 12);
}

TEST(NmeaLogs, HemiEveryLine) {
  const auto c = parse_log("nmea/gpsd/hemi.log");
  EXPECT_EQ(c.good, 753);
  EXPECT_EQ(c.bad, 2);  // '#' lines
  // 4 $GPHDT carry a heading (gpsd gives 4 ATT); the other 211 are empty and must be refused.
  int with = 0, empty = 0;
  for (const auto& s : c.sentences) {
    if (s.type != "HDT") continue;
    std::string why;
    const auto h = nmea::parse_hdt(s, &why);
    if (h) {
      ++with;
      EXPECT_NEAR(h->heading_deg, 274.08, 0.05);
      EXPECT_DOUBLE_EQ(h->heading_deg, std::atof(s.fields[0].c_str()));
    } else {
      EXPECT_EQ(why, "HDT: empty heading");
      ++empty;
    }
  }
  EXPECT_EQ(with, 4);
  EXPECT_EQ(empty, 211);
}

TEST(NmeaLogs, Mtk3301EveryLine) {
  const auto c = parse_log("nmea/gpsd/mtk-3301.log");
  // 56 checksummed sentences of which 11 $PMTKCHN have 203 characters; 3 $POLYN have no checksum.
  EXPECT_EQ(c.good, 45);
  EXPECT_EQ(c.reasons.at("no checksum"), 3);
  EXPECT_EQ(c.reasons.at("sentence longer than 82 characters "), 11);
  EXPECT_EQ(c.reasons.at("no '$' or '!'"), 17);
  EXPECT_EQ(c.bad, 31);
  // Its last RMC as written: 52 deg 12.981832' N, 6 deg 53.104686' E.
  const nmea::Sentence* last = nullptr;
  for (const auto& s : c.sentences)
    if (s.type == "RMC") last = &s;
  ASSERT_NE(last, nullptr);
  EXPECT_NEAR(to_deg(last->fields[2], last->fields[3], 2), 52.0 + 12.981832 / 60, 1e-12);
  EXPECT_NEAR(to_deg(last->fields[4], last->fields[5], 3), 6.0 + 53.104686 / 60, 1e-12);
}

TEST(NmeaLogs, PyaisMixed) {
  const auto c = parse_log("nmea/pyais/mixed.txt");
  EXPECT_EQ(c.good, 19);
  // The $PGHP with a wrong checksum, and a tag-blocked AIVDM whose '*' is missing ("...,013").
  EXPECT_EQ(c.reasons.at("bad checksum"), 1);
  EXPECT_EQ(c.reasons.at("no checksum"), 1);
  EXPECT_EQ(c.reasons.at("no '$' or '!'"), 7);  // '#' comments, "foobar", "IamNotAnAisMessage1111"
  EXPECT_EQ(c.bad, 9);
  std::string why;
  EXPECT_FALSE(nmea::parse("$PGHP,1,2009,5,9,0,0,0,10,338,2,,1,09*17", &why));
  EXPECT_EQ(why, "bad checksum: got 17, computed 16");
  // Tag blocks: the 4 tag-blocked sentences with a checksum parse, !SAVDM included.
  int tagged = 0, savdm = 0;
  for (const auto& l : read_lines("nmea/pyais/mixed.txt")) {
    if (l.empty() || l[0] != '\\') continue;
    if (auto s = nmea::parse(l, &why)) {
      ++tagged;
      EXPECT_EQ(s->type, "VDM");
      savdm += s->talker == "SA";
    }
  }
  EXPECT_EQ(tagged, 4);
  EXPECT_EQ(savdm, 2);
}

TEST(NmeaLogs, PyaisNmeaDataSample) {
  const auto c = parse_log("nmea/pyais/nmea_data_sample.txt");
  EXPECT_EQ(c.lines, 898);
  EXPECT_EQ(c.good, 898);
  for (const auto& s : c.sentences) EXPECT_EQ(s.type, "VDM");
}

// ---------------------------------------------------------------- encoders and decoders

TEST(NmeaEncode, HeadingRotRoundTrip) {
  std::string why;
  for (double h : {0.0, 0.004, 47.5, 180.0, 274.07, 359.99, 359.996, 360.0, -90.0, 725.25}) {
    const std::string l = nmea::hdt("GP", h);
    const auto d = nmea::parse_hdt(must_parse(l), &why);
    ASSERT_TRUE(d) << l << why;
    const double want = std::fmod(std::fmod(h, 360.0) + 360.0, 360.0);
    EXPECT_NEAR(std::remainder(d->heading_deg - want, 360.0), 0.0, 0.005 + 1e-9) << l;
    EXPECT_GE(d->heading_deg, 0.0);
    EXPECT_LT(d->heading_deg, 360.0) << l;
  }
  EXPECT_EQ(nmea::hdt("GP", 47.5), "$GPHDT,47.50,T*33\r\n");
  EXPECT_EQ(nmea::hdt("GP", 359.996), nmea::frame('$', "GPHDT,0.00,T"));
  EXPECT_EQ(nmea::hdt("GP", NAN), nmea::frame('$', "GPHDT,,T"));
  EXPECT_FALSE(nmea::parse_hdt(must_parse(nmea::hdt("GP", NAN)), &why));
  EXPECT_EQ(why, "HDT: empty heading");

  const auto t = nmea::parse_ths(must_parse(nmea::ths("HE", 123.456)), &why);
  ASSERT_TRUE(t) << why;
  EXPECT_DOUBLE_EQ(t->heading_deg, 123.46);
  EXPECT_TRUE(nmea::parse_ths(must_parse(nmea::ths("HE", 10, 'S')), &why));
  EXPECT_FALSE(nmea::parse_ths(must_parse(nmea::ths("HE", 10, 'V')), &why));
  EXPECT_EQ(why, "THS: mode 'V' (invalid)");
  EXPECT_EQ(nmea::ths("HE", INFINITY), nmea::frame('$', "HETHS,,V"));

  for (double r : {0.0, 12.345, -5.0, -720.0, 0.001}) {
    const std::string l = nmea::rot("TI", r);
    const auto d = nmea::parse_rot(must_parse(l), &why);
    ASSERT_TRUE(d) << l << why;
    EXPECT_NEAR(d->rot_deg_min, r, 0.005 + 1e-9) << l;
  }
  EXPECT_EQ(nmea::rot("TI", -5), nmea::frame('$', "TIROT,-5.00,A"));
  EXPECT_EQ(nmea::rot("TI", -0.001), nmea::frame('$', "TIROT,0.00,A"));  // no "-0.00"
  EXPECT_FALSE(nmea::parse_rot(must_parse(nmea::rot("TI", 3, false)), &why));
  EXPECT_EQ(why, "ROT: status V (invalid)");
  EXPECT_EQ(nmea::rot("TI", NAN), nmea::frame('$', "TIROT,,V"));
  EXPECT_EQ(nmea::rot("TI", -1e300), nmea::frame('$', "TIROT,,V"));  // too large to print: not garbage
  EXPECT_EQ(nmea::hdt("GP", 1e300).substr(0, 7), "$GPHDT,");          // wrapped, still a number
  EXPECT_TRUE(nmea::parse_hdt(must_parse(nmea::hdt("GP", 1e300)), &why)) << why;
}

TEST(NmeaEncode, ActuatorRoundTrip) {
  std::string why;
  for (double a : {0.0, 35.0, -35.0, 12.345, -0.5}) {
    auto r = nmea::parse_ror(must_parse(nmea::ror("AG", a)), &why);
    ASSERT_TRUE(r) << why;
    EXPECT_NEAR(r->rudder_deg, a, 0.005 + 1e-9);
    r = nmea::parse_rsa(must_parse(nmea::rsa("RC", a)), &why);
    ASSERT_TRUE(r) << why;
    EXPECT_NEAR(r->rudder_deg, a, 0.005 + 1e-9);
  }
  EXPECT_EQ(nmea::ror("AG", -10.5), nmea::frame('$', "AGROR,-10.50,A,,V,C"));
  EXPECT_EQ(nmea::rsa("RC", 3), nmea::frame('$', "RCRSA,3.00,A,,V"));
  EXPECT_EQ(nmea::ror("AG", NAN), nmea::frame('$', "AGROR,,V,,V,C"));
  EXPECT_FALSE(nmea::parse_ror(must_parse(nmea::ror("AG", NAN)), &why));
  EXPECT_FALSE(nmea::parse_rsa(must_parse(nmea::rsa("RC", NAN)), &why));
  EXPECT_EQ(why, "RSA: starboard status V (invalid)");

  for (double v : {0.0, 120.0, -80.25, 1500.0}) {
    auto p = nmea::parse_prc(must_parse(nmea::prc("AG", v, 2)), &why);
    ASSERT_TRUE(p) << why;
    EXPECT_NEAR(p->rpm, v, 0.005 + 1e-9);
    EXPECT_EQ(p->shaft, 2);
    p = nmea::parse_rpm(must_parse(nmea::rpm("ER", v, 1, 'E')), &why);
    ASSERT_TRUE(p) << why;
    EXPECT_NEAR(p->rpm, v, 0.005 + 1e-9);
    EXPECT_EQ(p->shaft, 1);
  }
  EXPECT_EQ(nmea::prc("AG", 95, 1), nmea::frame('$', "AGPRC,,V,95.00,R,,V,B,1"));
  EXPECT_EQ(nmea::rpm("ER", -60), nmea::frame('$', "ERRPM,S,1,-60.00,,A"));
  EXPECT_EQ(nmea::prc("AG", NAN), nmea::frame('$', "AGPRC,,V,,V,,V,B,1"));
  EXPECT_FALSE(nmea::parse_prc(must_parse(nmea::prc("AG", NAN)), &why));
  EXPECT_EQ(why, "PRC: rpm mode V (invalid)");
  EXPECT_FALSE(nmea::parse_rpm(must_parse(nmea::rpm("ER", NAN)), &why));
  EXPECT_FALSE(nmea::parse_prc(must_parse("$AGPRC,50,A,40,P,,V,B,1*" + nmea::checksum("AGPRC,50,A,40,P,,V,B,1")), &why));
  EXPECT_EQ(why, "PRC: rpm mode 'P', expected R");
}

TEST(NmeaDecode, RejectsBadFields) {
  std::string why;
  auto one = [](const std::string& body) { return must_parse(nmea::frame('$', body)); };
  EXPECT_FALSE(nmea::parse_hdt(one("GPTHS,1,A"), &why));
  EXPECT_EQ(why, "not HDT: $GPTHS");
  EXPECT_FALSE(nmea::parse_hdt(one("GPHDT,abc,T"), &why));
  EXPECT_EQ(why, "HDT: heading 'abc' is not a number");
  for (const char* bad : {"nan", "inf", "1e3", "0x10", " 5", "5 ", "1.2.3", "-", ".", "+-1", "1,5"}) {
    EXPECT_FALSE(nmea::parse_rot(one(std::string("TIROT,") + bad + ",A"), &why)) << bad;
  }
  EXPECT_TRUE(nmea::parse_rot(one("TIROT,.5,A"), &why)) << why;
  EXPECT_TRUE(nmea::parse_rot(one("TIROT,+5.,A"), &why)) << why;
  EXPECT_FALSE(nmea::parse_hdt(one("GPHDT,400,T"), &why));
  EXPECT_FALSE(nmea::parse_hdt(one("GPHDT,10,M"), &why));
  EXPECT_EQ(why, "HDT: reference 'M', expected T");
  EXPECT_FALSE(nmea::parse_hdt(one("GPHDT,10"), &why));
  EXPECT_EQ(why, "HDT: no reference field");
  EXPECT_FALSE(nmea::parse_ths(one("HETHS,10,X"), &why));
  EXPECT_FALSE(nmea::parse_rpm(one("ERRPM,X,1,10,,A"), &why));
  EXPECT_FALSE(nmea::parse_rpm(one("ERRPM,S,one,10,,A"), &why));
  EXPECT_FALSE(nmea::parse_rpm(one("ERRPM,S,1,10,"), &why));
  EXPECT_FALSE(nmea::parse_rot(must_parse("!AIROT,1,A*" + nmea::checksum("AIROT,1,A")), &why));
}

TEST(NmeaEncode, GgaRmcVtgFields) {
  nmea::FixData f;
  f.utc_ns = 1733070645'123'456'789LL;  // 2024-12-01T16:30:45.123456789Z
  f.lat_deg = -33.856789123;
  f.lon_deg = -151.215123456;
  f.sog_kn = 12.345;
  f.cog_deg = -0.004;
  f.satellites = 7;
  f.hdop = 0.94;
  f.altitude_m = 21.26;
  std::string why;

  auto g = must_parse(nmea::gga("GP", f));
  EXPECT_EQ(g.type, "GGA");
  ASSERT_EQ(g.fields.size(), 14u);
  EXPECT_EQ(g.fields[0], "163045.12");
  EXPECT_NEAR(to_deg(g.fields[1], g.fields[2], 2), f.lat_deg, 1e-6 / 60 * 0.5 + 1e-12);
  EXPECT_NEAR(to_deg(g.fields[3], g.fields[4], 3), f.lon_deg, 1e-6 / 60 * 0.5 + 1e-12);
  EXPECT_EQ(g.fields[1].size(), 11u);  // ddmm.mmmmmm
  EXPECT_EQ(g.fields[3].size(), 12u);  // dddmm.mmmmmm
  EXPECT_EQ(g.fields[2], "S");
  EXPECT_EQ(g.fields[4], "W");
  EXPECT_EQ(g.fields[5], "1");
  EXPECT_EQ(g.fields[6], "07");
  EXPECT_EQ(g.fields[7], "0.9");
  EXPECT_EQ(g.fields[8], "21.3");
  EXPECT_EQ(g.fields[9], "M");

  auto r = must_parse(nmea::rmc("GN", f));
  EXPECT_EQ(r.talker, "GN");
  ASSERT_EQ(r.fields.size(), 12u);
  EXPECT_EQ(r.fields[0], "163045.12");
  EXPECT_EQ(r.fields[1], "A");
  EXPECT_EQ(r.fields[2], g.fields[1]);
  EXPECT_EQ(r.fields[4], g.fields[3]);
  EXPECT_EQ(r.fields[6], "12.35");  // 0.01 kn (12.345 is 12.3449999... in binary: either is fine)
  EXPECT_EQ(r.fields[7], "0.00");   // -0.004 deg wrapped and rounded: never 360.00
  EXPECT_EQ(r.fields[8], "011224");
  EXPECT_EQ(r.fields[11], "A");

  auto v = must_parse(nmea::vtg("GP", f));
  ASSERT_EQ(v.fields.size(), 9u);
  EXPECT_EQ(v.fields[0], "0.00");
  EXPECT_EQ(v.fields[1], "T");
  EXPECT_EQ(v.fields[4], r.fields[6]);
  EXPECT_EQ(v.fields[6], "22.86");  // 12.345 kn * 1.852
  EXPECT_EQ(v.fields[8], "A");

  // North/east, carry of 59.9999999' into the degrees, midnight and date.
  f.utc_ns = 1735689599'999'000'000LL;  // 2024-12-31T23:59:59.999 -> rounds to 2025-01-01 00:00:00.00
  f.lat_deg = 59.0 + 59.9999999 / 60;
  f.lon_deg = 10.0 + 59.9999999 / 60;
  f.cog_deg = 359.996;
  g = must_parse(nmea::gga("GP", f));
  EXPECT_EQ(g.fields[0], "000000.00");
  EXPECT_EQ(g.fields[1], "6000.000000");
  EXPECT_EQ(g.fields[2], "N");
  EXPECT_EQ(g.fields[3], "01100.000000");
  EXPECT_EQ(g.fields[4], "E");
  r = must_parse(nmea::rmc("GP", f));
  EXPECT_EQ(r.fields[0], "000000.00");
  EXPECT_EQ(r.fields[7], "0.00");
  EXPECT_EQ(r.fields[8], "010125");

  // Values on a grid round-trip to 1e-6 min.
  for (double lat : {-89.999, -45.5, -0.0001, 0.0, 0.0001, 33.3, 89.9999}) {
    for (double lon : {-179.9999, -100.0, -0.5, 0.0, 7.77, 179.9999}) {
      f.lat_deg = lat;
      f.lon_deg = lon;
      g = must_parse(nmea::gga("GP", f));
      EXPECT_NEAR(to_deg(g.fields[1], g.fields[2], 2), lat, 1e-8) << lat;
      EXPECT_NEAR(to_deg(g.fields[3], g.fields[4], 3), lon, 1e-8) << lon;
    }
  }
}

TEST(NmeaEncode, NonFiniteGivesEmptyFields) {
  nmea::FixData f;
  f.utc_ns = 1733070645'000'000'000LL;
  f.lat_deg = NAN;
  f.lon_deg = 10.0;
  f.sog_kn = INFINITY;
  f.cog_deg = NAN;
  f.hdop = NAN;
  f.altitude_m = NAN;
  const auto g = must_parse(nmea::gga("GP", f));
  EXPECT_EQ(nmea::gga("GP", f), nmea::frame('$', "GPGGA,163045.00,,,,,0,10,,,M,0.0,M,,"));
  EXPECT_EQ(g.fields[5], "0");
  EXPECT_EQ(nmea::rmc("GP", f), nmea::frame('$', "GPRMC,163045.00,V,,,,,,,011224,,,N"));
  EXPECT_EQ(nmea::vtg("GP", f), nmea::frame('$', "GPVTG,,T,,M,,N,,K,N"));
  f.lat_deg = 95.0;  // out of range: not a position either
  EXPECT_EQ(must_parse(nmea::gga("GP", f)).fields[1], "");
  f.lat_deg = 10.0;
  f.quality = 0;  // valid numbers but no fix: RMC status V
  EXPECT_EQ(must_parse(nmea::rmc("GP", f)).fields[1], "V");
  EXPECT_EQ(must_parse(nmea::gga("GP", f)).fields[5], "0");
}

// ---------------------------------------------------------------- AIS

TEST(AisEncode, RealType1ByteForByte) {
  // gpsd sample.aivdm / sample.aivdm.js.chk: mmsi 371798000, status 0, turn -127 ("fastleft"),
  // 12.3 kn, accuracy, -123.395383 / 48.381633 (lon -74037230, lat 29028980 in 1/600000 deg),
  // course 224.0, heading 215, second 33, radio 34017.
  ais::PositionReport m;
  m.type = 1;
  m.mmsi = 371798000;
  m.nav_status = 0;
  m.rot_deg_min = -INFINITY;
  m.sog_kn = 12.3;
  m.accuracy = true;
  m.lon_deg = -74037230 / 600000.0;
  m.lat_deg = 29028980 / 600000.0;
  m.cog_deg = 224.0;
  m.heading_deg = 215;
  m.second = 33;
  m.radio = 34017;
  const auto out = ais::sentences(ais::encode(m));
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], "!AIVDM,1,1,,A,15RTgt0PAso;90TKcjM8h6g208CQ,0*4A\r\n");
  // The decoded degrees of the .chk (6 decimals) give the same units.
  m.lon_deg = -123.395383;
  m.lat_deg = 48.381633;
  EXPECT_EQ(ais::sentences(ais::encode(m))[0], out[0]);
  // Own ship: !AIVDO, channel B.
  EXPECT_EQ(strip_crlf(ais::sentences(ais::encode(m), 'B', 0, true)[0]).substr(0, 15), "!AIVDO,1,1,,B,1");
}

TEST(AisEncode, Type1FieldsByLocalDecoder) {
  ais::PositionReport m;
  m.type = 3;
  m.mmsi = 257123450;
  m.nav_status = 5;
  m.rot_deg_min = 20.0;  // 4.733 sqrt(20) = 21.17 -> 21
  m.sog_kn = 17.26;
  m.lon_deg = -70.7582;
  m.lat_deg = -43.08015;
  m.cog_deg = 359.97;  // rounds to 360.0 -> 0
  m.heading_deg = -0.4;
  m.second = 59;
  m.maneuver = 2;
  m.raim = true;
  m.radio = 0x7FFFF;
  const auto d = decode1(bits_of(ais::sentences(ais::encode(m))));
  EXPECT_EQ(d.type, 3u);
  EXPECT_EQ(d.repeat, 0u);
  EXPECT_EQ(d.mmsi, 257123450u);
  EXPECT_EQ(d.status, 5u);
  EXPECT_EQ(d.rot, 21);
  EXPECT_EQ(d.sog, 173u);
  EXPECT_EQ(d.acc, 0u);
  EXPECT_EQ(d.lon, -42454920);
  EXPECT_EQ(d.lat, -25848090);
  EXPECT_EQ(d.cog, 0u);
  EXPECT_EQ(d.hdg, 0u);
  EXPECT_EQ(d.second, 59u);
  EXPECT_EQ(d.maneuver, 2u);
  EXPECT_EQ(d.spare, 0u);
  EXPECT_EQ(d.raim, 1u);
  EXPECT_EQ(d.radio, 0x7FFFFu);

  // Payload size and fill: 168 bits = 28 characters, fill 0.
  int fill = -1;
  EXPECT_EQ(ais::encode(m).bits(), 168);
  EXPECT_EQ(ais::encode(m).armoured(&fill).size(), 28u);
  EXPECT_EQ(fill, 0);
}

TEST(AisEncode, NotAvailableValues) {
  ais::PositionReport m;  // defaults: everything n/a
  m.mmsi = 1;
  auto d = decode1(bits_of(ais::sentences(ais::encode(m))));
  EXPECT_EQ(d.rot, -128);
  EXPECT_EQ(d.sog, 1023u);
  EXPECT_EQ(d.lon, 181 * 600000);
  EXPECT_EQ(d.lat, 91 * 600000);
  EXPECT_EQ(d.cog, 3600u);
  EXPECT_EQ(d.hdg, 511u);
  EXPECT_EQ(d.second, 60u);
  EXPECT_EQ(d.status, 15u);
  // Out of range: treated as n/a, or saturated where the standard has a ceiling.
  m.lat_deg = 95;
  m.lon_deg = -200;
  m.sog_kn = 150;
  m.second = 99;
  m.nav_status = 42;
  m.type = 7;
  d = decode1(bits_of(ais::sentences(ais::encode(m))));
  EXPECT_EQ(d.type, 1u);
  EXPECT_EQ(d.lat, 91 * 600000);
  EXPECT_EQ(d.lon, 181 * 600000);
  EXPECT_EQ(d.sog, 1022u);
  EXPECT_EQ(d.second, 60u);
  EXPECT_EQ(d.status, 15u);
  m.sog_kn = -1;
  EXPECT_EQ(decode1(bits_of(ais::sentences(ais::encode(m)))).sog, 1023u);
}

TEST(AisEncode, RotAisMapping) {
  auto rot_of = [](double r) {
    ais::PositionReport m;
    m.rot_deg_min = r;
    return decode1(bits_of(ais::sentences(ais::encode(m)))).rot;
  };
  EXPECT_EQ(rot_of(0.0), 0);
  EXPECT_EQ(rot_of(720.0), 126);  // 4.733 sqrt(720) = 127.0 -> saturated
  EXPECT_EQ(rot_of(-720.0), -126);
  EXPECT_EQ(rot_of(1e6), 126);
  EXPECT_EQ(rot_of(-1e300), -126);
  EXPECT_EQ(rot_of(-5.0), -11);  // 4.733 sqrt(5) = 10.58
  EXPECT_EQ(rot_of(5.0), 11);
  EXPECT_EQ(rot_of(1.0), 5);     // 4.733
  EXPECT_EQ(rot_of(0.01), 0);    // 0.47
  EXPECT_EQ(rot_of(NAN), -128);
  EXPECT_EQ(rot_of(INFINITY), 127);
  EXPECT_EQ(rot_of(-INFINITY), -127);
  // The inverse gpsd documents (rate = sign (turn/4.733)^2) stays within half a step.
  for (double r = -700; r <= 700; r += 13.7) {
    const int t = rot_of(r);
    EXPECT_NEAR(std::copysign(std::sqrt(std::fabs(r)) * 4.733, r), t, 0.5 + 1e-9) << r;
  }
}

TEST(AisEncode, RealType5FromSample) {
  // sample.aivdm: HEALTH CONTROL 13 (mmsi 271010059), 424 bits, ETA n/a, AIS version 0, EPFD GPS,
  // DTE 0: the whole payload is reproduced bit for bit. The name was sent space-padded, the
  // destination '@'-padded (empty).
  const std::string real1 = "542M92h00001@<7;?G0PD4i@R0<tqA8tj37>220o0h:2240Ht50000000000";
  const std::string real2 = "00000000000";
  // mmsi, imo, callsign, name, ship type, to bow/stern/port/starboard [m], draught [m], destination
  const ais::StaticVoyage v{271010059, 0, "TCA2350", "HEALTH CONTROL 13   ", 55, 6, 10, 2, 2, 2.0, ""};
  const auto p = ais::encode(v);
  EXPECT_EQ(p.bits(), 424);
  int fill = -1;
  EXPECT_EQ(p.armoured(&fill), real1 + real2);
  EXPECT_EQ(fill, 2);
  // As the receiver framed it on channel B with sequential id 6 (60 + 11 characters).
  const auto out = ais::sentences(p, 'B', 6);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0], "!AIVDM,2,1,6,B," + real1 + ",0*3B\r\n");
  EXPECT_EQ(out[1], "!AIVDM,2,2,6,B," + real2 + ",2*21\r\n");

  // EVER DIADEM (mmsi 351759000) carries an ETA (05-15T14:00Z) the struct does not: every other
  // field compared through the local decoder against the real payload's.
  const auto real = decode5(bits_of({"!AIVDM,2,1,1,A,55?MbV02;H;s<HtKR20EHE:0@T4@Dn2222222216L961O5Gf0NSQEp6ClRp8,0*1C",
                                     "!AIVDM,2,2,1,A,88888888880,2*25"}));
  const ais::StaticVoyage e{351759000, 9134270, "3FOF8", "EVER DIADEM", 70, 225, 70, 1, 31, 12.2, "NEW YORK"};
  const auto ours_s = ais::sentences(ais::encode(e), 'A', 1);
  ASSERT_EQ(ours_s.size(), 2u);
  const auto ours = decode5(bits_of(ours_s));
  EXPECT_EQ(ours.type, real.type);
  EXPECT_EQ(ours.mmsi, real.mmsi);
  EXPECT_EQ(ours.version, real.version);
  EXPECT_EQ(ours.imo, real.imo);
  EXPECT_EQ(real.callsign, "3FOF8  ");  // real: space-padded; ours '@'-padded, same once trimmed
  EXPECT_EQ(ours.callsign, "3FOF8@@");
  EXPECT_EQ(real.name, "EVER DIADEM         ");
  EXPECT_EQ(ours.name, "EVER DIADEM@@@@@@@@@");
  EXPECT_EQ(ours.ship_type, real.ship_type);
  EXPECT_EQ(ours.bow, real.bow);
  EXPECT_EQ(ours.stern, real.stern);
  EXPECT_EQ(ours.port, real.port);
  EXPECT_EQ(ours.stbd, real.stbd);
  EXPECT_EQ(ours.epfd, real.epfd);
  EXPECT_EQ(ours.draught, real.draught);
  EXPECT_EQ(real.destination, "NEW YORK            ");
  EXPECT_EQ(ours.destination, "NEW YORK@@@@@@@@@@@@");
  EXPECT_EQ(ours.dte, real.dte);
  EXPECT_EQ(ours.spare, real.spare);
  EXPECT_EQ(real.month * 100 + real.day, 515u);
  EXPECT_EQ(ours.month, 0u);  // ETA n/a: month 0, day 0, hour 24, minute 60
  EXPECT_EQ(ours.day, 0u);
  EXPECT_EQ(ours.hour, 24u);
  EXPECT_EQ(ours.minute, 60u);
  // Same framing as the real one: 60 characters fill 0, then 11 characters fill 2.
  EXPECT_EQ(strip_crlf(ours_s[0]).size(), strip_crlf("!AIVDM,2,1,1,A,55?MbV02;H;s<HtKR20EHE:0@T4@Dn2222222216L961O5Gf0NSQEp6ClRp8,0*1C").size());
  EXPECT_EQ(ours_s[1].substr(0, 15), "!AIVDM,2,2,1,A,");
  EXPECT_EQ(strip_crlf(ours_s[1]).substr(26), ",2*" + nmea::checksum(strip_crlf(ours_s[1]).substr(1, 27)));
}

TEST(AisEncode, TextAndSaturation) {
  ais::StaticVoyage v;
  v.callsign = "ab-1 ?";              // lower case goes upper; '-', ' ', '?' are in the alphabet
  v.name = "NAME~WITH{BAD}_TOO_LONG_FOR_20";  // outside the alphabet -> '?', cut at 20
  v.to_bow = 600;
  v.to_stern = -3;
  v.to_port = 70;
  v.draught_m = 40;
  v.ship_type = 300;
  const auto d = decode5(bits_of(ais::sentences(ais::encode(v))));
  EXPECT_EQ(d.callsign, "AB-1 ?@");
  EXPECT_EQ(d.name, "NAME?WITH?BAD?_TOO_L");
  EXPECT_EQ(d.bow, 511u);
  EXPECT_EQ(d.stern, 0u);
  EXPECT_EQ(d.port, 63u);
  EXPECT_EQ(d.draught, 255u);
  EXPECT_EQ(d.ship_type, 255u);
  v.draught_m = 1e300;
  EXPECT_EQ(decode5(bits_of(ais::sentences(ais::encode(v)))).draught, 255u);
  v.draught_m = NAN;
  EXPECT_EQ(decode5(bits_of(ais::sentences(ais::encode(v)))).draught, 0u);
}

TEST(AisEncode, Fragmenting) {
  // A payload of 61..120 characters gives 2 fragments, 121..180 gives 3; fill only in the last.
  for (int bits : {6, 354, 360, 366, 424, 720, 721, 1000}) {
    ais::Payload p;
    for (int i = 0; i < bits; ++i) p.put_uint(static_cast<uint32_t>(i * 7 % 2), 1);
    int fill = -1;
    const std::string all = p.armoured(&fill);
    EXPECT_EQ(static_cast<int>(all.size()) * 6 - fill, bits);
    const auto out = ais::sentences(p, 'B', 13);
    const size_t n = (all.size() + 59) / 60;
    ASSERT_EQ(out.size(), n) << bits;
    std::string joined;
    for (size_t k = 0; k < n; ++k) {
      const auto s = must_parse(out[k]);
      ASSERT_EQ(s.fields.size(), 6u);
      EXPECT_EQ(s.fields[0], std::to_string(n));
      EXPECT_EQ(s.fields[1], std::to_string(k + 1));
      EXPECT_EQ(s.fields[2], n > 1 ? "3" : "");  // 13 -> 3: one digit
      EXPECT_EQ(s.fields[3], "B");
      EXPECT_LE(s.fields[4].size(), 60u);
      EXPECT_EQ(s.fields[5], k + 1 == n ? std::to_string(fill) : "0");
      EXPECT_LE(strip_crlf(out[k]).size(), 80u);  // inside IEC 61162-1's 82 with CR LF
      joined += s.fields[4];
    }
    EXPECT_EQ(joined, all);
  }
  // put_int: two's complement in the low bits.
  ais::Payload p;
  p.put_int(-1, 6);
  p.put_int(5, 6);
  int fill = -1;
  EXPECT_EQ(p.armoured(&fill), "w5");  // 63 -> 'w', 5 -> '5'
  EXPECT_EQ(fill, 0);
}
