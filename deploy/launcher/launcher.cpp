// mpgc_launch: starts the components of a YAML launch file, prefixes every line of their output
// with the component's name, forwards SIGINT/SIGTERM, restarts crashed components by policy and
// exits non-zero when a required component fails, and prints the system's health (which process
// is down, which component degraded or stale) from the processes it runs and the `health` topic.
// See deploy/launch/README.md for the format.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/types.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <sys/prctl.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <yaml-cpp/yaml.h>

#include "launch_file.hpp"
#include "mpgc/dds/dds.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/runtime/health_board.hpp"
#include "mpgc/topics.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

volatile std::sig_atomic_t g_signal = 0;
extern "C" void on_signal(int sig) { g_signal = sig; }

struct Proc {
  mpgc::launch::ComponentSpec spec;
  pid_t pid = -1;
  int out_fd = -1;
  std::string partial;          // output not yet ended by a newline
  int restarts = 0;
  bool done = false;            // exited and will not be restarted
  bool failed = false;          // exited with an error (non-zero code or a signal)
  Clock::time_point restart_at{};
  bool waiting_restart = false;
};

void emit(const std::string& name, const std::string& line) {
  std::string out = "[" + name + "] " + line + "\n";
  (void)!write(STDOUT_FILENO, out.data(), out.size());
}

bool start(Proc& p) {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) return false;
  std::vector<std::string> argv = p.spec.argv();
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return false;
  }
  if (pid == 0) {
    setpgid(0, 0);  // own process group: signals reach the component and whatever it started
    dup2(fds[1], STDOUT_FILENO);
    dup2(fds[1], STDERR_FILENO);
    for (const auto& [k, v] : p.spec.env) setenv(k.c_str(), v.c_str(), 1);
    std::vector<char*> cargv;
    for (auto& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    close_range(3, ~0U, 0);  // not the launcher's DDS sockets: they are not the component's
    execvp(cargv[0], cargv.data());
    // No stdio after fork: a DDS thread of the launcher may have held stderr's lock.
    dprintf(STDERR_FILENO, "cannot execute '%s': %s\n", cargv[0], std::strerror(errno));
    _exit(127);
  }
  setpgid(pid, pid);
  close(fds[1]);
  fcntl(fds[0], F_SETFL, O_NONBLOCK);
  p.pid = pid;
  p.out_fd = fds[0];
  p.partial.clear();
  emit("launch", "started " + p.spec.name + " (pid " + std::to_string(pid) + "): " + p.spec.command_line());
  return true;
}

// Reads what is available; emits complete lines (and the rest at end of stream).
void drain(Proc& p) {
  char buf[4096];
  for (;;) {
    const ssize_t n = read(p.out_fd, buf, sizeof buf);
    if (n > 0) {
      p.partial.append(buf, static_cast<size_t>(n));
      size_t pos;
      while ((pos = p.partial.find('\n')) != std::string::npos) {
        emit(p.spec.name, p.partial.substr(0, pos));
        p.partial.erase(0, pos + 1);
      }
      continue;
    }
    if (n == 0) {  // end of stream
      if (!p.partial.empty()) emit(p.spec.name, p.partial);
      p.partial.clear();
      close(p.out_fd);
      p.out_fd = -1;
    }
    return;
  }
}

std::string describe(int status) {
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return std::string("killed by signal ") + strsignal(WTERMSIG(status));
  return "stopped";
}

// What a component used, from the kernel's account at its end (read by the scenario runner into
// metrics.json: issue 20, where the wall time and the memory go).
std::string usage(const rusage& ru) {
  const double cpu = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  char b[96];
  std::snprintf(b, sizeof b, " (peak RSS %.1f MB, CPU %.2f s)", static_cast<double>(ru.ru_maxrss) / 1024.0, cpu);
  return b;
}

int64_t steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

