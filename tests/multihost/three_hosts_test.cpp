// The closed loop across a ship's network: deploy/hosts/three-hosts.yaml as network namespaces
// made by `mpgc_run --hosts` (ship: simulator; autonomy: awareness, obstacles, planner; bridge-pc:
// guidance & control and the evaluator). Needs root, as CI has.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "mpgc/testing.hpp"

namespace fs = std::filesystem;

namespace {

// A short DNV crossing (give way, about 1800 s simulated, 30 s in lockstep).
std::string scenario() {
  return mpgc::testing::shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_02.json");
}
std::string deployment() { return mpgc::testing::source_dir() + "/deploy/hosts/three-hosts.yaml"; }

mpgc::testing::CommandResult run(const std::string& args) {
  return mpgc::testing::shell(mpgc::testing::bin_dir() + "/mpgc_run " + args);
}

std::string slurp(const fs::path& p) { return mpgc::testing::read_file(p.string()); }

std::string out_dir(const std::string& tag) {
  const fs::path d = fs::path(::testing::TempDir()) / ("mpgc_three_hosts_" + tag + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  return d.string();
}

bool in_subnet(const std::string& addr) {  // 10.231.78.0/24, the deployment's subnet
  in_addr a{};
  return inet_pton(AF_INET, addr.c_str(), &a) == 1 && (ntohl(a.s_addr) & 0xffffff00u) == 0x0ae74e00u;
}

// The run's namespaces are gone once it has ended (its pid is in their names: none of a dead pid).
void expect_no_lab_left() {
  if (!fs::is_directory("/run/netns")) return;
  for (const auto& e : fs::directory_iterator("/run/netns")) {
    const std::string n = e.path().filename().string();
    std::smatch m;
    static const std::regex re("^mpgc([0-9]+)-");
    if (!std::regex_search(n, m, re)) continue;
    EXPECT_TRUE(fs::exists("/proc/" + m[1].str())) << "namespace left behind: " << n;
  }
}

}  // namespace

TEST(ThreeHosts, LockstepLoopIsTheSingleHostLoopBitForBitAndNoPacketLeavesTheLinks) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces need root (CI runs as root)";
  const std::string single = out_dir("single"), multi = out_dir("multi");
  const auto a = run(scenario() + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --out " + single);
  ASSERT_EQ(a.code, 0) << a.output;
  const auto b = run(scenario() + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --hosts " + deployment() + " --capture --out " + multi);
  ASSERT_EQ(b.code, 0) << b.output;
  const std::string ts1 = slurp(fs::path(single) / "dnv_02_CR-GW" / "timeseries.csv");
  const std::string ts3 = slurp(fs::path(multi) / "dnv_02_CR-GW" / "timeseries.csv");
  ASSERT_GT(ts1.size(), 1000u);
  EXPECT_TRUE(ts1 == ts3) << "timeseries.csv differs between one host and three hosts";

  // Every packet any host's namespace saw (its interface and its loopback) is ARP or IPv4 between
  // addresses of the deployment's subnet: nothing was sent anywhere else.
  const fs::path net = fs::path(multi) / "dnv_02_CR-GW" / "network";
  for (const char* h : {"ship", "autonomy", "bridge-pc"}) {
    const std::string pcap = (net / (std::string(h) + ".pcap")).string();
    ASSERT_TRUE(fs::exists(pcap)) << pcap;
    FILE* p = popen(("tcpdump -n -r " + pcap + " 2>/dev/null").c_str(), "r");
    ASSERT_NE(p, nullptr);
    char line[2048];
    long ip = 0, arp = 0, other = 0;
    std::string first_other;
    static const std::regex ipv4(R"( IP (\d+\.\d+\.\d+\.\d+)(\.\d+)? > (\d+\.\d+\.\d+\.\d+)(\.\d+)?:)");
    while (fgets(line, sizeof line, p) != nullptr) {
      const std::string l(line);
      std::smatch m;
      if (std::regex_search(l, m, ipv4) && in_subnet(m[1].str()) && in_subnet(m[3].str())) ++ip;
      else if (l.find(" ARP, ") != std::string::npos && l.find("10.231.78.") != std::string::npos) ++arp;
      else if (other++ == 0) first_other = l;
    }
    pclose(p);
    EXPECT_GT(ip, 1000) << h << ": the host exchanged too little over its link";
    EXPECT_EQ(other, 0) << h << ": " << other << " packets outside the deployment's subnet, first: " << first_other;
  }
  expect_no_lab_left();
}

// A bad network at a real-time factor (lockstep would wait out every delay): 20 % loss and 50 ms
// on every host's egress (1 s simulated at 20x), and the autonomy host cut off for 5 s (100 s
// simulated) during the encounter. The run's own criteria (goal, no collision, d_safety, COLREG)
// must hold, and the cut and netem's counts must be in its output.
TEST(ThreeHosts, LossyDelayedLinkAndACutStillPassTheScenario) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces need root (CI runs as root)";
  const std::string dir = out_dir("lossy");
  const auto r = run(scenario() + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --hosts " + deployment() +
                       " --link 'loss 20% delay 50ms' --link-seed 7 --cut autonomy@500+5 --realtime-factor 20 --out " + dir);
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("network: cut autonomy at sim"), std::string::npos) << r.output;
  const std::string nj = slurp(fs::path(dir) / "dnv_02_CR-GW" / "network.json");
  const auto j = nlohmann::json::parse(nj);
  EXPECT_EQ(j.at("links"), nlohmann::json({{"autonomy", "loss 20% delay 50ms"},
                                           {"bridge-pc", "loss 20% delay 50ms"},
                                           {"ship", "loss 20% delay 50ms"}}))
      << nj;
  ASSERT_EQ(j.at("cuts").size(), 1u) << nj;
  EXPECT_EQ(j["cuts"][0].at("happened"), true) << nj;
  // netem's summary per host: "netem: queue 0 passed P dropped L (x.x%) ..." — loss near 20 %.
  static const std::regex summary(R"(passed (\d+) dropped (\d+))");
  int hosts = 0;
  for (std::sregex_iterator it(nj.begin(), nj.end(), summary), end; it != end; ++it) {
    const double passed = std::stod((*it)[1].str()), dropped = std::stod((*it)[2].str());
    ASSERT_GT(passed + dropped, 500) << nj;
    const double loss = dropped / (passed + dropped);
    EXPECT_GT(loss, 0.15) << nj;
    EXPECT_LT(loss, 0.25) << nj;
    ++hosts;
  }
  EXPECT_EQ(hosts, 3) << "netem summaries of the three hosts: " << nj;
  // The hosts' sim clocks lag each other over the link: no component may drop a target for that
  // (stop 27: obstacle_manager refused the crossing target for negative since_update and the
  // planner saw an empty sea; situational_awareness refused scans from "the future").
  const std::string log = slurp(fs::path(dir) / "dnv_02_CR-GW" / "components.log");
  for (const char* bad : {"rejected input on sa/tracks", "future_stamp"}) {
    const auto at = log.find(bad);
    EXPECT_EQ(at, std::string::npos) << bad << ": " << log.substr(at == std::string::npos ? 0 : at, 300);
  }
  expect_no_lab_left();
}
