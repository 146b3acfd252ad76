// Starts real processes through mpgc_launch over loopback DDS: they exchange data, their output is
// prefixed with their names, SIGTERM stops everything cleanly, restart policies and required
// failures behave as documented.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <thread>
#include <sstream>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include "mpgc/testing.hpp"

namespace {

class Launch {
 public:
  explicit Launch(const std::string& yaml, std::vector<std::string> extra = {}) {
    file_ = ::testing::TempDir() + "/launch_" + std::to_string(getpid()) + "_" + std::to_string(counter_++) + ".yaml";
    std::ofstream(file_) << yaml;
    int fds[2];
    EXPECT_EQ(pipe(fds), 0);
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[1], STDOUT_FILENO);
      dup2(fds[1], STDERR_FILENO);
      close(fds[0]);
      const std::string exe = mpgc::testing::bin_dir() + "/mpgc_launch";
      const std::string domain = std::to_string(mpgc::testing::unique_domain());
      std::vector<std::string> args = {exe, file_, "--domain", domain, "--stop-timeout", "5"};
      args.insert(args.end(), extra.begin(), extra.end());
      std::vector<char*> argv;
      for (auto& a : args) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(exe.c_str(), argv.data());
      _exit(127);
    }
    close(fds[1]);
    fd_ = fds[0];
  }
  ~Launch() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    close(fd_);
  }
  // Reads output until `pattern` matches the whole output or the time runs out.
  bool wait_output(const std::string& pattern, double seconds) {
    const std::regex re(pattern);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!std::regex_search(out_, re)) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) return false;
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
      char buf[4096];
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n <= 0) return std::regex_search(out_, re);
      out_.append(buf, static_cast<size_t>(n));
    }
    return true;
  }
  // Appends whatever arrives within `seconds` (until end of stream).
  void drain(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
      if (left.count() <= 0) return;
      pollfd p{fd_, POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(left.count())) <= 0) return;
      char buf[4096];
      const ssize_t n = read(fd_, buf, sizeof buf);
      if (n <= 0) return;
      out_.append(buf, static_cast<size_t>(n));
    }
  }
  // Waits for the launcher to exit; returns its exit code (-1 on timeout or signal).
  int wait_exit(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      drain(0.05);  // keep the pipe from filling up
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        drain(0.5);
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
    }
    return -1;
  }
  void signal(int sig) { kill(pid_, sig); }
  pid_t pid() const { return pid_; }
  const std::string& output() const { return out_; }

 private:
  static inline int counter_ = 0;
  std::string file_;
  pid_t pid_ = -1;
  int fd_ = -1;
  bool exited_ = false;
  std::string out_;
};

}  // namespace

TEST(Launcher, TwoProcessesExchangeDataAndStopCleanlyOnSigterm) {
  Launch l(R"(
components:
  - name: talker
    executable: mpgc_test_talker
    set: {rate: 20}
  - name: listener
    executable: mpgc_test_listener
)");
  ASSERT_TRUE(l.wait_output(R"(\[listener\] .*received 5 \(value)", 30.0)) << l.output();
  l.signal(SIGTERM);
  EXPECT_EQ(l.wait_exit(20.0), 0) << l.output();
  const std::string& out = l.output();
  EXPECT_NE(out.find("[talker] "), std::string::npos);
  EXPECT_NE(out.find("[launch] talker exited with code 0 (peak RSS "), std::string::npos) << out;
  EXPECT_NE(out.find("[launch] listener exited with code 0"), std::string::npos) << out;
  EXPECT_NE(out.find("[listener] "), std::string::npos);
  EXPECT_NE(out.find("all components stopped cleanly"), std::string::npos);
}

