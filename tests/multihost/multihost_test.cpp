// Two hosts on one machine: network namespaces joined by a veth pair on a subnet that exists only
// inside them. The launcher places the talker on one and the listener on the other (`host:`);
// each host's Cyclone configuration names its own interface and lists both hosts as peers.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "mpgc/testing.hpp"

namespace {

int sh(const std::string& cmd) {
  const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string cyclone_config(const std::string& iface, const std::string& self, const std::string& peer) {
  return "<CycloneDDS xmlns=\"https://cdds.io/config\"><Domain Id=\"any\"><General><Interfaces>"
         "<NetworkInterface name=\"" + iface + "\"/></Interfaces><AllowMulticast>false</AllowMulticast>"
         "</General><Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>50"
         "</MaxAutoParticipantIndex><Peers><Peer address=\"" + self + "\"/><Peer address=\"" + peer +
         "\"/></Peers></Discovery></Domain></CycloneDDS>\n";
}

// Creates the two namespaces and the link; removes them when destroyed.
class TwoHosts {
 public:
  TwoHosts() {
    const std::string id = std::to_string(getpid() % 100000);
    a_ = "mpgcA" + id;
    b_ = "mpgcB" + id;
    subnet_ = "10.77." + std::to_string(getpid() % 250 + 1);
    ok_ = sh("ip netns add " + a_) == 0 && sh("ip netns add " + b_) == 0 &&
          sh("ip link add va" + id + " type veth peer name vb" + id) == 0 &&
          sh("ip link set va" + id + " netns " + a_) == 0 && sh("ip link set vb" + id + " netns " + b_) == 0 &&
          sh("ip -n " + a_ + " addr add " + subnet_ + ".1/24 dev va" + id) == 0 &&
          sh("ip -n " + b_ + " addr add " + subnet_ + ".2/24 dev vb" + id) == 0 &&
          sh("ip -n " + a_ + " link set va" + id + " up") == 0 && sh("ip -n " + b_ + " link set vb" + id + " up") == 0 &&
          sh("ip -n " + a_ + " link set lo up") == 0 && sh("ip -n " + b_ + " link set lo up") == 0;
    ia_ = "va" + id;
    ib_ = "vb" + id;
  }
  ~TwoHosts() {
    sh("ip netns del " + a_);  // deleting a namespace deletes its end of the veth pair, and so both
    sh("ip netns del " + b_);
  }
  bool ok() const { return ok_; }
  std::string a_, b_, ia_, ib_, subnet_;

 private:
  bool ok_ = false;
};

}  // namespace

TEST(MultiHost, TalkerAndListenerOnSeparateNamespacesExchangeData) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces need root (CI runs as root)";
  TwoHosts hosts;
  ASSERT_TRUE(hosts.ok()) << "could not create network namespaces (ip netns)";
  const std::string dir = ::testing::TempDir();
  const std::string cfg_a = dir + "/cyclone_" + hosts.a_ + ".xml", cfg_b = dir + "/cyclone_" + hosts.b_ + ".xml";
  std::ofstream(cfg_a) << cyclone_config(hosts.ia_, hosts.subnet_ + ".1", hosts.subnet_ + ".2");
  std::ofstream(cfg_b) << cyclone_config(hosts.ib_, hosts.subnet_ + ".2", hosts.subnet_ + ".1");
  const std::string launch = dir + "/multihost_" + hosts.a_ + ".yaml";
  std::ofstream(launch) << "components:\n"
                        << "  - {name: talker, executable: mpgc_test_talker, host: " << hosts.a_
                        << ", set: {rate: 20, count: 40}, env: {CYCLONEDDS_URI: 'file://" << cfg_a << "'}}\n"
                        << "  - {name: listener, executable: mpgc_test_listener, host: " << hosts.b_
                        << ", env: {CYCLONEDDS_URI: 'file://" << cfg_b << "'}}\n";
  // The talker stops after 40 samples (2 s); the listener is stopped by the timeout's SIGTERM.
  const std::string cmd = "timeout --preserve-status -s TERM 8 " + mpgc::testing::bin_dir() + "/mpgc_launch " + launch +
                          " --domain " + std::to_string(mpgc::testing::unique_domain()) + " 2>&1";
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int status = pclose(p);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("[listener] "), std::string::npos) << out;
  EXPECT_NE(out.find("received 10 (value"), std::string::npos) << "samples did not cross the veth link\n" << out;
  EXPECT_NE(out.find("[launch] talker exited with code 0"), std::string::npos) << out;
  EXPECT_NE(out.find("[launch] listener exited with code 0"), std::string::npos) << out;
}
