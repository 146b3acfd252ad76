// The deployment description (deploy/hosts/*.yaml) and what is generated from it, without a network.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "deployment.hpp"
#include "launch_file.hpp"
#include "mpgc/testing.hpp"

namespace dp = mpgc::deploy;
namespace fs = std::filesystem;

namespace {

const char* kGood = R"(name: t
network: {subnet: 10.9.8.0/24, spdp_interval: 0.5, link: "loss 5% delay 20ms"}
hosts:
  - {name: a, address: 10.9.8.1, components: [ship_simulator]}
  - {name: b, address: 10.9.8.2, interface: ens3, components: [opp, scenario_runner]}
)";

std::string error_of(const std::string& yaml) {
  try {
    dp::parse(yaml, "x.yaml");
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

std::string with_hosts(const std::string& hosts) { return "network: {subnet: 10.9.8.0/24}\nhosts:\n" + hosts; }

}  // namespace

TEST(Deployment, ParsesHostsNetworkAndPlacement) {
  const dp::Deployment d = dp::parse(kGood, "x.yaml");
  ASSERT_EQ(d.hosts.size(), 2u);
  EXPECT_EQ(d.prefix, 24);
  EXPECT_DOUBLE_EQ(d.spdp_interval_s, 0.5);
  EXPECT_DOUBLE_EQ(d.link.loss_pct, 5.0);
  EXPECT_DOUBLE_EQ(d.link.delay_ms, 20.0);
  EXPECT_EQ(d.hosts[0].interface, "eth0");  // the default
  EXPECT_EQ(d.hosts[1].interface, "ens3");
  ASSERT_NE(d.host_of("opp"), nullptr);
  EXPECT_EQ(d.host_of("opp")->name, "b");
  EXPECT_EQ(d.host_of("guidance_control"), nullptr);
}

TEST(Deployment, RejectsWithFileLineAndReason) {
  EXPECT_NE(error_of("network: {subnet: 10.9.8.0/33}\nhosts: [{name: a, address: 10.9.8.1, components: []}]").find("prefix"), std::string::npos);
  EXPECT_NE(error_of("network: {subnet: 10.9.8.1/24}\nhosts: [{name: a, address: 10.9.8.1, components: []}]").find("host bits"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.9.1, components: [opp]}\n")).find("outside the subnet"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.255, components: [opp]}\n")).find("broadcast"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: nope, components: [opp]}\n")).find("not an IPv4"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [opp]}\n  - {name: b, address: 10.9.8.1, components: []}\n"))
                .find("used twice"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [opp]}\n  - {name: a, address: 10.9.8.2, components: []}\n"))
                .find("duplicate host"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [opp]}\n  - {name: b, address: 10.9.8.2, components: [opp]}\n"))
                .find("two hosts"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [planner]}\n")).find("unknown component 'planner'"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: A_1, address: 10.9.8.1, components: []}\n")).find("host name"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, interface: 'a b', components: []}\n")).find("interface"), std::string::npos);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [], colour: red}\n")).find("unknown field 'colour'"), std::string::npos);
  EXPECT_NE(error_of("network: {subnet: 10.9.8.0/24, spdp_interval: 5, lease_duration: 6}\nhosts: [{name: a, address: 10.9.8.1, components: []}]")
                .find("twice spdp_interval"), std::string::npos);
  EXPECT_NE(error_of("hosts: [").find("x.yaml:"), std::string::npos);
  EXPECT_NE(error_of("network: {subnet: 10.9.8.0/24}\nhosts: []").find("non-empty"), std::string::npos);
}

TEST(Deployment, LinkAndCutSpecs) {
  const dp::LinkSpec l = dp::parse_link("delay 50ms loss 20% jitter 5ms");
  EXPECT_DOUBLE_EQ(l.loss_pct, 20.0);
  EXPECT_DOUBLE_EQ(l.delay_ms, 50.0);
  EXPECT_DOUBLE_EQ(l.jitter_ms, 5.0);
  EXPECT_EQ(dp::parse_link("loss 20% delay 50ms").text(), "loss 20% delay 50ms");
  EXPECT_FALSE(dp::parse_link("").impaired());
  for (const char* bad : {"loss 20", "loss 20ms", "delay 50%", "loss", "loss 100%", "loss 5% loss 6%", "rate 1mbit",
                          "delay -5ms", "delay nanms", "delay 20000ms"})
    EXPECT_THROW(dp::parse_link(bad), std::invalid_argument) << bad;
  const dp::LinkCut c = dp::parse_cut("autonomy@600+5.5");
  EXPECT_EQ(c.host, "autonomy");
  EXPECT_DOUBLE_EQ(c.at_s, 600.0);
  EXPECT_DOUBLE_EQ(c.duration_s, 5.5);
  for (const char* bad : {"autonomy", "autonomy@600", "@600+5", "autonomy@x+5", "autonomy@600+0", "autonomy@600+-1", "autonomy@600+9999"})
    EXPECT_THROW(dp::parse_cut(bad), std::invalid_argument) << bad;
}