// The system health view: the processes the launcher runs and the components' `health` samples,
// through a plain DDS reader (the launcher is no component: it lives on the wall clock whatever
// clock the components use). Printed every `period` and at once when a component gets into or out
// of trouble (down, degraded, stale).
class HealthView {
 public:
  HealthView(double period, double component_period, const std::vector<Proc>& procs, int domain)
      : period_(period), board_({component_period, 3}), next_(Clock::now() + to_duration(period)) {
    const int64_t now = steady_ns();
    for (const auto& p : procs) {
      // Only mpgc components publish health; others (gpsd, a shell) are judged by their process.
      const std::string exe = fs::path(p.spec.executable).filename().string();
      board_.expect(p.spec.name, now, exe.rfind("mpgc_", 0) == 0);
    }
    board_.changes(now);  // prime: the start itself is no news
    if (domain < 0) return;   // no DDS: processes only
    try {
      participant_ = std::make_unique<mpgc::dds::Participant>(static_cast<uint32_t>(domain));
      topic_ = std::make_unique<mpgc::dds::Topic<mpgc::msg::ComponentHealth>>(*participant_, mpgc::topics::kHealth);
      reader_ = std::make_unique<mpgc::dds::Reader<mpgc::msg::ComponentHealth>>(*participant_, *topic_,
                                                                                mpgc::dds::QosProfile::latched());
    } catch (const std::exception& e) {
      reader_.reset();
      topic_.reset();
      participant_.reset();
      emit("launch", std::string("health view from process states only: cannot read the health topic: ") + e.what());
    }
  }
  void started(const Proc& p) { board_.process_started(p.spec.name, steady_ns()); }
  void gone(const Proc& p, const std::string& why) { board_.process_gone(p.spec.name, why, steady_ns()); }

  void update(bool quiet) {
    const int64_t now = steady_ns();
    if (reader_) {
      try {
        for (const auto& s : reader_->take()) board_.sample(s.value, now);
      } catch (const std::exception& e) {
        emit("launch", std::string("health topic: ") + e.what());
      }
    }
    bool news = false;
    for (const auto& v : board_.changes(now)) {
      const bool trouble = v.status == mpgc::rt::Status::kDown || v.status == mpgc::rt::Status::kDegraded ||
                           v.status == mpgc::rt::Status::kStale;
      bool& was = troubled_[v.name];
      news = news || trouble || was;  // into trouble, or on the way out of it (restarted, ok)
      was = trouble || (was && v.status != mpgc::rt::Status::kUp);
    }
    const bool due = Clock::now() >= next_;
    if (due) next_ = Clock::now() + to_duration(period_);
    if (!quiet && (news || due)) emit("launch", "health: " + board_.line(now));
  }

 private:
  static Clock::duration to_duration(double s) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  }
  double period_;
  mpgc::rt::HealthBoard board_;
  Clock::time_point next_;
  std::map<std::string, bool> troubled_;
  std::unique_ptr<mpgc::dds::Participant> participant_;
  std::unique_ptr<mpgc::dds::Topic<mpgc::msg::ComponentHealth>> topic_;
  std::unique_ptr<mpgc::dds::Reader<mpgc::msg::ComponentHealth>> reader_;
};

