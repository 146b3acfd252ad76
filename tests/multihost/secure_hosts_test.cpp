// The secured closed loop on three hosts (deploy/hosts/three-hosts.yaml as network namespaces,
// DDS Security from deploy/security/make-pki.sh), with intruders on the ship's network while it
// runs: one without a certificate, one with a valid certificate beyond its grant, one with a
// certificate of another CA. The ship must sail exactly the single-host run (lockstep, bit for
// bit): no injected rudder order ever reached it. Needs root, as CI has.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "mpgc/testing.hpp"

namespace fs = std::filesystem;

namespace {

std::string capture(const std::string& cmd, int* code = nullptr) {
  const auto r = mpgc::testing::shell(cmd);
  if (code) *code = r.code;
  return r.output;
}

std::string slurp(const fs::path& p) { return mpgc::testing::read_file(p.string()); }

}  // namespace

TEST(SecureHosts, SecuredThreeHostLoopIsTheOpenLoopAndIntrudersGetNothingIn) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces need root (CI runs as root)";
  const fs::path tmp = fs::path(::testing::TempDir()) / ("mpgc_secure_hosts_" + std::to_string(getpid()));
  fs::remove_all(tmp);
  const std::string src = mpgc::testing::source_dir(), bin = mpgc::testing::bin_dir();
  int rc = 0;
  const std::string pki = (tmp / "pki").string(), rogue = (tmp / "rogue-pki").string();
  std::string out = capture(src + "/deploy/security/make-pki.sh " + pki, &rc);
  ASSERT_EQ(rc, 0) << out;
  out = capture(src + "/deploy/security/make-pki.sh " + rogue + " --ca-name 'rogue CA'", &rc);
  ASSERT_EQ(rc, 0) << out;

  const std::string scenario =
      mpgc::testing::shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_02.json");
  const std::string single = (tmp / "single").string(), secured = (tmp / "secured").string();
  out = capture(bin + "/mpgc_run " + scenario + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --out " + single, &rc);
  ASSERT_EQ(rc, 0) << out;

  const int domain = mpgc::testing::unique_domain();
  auto run = std::async(std::launch::async, [&] {
    int code = 0;
    std::string o = capture(bin + "/mpgc_run " + scenario + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --hosts " + src + "/deploy/hosts/three-hosts.yaml --secure " +
                                pki + " --domain " + std::to_string(domain) + " --out " + secured,
                            &code);
    return std::make_pair(code, o);
  });
  // The run's hosts exist once their Cyclone configurations are written and the namespaces made.
  const fs::path net = fs::path(secured) / "dnv_02_CR-GW" / "network";
  std::string ns_prefix;
  for (int i = 0; i < 200 && ns_prefix.empty(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (!fs::exists(net / "bridge-pc" / "cyclonedds.xml") || !fs::is_directory("/run/netns")) continue;
    for (const auto& e : fs::directory_iterator("/run/netns")) {
      const std::string n = e.path().filename().string();
      if (n.rfind("mpgc", 0) == 0 && n.size() > 5 && n.substr(n.size() - 5) == "-ship" &&
          fs::exists("/run/netns/" + n.substr(0, n.size() - 5) + "-autonomy") && fs::last_write_time(e.path()) >
          fs::last_write_time(fs::path(single) / "dnv_02_CR-GW" / "timeseries.csv"))
        ns_prefix = n.substr(0, n.size() - 4);
    }
  }
  ASSERT_FALSE(ns_prefix.empty()) << "the secured run's namespaces did not appear";
  std::this_thread::sleep_for(std::chrono::seconds(2));  // the components are up and matched
  // An intruder on a host of the run: identity and PKI folder empty = no security at all.
  auto intruder = [&](const std::string& host, const std::string& identity, const std::string& pki_dir) {
    std::string uri = "file://" + (net / host / "cyclonedds.xml").string();
    if (!pki_dir.empty()) uri += ",file://" + pki_dir + "/security.xml";
    return capture("ip netns exec " + ns_prefix + host + " env MPGC_SECURITY_ID=" + identity + " CYCLONEDDS_URI=" + uri +
                   " " + bin + "/mpgc_test_intruder --domain " + std::to_string(domain) +
                   " --seconds 6 --subscribe nav/own_state --publish control/actuators --rudder-deg 35");
  };
  // No certificate, on the ship's own host: reads nothing, its hard-over orders match no reader.
  auto open_one = std::async(std::launch::async, [&] { return intruder("ship", "", ""); });
  // opp's valid certificate: may read nav/own_state, may not write control/actuators.
  auto beyond_grant = std::async(std::launch::async, [&] { return intruder("autonomy", "opp", pki); });
  // guidance_control's name and grant, signed by another CA.
  auto foreign = std::async(std::launch::async, [&] { return intruder("bridge-pc", "guidance_control", rogue); });
  const std::string o1 = open_one.get(), o2 = beyond_grant.get(), o3 = foreign.get();
  const auto [code, run_out] = run.get();

  EXPECT_NE(o1.find("received nav/own_state: 0\n"), std::string::npos) << o1;
  EXPECT_NE(o1.find("matched control/actuators: 0\n"), std::string::npos) << o1;
  // No rule of opp's names control/actuators, so the topic itself is refused, before any writer.
  EXPECT_TRUE(o2.find("topic control/actuators: -13 NOT_ALLOWED_BY_SECURITY") != std::string::npos ||
              o2.find("writer control/actuators: -13 NOT_ALLOWED_BY_SECURITY") != std::string::npos)
      << o2;
  EXPECT_NE(o2.find("written control/actuators: 0\n"), std::string::npos) << o2;
  EXPECT_EQ(o2.find("received nav/own_state: 0\n"), std::string::npos) << "opp's identity should read the state: " << o2;
  EXPECT_EQ(o3.find("received nav/own_state: 0\n") != std::string::npos ||
                o3.find("participant: -1") != std::string::npos,
            true)
      << o3;
  EXPECT_EQ(o3.find("matched control/actuators: 1"), std::string::npos) << o3;

  ASSERT_EQ(code, 0) << run_out;
  const std::string a = slurp(fs::path(single) / "dnv_02_CR-GW" / "timeseries.csv");
  const std::string b = slurp(fs::path(secured) / "dnv_02_CR-GW" / "timeseries.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the secured three-host run differs from the open single-host run";
  EXPECT_EQ(nlohmann::json::parse(slurp(fs::path(secured) / "dnv_02_CR-GW" / "network.json")).at("secure"), true);
}
