// mpgc::rt::spawn_logged, wait_exit, run_command: the one way the project starts a program.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "mpgc/runtime/process.hpp"

namespace rt = mpgc::rt;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
fs::path temp_log(const char* name) { return fs::temp_directory_path() / (std::string(name) + std::to_string(getpid()) + ".log"); }
}  // namespace

TEST(Process, OutputAndErrorsGoToTheLogAndTheExitStatusComesBack) {
  const fs::path log = temp_log("mpgc_process_a");
  const pid_t pid = rt::spawn_logged({"sh", "-c", "echo out; echo err >&2; exit 3"}, log.string());
  ASSERT_GT(pid, 0);
  EXPECT_EQ(rt::wait_exit(pid), 3);
  EXPECT_EQ(slurp(log), "out\nerr\n");
  fs::remove(log);
}

TEST(Process, AKilledChildReports128PlusTheSignalAndLeadsItsOwnGroup) {
  const pid_t pid = rt::spawn_logged({"sleep", "30"}, "");
  ASSERT_GT(pid, 0);
  EXPECT_EQ(getpgid(pid), pid);
  ASSERT_EQ(kill(-pid, SIGKILL), 0);  // the group: what a runner stopping a launcher does
  EXPECT_EQ(rt::wait_exit(pid), 128 + SIGKILL);
  EXPECT_EQ(rt::wait_exit(pid), -1);  // reaped: no such child any more
}

TEST(Process, AMissingProgramExits127WithTheReasonInTheLog) {
  const fs::path log = temp_log("mpgc_process_b");
  const pid_t pid = rt::spawn_logged({"/nonexistent/mpgc_no_such_program", "x"}, log.string(), false);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(rt::wait_exit(pid), 127);
  EXPECT_NE(slurp(log).find("cannot execute '/nonexistent/mpgc_no_such_program'"), std::string::npos) << slurp(log);
  EXPECT_EQ(rt::spawn_logged({}, log.string()), -1);
  fs::remove(log);
}

TEST(Process, RunCommandCapturesBothStreams) {
  std::string out;
  EXPECT_EQ(rt::run_command({"sh", "-c", "printf a; printf b >&2; exit 2"}, &out), 2);
  EXPECT_EQ(out, "ab");
  EXPECT_EQ(rt::run_command({"true"}), 0);
  EXPECT_EQ(rt::run_command({}), -1);
  out.clear();
  EXPECT_EQ(rt::run_command({"mpgc_no_such_program_in_path"}, &out), 127);
  EXPECT_NE(out.find("cannot execute"), std::string::npos);
}