static_assert(static_cast<int>(mpgc::msg::HealthState::HEALTH_STOPPING) == static_cast<int>(mpgc::rt::Reported::kStopping) &&
                  static_cast<int>(mpgc::msg::HealthState::HEALTH_DEGRADED) == static_cast<int>(mpgc::rt::Reported::kDegraded),
              "rt::Reported mirrors msg::HealthState");

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc_launch: start the components of a launch file"};
  std::string file;
  int domain = -1;
  double stop_timeout = 5.0;
  app.add_option("file", file, "launch file (YAML)")->required();
  app.add_option("--domain", domain, "DDS domain for every component (overrides the file)");
  app.add_option("--stop-timeout", stop_timeout, "[s] grace period after SIGTERM before SIGKILL");
  std::string secure;
  app.add_option("--secure", secure,
                 "DDS Security: every component joins with its identity (certificate CN = its name) from this folder "
                 "(deploy/security/make-pki.sh DIR): its security.xml is added to CYCLONEDDS_URI");
  double health_period = 10.0;
  app.add_option("--health-period", health_period,
                 "[s] print the system health every this many seconds, and at once when a component changes state "
                 "(down, restarted, degraded, stale, ok); 0 = no health view")
      ->check(CLI::Range(0.0, 86400.0));
  CLI11_PARSE(app, argc, argv);

  mpgc::launch::LaunchFile lf;
  try {
    lf = mpgc::launch::load(file, fs::canonical("/proc/self/exe").parent_path().string());
  } catch (const std::exception& e) {
    std::cerr << "mpgc_launch: " << e.what() << "\n";
    return 2;
  }
  if (domain >= 0) lf.domain = domain;

  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  signal(SIGPIPE, SIG_IGN);
  prctl(PR_SET_CHILD_SUBREAPER, 1);  // a component's orphaned children come to us, not to init

  std::vector<Proc> procs;
  if (!secure.empty()) {
    secure = fs::absolute(secure).string();
    if (!fs::exists(fs::path(secure) / "security.xml")) {
      std::cerr << "mpgc_launch: --secure " << secure << ": no security.xml (make it with deploy/security/make-pki.sh)\n";
      return 2;
    }
  }
  for (auto& c : lf.components) {
    if (lf.domain >= 0) c.env["MPGC_DOMAIN"] = std::to_string(lf.domain);
    if (!secure.empty()) {
      // The network configuration stays (the component's own, else ours); security is merged after it.
      const char* inherited = std::getenv("CYCLONEDDS_URI");
      std::string uri = c.env.count("CYCLONEDDS_URI") ? c.env["CYCLONEDDS_URI"] : inherited != nullptr ? inherited : "";
      if (uri.empty()) {
        std::cerr << "mpgc_launch: --secure needs CYCLONEDDS_URI (the network configuration) for " << c.name << "\n";
        return 2;
      }
      c.env["CYCLONEDDS_URI"] = uri + ",file://" + secure + "/security.xml";
      if (!c.env.count("MPGC_SECURITY_ID")) c.env["MPGC_SECURITY_ID"] = c.name;
    }
    procs.push_back(Proc{c});
  }
  std::unique_ptr<HealthView> health;
  if (health_period > 0.0) {
    if (!secure.empty()) {
      // The launcher has no identity of its own in the PKI: on a secured domain it would be an intruder.
      emit("launch", "health view from process states only: --secure (the launcher joins no secured domain)");
    }
    int health_domain = lf.domain;
    if (health_domain < 0) health_domain = std::getenv("MPGC_DOMAIN") != nullptr ? std::atoi(std::getenv("MPGC_DOMAIN")) : 0;
    // Stale means silent for 3 of the components' health periods: the longest any of them was given.
    double component_period = 1.0;
    for (const auto& p : procs)
      if (auto it = p.spec.set.find("health.period"); it != p.spec.set.end()) {
        try {
          component_period = std::max(component_period, std::stod(it->second));
        } catch (const std::exception&) {
        }  // the component refuses it itself
      }
    health = std::make_unique<HealthView>(health_period, component_period, procs, secure.empty() ? health_domain : -1);
  }
  for (auto& p : procs) {
    if (!start(p)) {
      emit("launch", "cannot start " + p.spec.name + ": " + std::strerror(errno));
      p.done = p.failed = true;
      if (health) health->gone(p, std::string("cannot start: ") + std::strerror(errno));
    } else if (health) {
      health->started(p);
    }
  }

  bool stopping = false;
  bool required_failed = false;
  Clock::time_point kill_at{};
  for (;;) {
    if (g_signal != 0 && !stopping) {
      emit("launch", std::string("received ") + strsignal(g_signal) + ", stopping all components");
      stopping = true;
    }
    if (stopping && kill_at == Clock::time_point{}) {
      for (auto& p : procs)
        if (p.pid > 0) kill(-p.pid, SIGTERM);
      kill_at = Clock::now() + std::chrono::milliseconds(static_cast<int>(stop_timeout * 1000));
    }
    if (stopping && Clock::now() > kill_at) {
      for (auto& p : procs)
        if (p.pid > 0) {
          emit("launch", p.spec.name + " did not stop in time: SIGKILL");
          kill(-p.pid, SIGKILL);
          p.failed = true;
        }
      kill_at = Clock::now() + std::chrono::hours(1);
    }

    std::vector<pollfd> fds;
    std::vector<Proc*> owners;
    for (auto& p : procs)
      if (p.out_fd >= 0) {
        fds.push_back({p.out_fd, POLLIN, 0});
        owners.push_back(&p);
      }
    if (!fds.empty()) {
      poll(fds.data(), fds.size(), 100);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    for (size_t i = 0; i < fds.size(); ++i)
      if (fds[i].revents != 0) drain(*owners[i]);

    // Every child that ended: ours, or an orphan re-parented to us (as a container's first process
    // or a subreaper the launcher inherits what its components left behind, and must reap it).
    for (;;) {
      int status = 0;
      rusage ru{};
      const pid_t w = wait4(-1, &status, WNOHANG, &ru);
      if (w <= 0) break;
      auto it = std::find_if(procs.begin(), procs.end(), [w](const Proc& q) { return q.pid == w; });
      if (it == procs.end()) continue;
      Proc& p = *it;
      if (p.out_fd >= 0) {
        drain(p);
        if (p.out_fd >= 0) close(p.out_fd);
        p.out_fd = -1;
      }
      p.pid = -1;
      const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
      emit("launch", p.spec.name + " " + describe(status) + usage(ru));
      const bool may_restart = !stopping && p.restarts < p.spec.max_restarts &&
                               (p.spec.restart == "always" || (p.spec.restart == "on-failure" && !ok));
      if (health) {
        std::string why = WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status)) + " (" +
                                                    strsignal(WTERMSIG(status)) + ")"
                                              : describe(status);
        if (may_restart) why += ", restarting " + std::to_string(p.restarts + 1) + "/" + std::to_string(p.spec.max_restarts);
        health->gone(p, why);
      }
      if (may_restart) {
        p.waiting_restart = true;
        p.restart_at = Clock::now() + std::chrono::milliseconds(static_cast<int>(p.spec.restart_delay * 1000));
        continue;
      }
      p.done = true;
      p.failed = p.failed || !ok;
      if (p.failed && p.spec.required && !stopping) {
        emit("launch", "required component " + p.spec.name + " failed: stopping all components");
        required_failed = true;
        stopping = true;
      }
    }
    for (auto& p : procs) {
      if (!p.waiting_restart || Clock::now() < p.restart_at) continue;
      p.waiting_restart = false;
      ++p.restarts;
      emit("launch", "restarting " + p.spec.name + " (" + std::to_string(p.restarts) + "/" +
                         std::to_string(p.spec.max_restarts) + ")");
      if (!start(p)) {
        p.done = p.failed = true;
        if (health) health->gone(p, std::string("cannot restart: ") + std::strerror(errno));
      } else if (health) {
        health->started(p);
      }
    }
    if (health) health->update(stopping);

    bool all_done = true;
    for (auto& p : procs) all_done = all_done && p.done && p.out_fd < 0;
    if (all_done) break;
  }

  int failed = 0;
  for (auto& p : procs) failed += (p.failed && p.spec.required) ? 1 : 0;
  emit("launch", failed == 0 && !required_failed ? "all components stopped cleanly"
                                                 : std::to_string(failed) + " required component(s) failed");
  return failed == 0 && !required_failed ? 0 : 1;
}
