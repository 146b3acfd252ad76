// mpgc_classify (./mpgc classify): per-target lines and the closing JSON agreement line, with the
// DNV sector angles and with seed 000's; a malformed file is an error that leaves the others counted.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <tuple>
#include <utility>

#include <nlohmann/json.hpp>

#include "mpgc/testing.hpp"

using mpgc::testing::shared_data;

namespace {
std::string situation_path(const std::string& nn) {
  return shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_" + nn + ".json");
}
std::pair<int, std::string> run(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>/dev/null").c_str(), "r");
  if (!p) return {-1, ""};
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int rc = pclose(p);
  return {WEXITSTATUS(rc), out};
}
std::string last_line(const std::string& s) {
  const auto e = s.find_last_not_of('\n');
  const auto b = s.rfind('\n', e);
  return s.substr(b == std::string::npos ? 0 : b + 1, e - (b == std::string::npos ? 0 : b + 1) + 1);
}
// The closing JSON line {"agree": N, "total": M} as (N, M); it must be that object and no more.
std::pair<int, int> agreement(const std::string& out) {
  const auto j = nlohmann::json::parse(last_line(out));
  EXPECT_EQ(j.size(), 2u) << j;
  return {j.at("agree").get<int>(), j.at("total").get<int>()};
}
}  // namespace

TEST(ClassifyTool, PrintsTargetsAndAgreementLine) {
  const std::string exe = mpgc::testing::bin_dir() + "/mpgc_classify";
  const std::string files = situation_path("01") + " " + situation_path("11") + " " + situation_path("55");
  auto [rc, out] = run(exe + " --settings " + shared_data("encounters/dnv/encounter_settings.json") + " " + files);
  EXPECT_EQ(rc, 0);
  EXPECT_EQ(agreement(out), std::make_pair(6, 6)) << out;
  EXPECT_NE(out.find("desired head-on [agree]"), std::string::npos);
  EXPECT_NE(out.find("CPA "), std::string::npos);
  // Seed 000 sectors: situation 11's first target is a fine crossing, head-on for head_on_sector = 22.5.
  std::tie(rc, out) = run(exe + " " + files);
  EXPECT_EQ(agreement(out), std::make_pair(5, 6)) << out;
  // A malformed file: error on stderr, exit 1, the others still counted.
  const std::string bad = ::testing::TempDir() + "sa_tool_bad.json";
  std::ofstream(bad) << "{";
  std::tie(rc, out) = run(exe + " " + bad + " " + situation_path("01"));
  EXPECT_EQ(rc, 1);
  EXPECT_EQ(agreement(out), std::make_pair(1, 1)) << out;
}

// --escape: which starts allow a safe CPA at all (issue 18). Situation 42 starts with its
// overtaking ship 1290 m off, inside 0.7 NM (1296.4 m): no manoeuvre keeps it; 21's three
// head-on ships are 9.8 km and more away.
TEST(ClassifyTool, EscapeSaysWhichStartsAllowTheSafeCpa) {
  const std::string exe = mpgc::testing::bin_dir() + "/mpgc_classify";
  auto [rc, out] = run(exe + " --escape 0.7 --turn-radius 134 --escape-speeds 1,0.5 " + situation_path("21") + " " +
                       situation_path("42"));
  EXPECT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("\"HO, HO, HO\" escape: "), std::string::npos) << out;
  EXPECT_NE(out.find("allows 0.70 NM"), std::string::npos) << out;
  EXPECT_NE(out.find("(target 3): does not allow 0.70 NM"), std::string::npos) << out;
  EXPECT_NE(out.find("\"escape_allows\":1,\"escape_total\":2"), std::string::npos) << out;
  // 25's overtaking ship comes up on the starboard quarter: only a turn to port keeps 0.7 NM.
  std::tie(rc, out) = run(exe + " --escape 0.7 --turn-radius 134 " + situation_path("25"));
  EXPECT_NE(out.find("to port at 100 % speed"), std::string::npos) << out;
  EXPECT_NE(out.find(": allows 0.70 NM"), std::string::npos) << out;
  std::tie(rc, out) = run(exe + " --escape 0.7 --turn-radius 134 --escape-starboard " + situation_path("25"));
  EXPECT_NE(out.find(": does not allow 0.70 NM"), std::string::npos) << out;
  std::tie(rc, out) = run(exe + " --escape 0.7 --escape-speeds 1,fast " + situation_path("21"));
  EXPECT_NE(rc, 0);  // CLI11 refuses it before any file is read (its message, on stderr, names 'fast')
  EXPECT_EQ(out.find("escape:"), std::string::npos) << out;
}