TEST(Launcher, RestartsOnFailureThenFailsWhenRequired) {
  Launch l(R"(
components:
  - name: crasher
    executable: mpgc_test_talker
    set: {count: 2, rate: 50, exit_code: 3}
    restart: on-failure
    max_restarts: 2
    restart_delay: 0.1
  - name: bystander
    executable: mpgc_test_listener
)");
  EXPECT_EQ(l.wait_exit(60.0), 1) << l.output();
  const std::string& out = l.output();
  EXPECT_NE(out.find("restarting crasher (1/2)"), std::string::npos) << out;
  EXPECT_NE(out.find("restarting crasher (2/2)"), std::string::npos) << out;
  EXPECT_EQ(out.find("restarting crasher (3/2)"), std::string::npos) << out;
  EXPECT_NE(out.find("required component crasher failed"), std::string::npos) << out;
  EXPECT_NE(out.find("[launch] bystander exited with code 0"), std::string::npos) << out;
}

TEST(Launcher, OptionalFailureDoesNotStopTheOthers) {
  Launch l(R"(
components:
  - name: optional
    executable: /bin/false
    required: false
  - name: finisher
    executable: mpgc_test_talker
    set: {count: 3, rate: 20}
)");
  EXPECT_EQ(l.wait_exit(30.0), 0) << l.output();
  EXPECT_NE(l.output().find("[launch] optional exited with code 1"), std::string::npos) << l.output();
  EXPECT_NE(l.output().find("[launch] finisher exited with code 0"), std::string::npos) << l.output();
}

// A component's orphaned children are re-parented to the launcher (a subreaper, and PID 1 in a
// container) and reaped by it: no zombie is left while the run goes on.
TEST(Launcher, AdoptsAndReapsOrphansOfItsComponents) {
  Launch l(R"(
components:
  - name: forker
    executable: /bin/sh
    args: [-c, "(sleep 1 &); (sleep 1 &); sleep 3"]
)");
  ASSERT_TRUE(l.wait_output("started forker", 10.0)) << l.output();
  // The launcher's children and how many of them are zombies.
  auto children = [&] {
    int all = 0, zombies = 0;
    for (const auto& e : std::filesystem::directory_iterator("/proc")) {
      std::ifstream in(e.path() / "stat");
      std::string stat;
      if (!std::getline(in, stat)) continue;
      const auto close_paren = stat.rfind(')');
      if (close_paren == std::string::npos) continue;
      std::istringstream rest(stat.substr(close_paren + 2));
      char state = 0;
      int ppid = 0;
      rest >> state >> ppid;
      if (ppid != l.pid()) continue;
      ++all;
      zombies += state == 'Z' ? 1 : 0;
    }
    return std::make_pair(all, zombies);
  };
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(children().first, 3) << "the shell and its two orphaned sleeps, adopted by the launcher";
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));  // the orphans have ended
  const auto [all, zombies] = children();
  EXPECT_EQ(zombies, 0) << "orphans left as zombies under the launcher";
  EXPECT_EQ(all, 1) << "only the shell is left";
  EXPECT_EQ(l.wait_exit(10.0), 0) << l.output();
}