TEST(Deployment, PerHostLinksFromTheFileAndTheCommandLine) {
  const dp::Deployment d = dp::parse(with_hosts("  - {name: a, address: 10.9.8.1, components: [opp], link: 'delay 5ms'}\n"
                                                "  - {name: b, address: 10.9.8.2, components: []}\n"),
                                     "x.yaml");
  auto l = dp::host_links(d, {});
  EXPECT_DOUBLE_EQ(l["a"].delay_ms, 5.0);
  EXPECT_FALSE(l["b"].impaired());
  l = dp::host_links(d, {"loss 20% delay 50ms", "b: loss 1%"});
  EXPECT_DOUBLE_EQ(l["a"].loss_pct, 20.0);
  EXPECT_DOUBLE_EQ(l["a"].delay_ms, 50.0);
  EXPECT_DOUBLE_EQ(l["b"].loss_pct, 1.0);
  EXPECT_DOUBLE_EQ(l["b"].delay_ms, 0.0);
  EXPECT_THROW(dp::host_links(d, {"c: loss 1%"}), std::invalid_argument);
  EXPECT_THROW(dp::host_links(d, {"a: loss"}), std::invalid_argument);
  EXPECT_NE(error_of(with_hosts("  - {name: a, address: 10.9.8.1, components: [], link: 'loss 200%'}\n")).find("below 100%"),
            std::string::npos);
}

TEST(Deployment, CycloneConfigNamesTheInterfaceAndEveryPeer) {
  const dp::Deployment d = dp::parse(kGood, "x.yaml");
  const std::string x = dp::cyclone_config(d, d.hosts[1]);
  EXPECT_NE(x.find("<NetworkInterface name=\"ens3\"/>"), std::string::npos) << x;
  EXPECT_NE(x.find("<AllowMulticast>false</AllowMulticast>"), std::string::npos);
  EXPECT_NE(x.find("<Peer address=\"10.9.8.1\"/>"), std::string::npos);
  EXPECT_NE(x.find("<Peer address=\"10.9.8.2\"/>"), std::string::npos);
  EXPECT_NE(x.find("<SPDPInterval>0.5s</SPDPInterval>"), std::string::npos);
  EXPECT_EQ(x.find("eth0"), std::string::npos);
}

// The generated launch file is one mpgc_launch accepts: its components, restarted always, with the
// host's Cyclone configuration; the evaluator is not a ship's process.
TEST(Deployment, HostLaunchFileIsValidForTheLauncher) {
  const dp::Deployment d = dp::parse(kGood, "x.yaml");
  dp::LaunchOptions o;
  o.params_dir = ::testing::TempDir();
  std::ofstream(fs::path(o.params_dir) / "opp.yaml") << "{}\n";
  const auto lf = mpgc::launch::parse(dp::host_launch(d, d.hosts[1], o), "gen.yaml", "/", "/");
  ASSERT_EQ(lf.components.size(), 1u);
  EXPECT_EQ(lf.components[0].name, "opp");
  EXPECT_EQ(lf.components[0].executable, "/opt/mpgc/bin/mpgc_opp");
  EXPECT_EQ(lf.components[0].restart, "always");
  EXPECT_EQ(lf.components[0].env.at("CYCLONEDDS_URI"), "file:///etc/mpgc/cyclonedds.xml");
}

// deploy/systemd/ is what the generator writes (regenerate with ./mpgc deploy units --out deploy/systemd).
TEST(Deployment, ShippedSystemdUnitsAreTheGeneratedOnes) {
  const fs::path dir = fs::path(mpgc::testing::source_dir()) / "deploy" / "systemd";
  dp::LaunchOptions o;
  int units = 0;
  for (const auto& c : dp::known_components()) {
    if (c == "scenario_runner") continue;
    std::ifstream in(dir / ("mpgc-" + c + ".service"));
    ASSERT_TRUE(in) << "missing " << (dir / ("mpgc-" + c + ".service"));
    std::stringstream ss;
    ss << in.rdbuf();
    EXPECT_EQ(ss.str(), dp::systemd_unit(c, o)) << c << ": deploy/systemd is stale";
    EXPECT_NE(ss.str().find("Restart=always"), std::string::npos);
    ++units;
  }
  EXPECT_EQ(units, 6);
}

// systemd itself accepts the units (sections, keys, the executables they start).
TEST(Deployment, GeneratedUnitsPassSystemdAnalyzeVerify) {
  if (mpgc::testing::shell("command -v systemd-analyze").code != 0) GTEST_SKIP() << "no systemd-analyze on this machine";
  const fs::path dir = fs::path(::testing::TempDir()) / ("mpgc_units_" + std::to_string(getpid()));
  fs::create_directories(dir);
  dp::LaunchOptions o;
  o.bin_dir = mpgc::testing::bin_dir();
  std::string files;
  for (const auto& c : dp::known_components()) {
    if (c == "scenario_runner" || !fs::exists(o.bin_dir + "/mpgc_" + c)) continue;
    std::ofstream(dir / ("mpgc-" + c + ".service")) << dp::systemd_unit(c, o);
    files += " " + (dir / ("mpgc-" + c + ".service")).string();
  }
  std::ofstream(dir / "mpgc.target") << dp::systemd_target();
  const auto r = mpgc::testing::shell("systemd-analyze verify" + files + " " + (dir / "mpgc.target").string());
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output, "") << "systemd-analyze has remarks";
  fs::remove_all(dir);
}

TEST(Deployment, ShippedThreeHostsFileIsValidAndPlacesTheClosedLoop) {
  const dp::Deployment d = dp::load(mpgc::testing::source_dir() + "/deploy/hosts/three-hosts.yaml");
  ASSERT_EQ(d.hosts.size(), 3u);
  for (const char* c : {"ship_simulator", "situational_awareness", "obstacle_manager", "opp", "guidance_control", "scenario_runner"})
    EXPECT_NE(d.host_of(c), nullptr) << c;
  EXPECT_EQ(d.host_of("ship_simulator")->name, "ship");
  EXPECT_EQ(d.host_of("opp")->name, "autonomy");
  EXPECT_EQ(d.host_of("guidance_control")->name, "bridge-pc");
}
