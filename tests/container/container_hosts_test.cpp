// The three-host deployment (deploy/hosts/three-hosts.yaml) with every host its own podman
// container on its network namespace (`mpgc_run --hosts ... --containers`): the lockstep run is
// the single-host run bit for bit. Builds (or finds cached) the runtime image first. Needs root,
// podman, runc and debootstrap, as CI has.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "mpgc/testing.hpp"

namespace fs = std::filesystem;

namespace {

std::string capture(const std::string& cmd, int* code) {
  const auto r = mpgc::testing::shell(cmd);
  *code = r.code;
  return r.output;
}

std::string slurp(const fs::path& p) { return mpgc::testing::read_file(p.string()); }

}  // namespace

TEST(ContainerHosts, EachHostItsOwnContainerAndTheLoopIsTheSingleHostLoop) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces and podman need root (CI runs as root)";
  const std::string src = mpgc::testing::source_dir(), bin = mpgc::testing::bin_dir();
  int rc = 0;
  std::string out = capture(src + "/deploy/container/build-image.sh --quiet", &rc);
  ASSERT_EQ(rc, 0) << "image build failed:\n" << out;
  const fs::path tmp = fs::path(::testing::TempDir()) / ("mpgc_container_hosts_" + std::to_string(getpid()));
  fs::remove_all(tmp);
  const std::string scenario =
      mpgc::testing::shared_data("encounters/dnv/baseline_situations_generated/traffic_situation_02.json");
  out = capture(bin + "/mpgc_run " + scenario + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --out " + (tmp / "single").string(), &rc);
  ASSERT_EQ(rc, 0) << out;
  out = capture(bin + "/mpgc_run " + scenario + " --quiet --baseline " + mpgc::testing::source_dir() + "/scenarios/baseline.json --hosts " + src + "/deploy/hosts/three-hosts.yaml --containers --out " +
                    (tmp / "containers").string(),
                &rc);
  ASSERT_EQ(rc, 0) << out;
  const std::string log = slurp(tmp / "containers" / "dnv_02_CR-GW" / "components.log");
  for (const char* h : {"ship", "autonomy"})  // bridge-pc: guidance_control's container (the evaluator is mpgc_run)
    EXPECT_NE(log.find(std::string("[launch] started ") + h + " (pid"), std::string::npos) << log.substr(0, 2000);
  EXPECT_NE(log.find("podman run --rm --name"), std::string::npos);
  EXPECT_NE(log.find("[bridge-pc] [launch] started guidance_control"), std::string::npos);
  // The recorder runs in the evaluator's host's container too and leaves the run's recording.
  EXPECT_NE(log.find("[bridge-pc] [launch] started recorder"), std::string::npos);
  const std::string info = capture(bin + "/mpgc_inspect " + (tmp / "containers" / "dnv_02_CR-GW" / "run.mcap").string(), &rc);
  EXPECT_EQ(rc, 0) << info;
  EXPECT_NE(info.find("indexed:     yes"), std::string::npos) << info;
  EXPECT_NE(info.find("nav/own_state"), std::string::npos) << info;
  const std::string a = slurp(tmp / "single" / "dnv_02_CR-GW" / "timeseries.csv");
  const std::string b = slurp(tmp / "containers" / "dnv_02_CR-GW" / "timeseries.csv");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_TRUE(a == b) << "the containerised three-host run differs from the single-host run";
  // Stopped at the end by SIGTERM through podman: each host's launcher stopped its components cleanly.
  for (const char* h : {"ship", "autonomy", "bridge-pc"})
    EXPECT_NE(log.find(std::string("[launch] ") + h + " exited with code 0"), std::string::npos) << h;
}