// The health view: every --health-period a line about every component, and at once when one goes
// down (how, and that it is restarted), stale (SIGSTOP: alive but silent) or comes back.
TEST(Launcher, HealthViewSaysWhichComponentIsDownOrStaleAndWhenItIsBack) {
  Launch l(R"(
components:
  - name: talker
    executable: mpgc_test_talker
    set: {rate: 20, health.period: 0.5}
    restart: on-failure
    max_restarts: 3
    restart_delay: 0.5
  - name: listener
    executable: mpgc_test_listener
    set: {health.period: 0.5}
)", {"--health-period", "1"});
  ASSERT_TRUE(l.wait_output(R"(\[launch\] health: all 2 up)", 30.0)) << l.output();
  std::smatch m;
  const std::string before = l.output();
  ASSERT_TRUE(std::regex_search(before, m, std::regex(R"(started talker \(pid (\d+)\))")));
  const pid_t talker = std::stoi(m[1]);
  ASSERT_TRUE(std::regex_search(before, m, std::regex(R"(started listener \(pid (\d+)\))")));
  const pid_t listener = std::stoi(m[1]);

  // Killed: down at once, with how and the restart; then starting, then up again.
  const size_t mark = l.output().size();
  kill(talker, SIGKILL);
  ASSERT_TRUE(l.wait_output(R"(\[launch\] health: talker down \(killed by signal 9 \(Killed\), restarting 1/3\); 1 up)", 10.0))
      << l.output().substr(mark);
  ASSERT_TRUE(l.wait_output(R"(restarting talker \(1/3\)[\s\S]*\[launch\] health: talker starting)", 10.0))
      << l.output().substr(mark);
  ASSERT_TRUE(l.wait_output(R"(health: talker starting[\s\S]*\[launch\] health: all 2 up)", 20.0)) << l.output().substr(mark);

  // Stopped (SIGSTOP): its process is there but it says nothing: stale after 3 periods of 0.5 s.
  const size_t mark2 = l.output().size();
  kill(listener, SIGSTOP);
  const bool stale = l.wait_output(R"(restarting talker[\s\S]*\[launch\] health: listener stale \(no health for \d)", 10.0);
  kill(listener, SIGCONT);
  ASSERT_TRUE(stale) << l.output().substr(mark2);
  ASSERT_TRUE(l.wait_output(R"(listener stale[\s\S]*\[launch\] health: all 2 up)", 20.0)) << l.output().substr(mark2);

  l.signal(SIGTERM);
  EXPECT_EQ(l.wait_exit(20.0), 0) << l.output();
  // Stopping is said by the exits themselves, not by health lines.
  const std::string after_stop = l.output().substr(l.output().find("received Terminated"));
  EXPECT_EQ(after_stop.find("health:"), std::string::npos) << after_stop;
}

TEST(Launcher, BadLaunchFileIsRejectedWithItsError) {
  Launch l("components:\n  - name: a\n    exectuable: x\n");
  EXPECT_EQ(l.wait_exit(10.0), 2);
  EXPECT_NE(l.output().find("unknown component field 'exectuable'"), std::string::npos) << l.output();
}

TEST(Launcher, MissingExecutableFailsTheRun) {
  Launch l("components:\n  - name: ghost\n    executable: /nonexistent/mpgc_ghost\n");
  EXPECT_EQ(l.wait_exit(10.0), 1) << l.output();
  EXPECT_NE(l.output().find("[ghost] cannot execute '/nonexistent/mpgc_ghost'"), std::string::npos) << l.output();
}

namespace {
// Runs a command, returns (exit code, stdout+stderr).
std::pair<int, std::string> run(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (p == nullptr) return {-1, ""};
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}
}  // namespace

TEST(ComponentCli, HelpListsParametersWithUnitsAndRanges) {
  const auto [code, out] = run(mpgc::testing::bin_dir() + "/mpgc_test_talker --help");
  EXPECT_EQ(code, 0);
  for (const char* s : {"rate", "Hz", "[0.1, 1000]", "dds.domain", "clock.source", "wall|sim", "log.level"})
    EXPECT_NE(out.find(s), std::string::npos) << s << "\n" << out;
}

TEST(ComponentCli, BadParametersExitWithCode2AndNameEachOne) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/talker_bad.yaml") << "rate: 5000\nclock:\n  source: gps\n";
  const auto [code, out] = run(mpgc::testing::bin_dir() + "/mpgc_test_talker --params " + dir +
                               "/talker_bad.yaml --set count=-1");
  EXPECT_EQ(code, 2) << out;
  for (const char* s : {"'rate'", "5000 Hz is outside its range", "'clock.source'", "'count'", "talker_bad.yaml"})
    EXPECT_NE(out.find(s), std::string::npos) << s << "\n" << out;
  const auto [code2, out2] = run(mpgc::testing::bin_dir() + "/mpgc_test_talker --set no.such=1");
  EXPECT_EQ(code2, 2);
  EXPECT_NE(out2.find("unknown parameter 'no.such'"), std::string::npos) << out2;
}
