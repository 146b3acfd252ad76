// Test harness for the hardware-in-the-loop tests: a gpsd of the test's own on loopback, fed over
// UDP by the test, or a gpsfake replaying a log (notes/gpsd.md §1, §4); a JSON watch on its TCP
// port; a UDP sender to feed gpsd's devices; a tiny field extraction for gpsd's flat JSON lines.
// Header-only, no gtest: callers check ok() / error() and put the message in their own assertion
// (MPGC_HIL_GPSD_WITH_WATCH at the end expands to the caller's gtest assertions).
//
// Processes run in their own process group (runuser -> gpsd, gpsfake -> python -> gpsd), so the
// destructor signals exactly that group: SIGTERM, then SIGKILL after 3 s. As root they run as
// `nobody` (a root gpsd drops to user gpsd and leaves its socket and SHM segment behind).
#pragma once

#include <arpa/inet.h>
#include <dirent.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace mpgc::hil {

// Absolute path of an executable in PATH, /usr/sbin or /usr/bin; "" when not installed.
inline std::string find_exe(const std::string& name) {
  std::string dirs = "/usr/sbin:/usr/bin:/sbin:/bin";
  if (const char* p = std::getenv("PATH")) dirs = std::string(p) + ":" + dirs;
  std::stringstream ss(dirs);
  for (std::string d; std::getline(ss, d, ':');) {
    if (d.empty()) continue;
    const std::string f = d + "/" + name;
    if (access(f.c_str(), X_OK) == 0) return f;
  }
  return "";
}

// Is anything bound to 127.0.0.1/0.0.0.0:port (TCP in state LISTEN, or UDP at all)? From
// /proc/net/{tcp,udp}, so checking opens no connection gpsd would see as a client.
inline bool port_bound(int port, bool tcp) {
  for (const char* file : tcp ? std::vector<const char*>{"/proc/net/tcp", "/proc/net/tcp6"}
                              : std::vector<const char*>{"/proc/net/udp", "/proc/net/udp6"}) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string slot, local, remote, state;
      ls >> slot >> local >> remote >> state;
      const size_t colon = local.rfind(':');
      if (colon == std::string::npos) continue;
      if (std::strtol(local.c_str() + colon + 1, nullptr, 16) != port) continue;
      if (!tcp || state == "0A") return true;  // 0A = LISTEN
    }
  }
  return false;
}

// Can we bind port on 127.0.0.1 right now (nobody else has it)?
inline bool port_free(int port, bool tcp) {
  const int fd = socket(AF_INET, tcp ? SOCK_STREAM : SOCK_DGRAM, 0);
  if (fd < 0) return false;
  // As gpsd binds: TIME_WAIT left by an earlier replay on this port does not make it taken.
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const bool ok = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  close(fd);
  return ok && !port_bound(port, tcp);
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

class GpsdProcess {
 public:
  // gpsd -N -n reading one UDP device per port in `udp_ports` (127.0.0.1 only). The ports and the
  // TCP port are chosen here, away from other tests (29500 + a pid-derived offset), retried on a
  // bind failure. udp_port(i) gives the i-th device's port.
  static GpsdProcess udp(int n_udp_ports) {
    GpsdProcess g;
    const std::string gpsd = find_exe("gpsd");
    if (gpsd.empty()) return g.failed("gpsd is not installed: apt-get install gpsd gpsd-clients");
    if (!g.make_dir()) return g;
    for (int attempt = 0; attempt < 8; ++attempt) {
      if (!g.pick_ports(attempt, 1 + n_udp_ports)) continue;
      char key[32];
      std::snprintf(key, sizeof key, "GPSD_SHM_KEY=0x4750%04X", g.port_ & 0xFFFF);  // not the system 0x47505344
      std::vector<std::string> cmd = {"env", key, gpsd, "-N", "-n", "-S", std::to_string(g.port_), "-F",
                                      g.dir_ + "/ctl.sock"};
      for (int i = 0; i < n_udp_ports; ++i) cmd.push_back("udp://127.0.0.1:" + std::to_string(g.udp_[i]));
      if (!g.spawn(cmd)) return g;
      bool up = g.wait_listening(8000);
      for (int i = 0; up && i < n_udp_ports; ++i) up = g.wait_bound(g.udp_[i], false, 2000);
      if (up) {
        g.error_.clear();
        return g;
      }
      g.stop();  // port lost to someone else (or gpsd failed): try other ports
    }
    if (g.error_.empty()) g.error_ = "gpsd did not start";
    return g;
  }

  // As udp(), but on exactly the TCP port and UDP device ports given (no other ports tried), e.g.
  // a gpsd that comes back where a client keeps reconnecting. Fails when one of them is taken.
  static GpsdProcess udp_on(int tcp_port, const std::vector<int>& udp_ports) {
    GpsdProcess g;
    const std::string gpsd = find_exe("gpsd");
    if (gpsd.empty()) return g.failed("gpsd is not installed: apt-get install gpsd gpsd-clients");
    if (!g.make_dir()) return g;
    g.port_ = tcp_port;
    g.udp_ = udp_ports;
    if (!port_free(tcp_port, true)) return g.failed("port " + std::to_string(tcp_port) + " in use");
    for (int p : udp_ports)
      if (!port_free(p, false)) return g.failed("port " + std::to_string(p) + " in use");
    char key[32];
    std::snprintf(key, sizeof key, "GPSD_SHM_KEY=0x4750%04X", g.port_ & 0xFFFF);
    std::vector<std::string> cmd = {"env", key, gpsd, "-N", "-n", "-S", std::to_string(g.port_), "-F",
                                    g.dir_ + "/ctl.sock"};
    for (int p : udp_ports) cmd.push_back("udp://127.0.0.1:" + std::to_string(p));
    if (!g.spawn(cmd)) return g;
    bool up = g.wait_listening(8000);
    for (size_t i = 0; up && i < udp_ports.size(); ++i) up = g.wait_bound(udp_ports[i], false, 2000);
    if (!up) {
      g.stop();
      if (g.error_.empty()) g.error_ = "gpsd did not start";
    }
    return g;
  }

  // gpsfake -1 -p -q -P <port> <log> (+ extra_args): replays the log once into its own gpsd. With
  // -p gpsfake watches itself, so the feed starts ~1.4 s after its port listens and a client that
  // connects at once gets every message (notes §1); its own JSON/NMEA output goes to stdout_path().
  static GpsdProcess gpsfake(const std::string& log, const std::vector<std::string>& extra_args = {}) {
    GpsdProcess g;
    const std::string gpsfake_exe = find_exe("gpsfake");
    if (gpsfake_exe.empty() || find_exe("gpsd").empty())
      return g.failed("gpsfake/gpsd are not installed: apt-get install gpsd gpsd-clients");
    if (access(log.c_str(), R_OK) != 0) return g.failed("cannot read log " + log);
    if (!g.make_dir()) return g;
    for (int attempt = 0; attempt < 8; ++attempt) {
      if (!g.pick_ports(attempt, 1)) continue;
      // TMPDIR: gpsfake puts its control socket there, so it goes away with our directory.
      std::vector<std::string> cmd = {"env", "TMPDIR=" + g.dir_, gpsfake_exe, "-1", "-p", "-q", "-P",
                                      std::to_string(g.port_)};
      cmd.insert(cmd.end(), extra_args.begin(), extra_args.end());
      cmd.push_back(log);
      if (!g.spawn(cmd)) return g;
      if (g.wait_listening(15000)) {
        g.error_.clear();
        return g;
      }
      g.stop();
    }
    if (g.error_.empty()) g.error_ = "gpsfake did not start";
    return g;
  }

  GpsdProcess(GpsdProcess&& o) noexcept { *this = std::move(o); }
  GpsdProcess& operator=(GpsdProcess&& o) noexcept {
    if (this != &o) {
      stop();
      remove_dir();
      pid_ = std::exchange(o.pid_, -1);
      port_ = o.port_;
      udp_ = std::move(o.udp_);
      dir_ = std::exchange(o.dir_, std::string());
      error_ = std::move(o.error_);
      rc_ = o.rc_;
      leader_is_runuser_ = o.leader_is_runuser_;
    }
    return *this;
  }
  GpsdProcess(const GpsdProcess&) = delete;
  GpsdProcess& operator=(const GpsdProcess&) = delete;
  ~GpsdProcess() {
    stop();
    remove_dir();
  }

  bool ok() const { return error_.empty() && pid_ > 0; }
  const std::string& error() const { return error_; }
  int port() const { return port_; }                  // gpsd's TCP port (127.0.0.1)
  int udp_port(size_t i) const { return udp_.at(i); }  // the i-th UDP device
  const std::string& dir() const { return dir_; }
  std::string stdout_path() const { return dir_ + "/stdout"; }
  std::string stderr_text() const { return read_file(dir_ + "/stderr"); }

  bool running() {
    if (pid_ <= 0) return false;
    int st = 0;
    if (waitpid(pid_, &st, WNOHANG) == pid_) {
      rc_ = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      kill(-pid_, SIGKILL);  // anything left in the group
      pid_ = -1;
      return false;
    }
    return true;
  }
  // Waits up to timeout_ms for the process (gpsfake at the end of its log) to exit; its exit code.
  std::optional<int> wait_exit(int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (running()) {
      if (std::chrono::steady_clock::now() > end) return std::nullopt;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return rc_;
  }

  void stop() {
    if (pid_ <= 0) return;
    // runuser answers SIGTERM by passing it on and then sleeping 2 s before it exits: signal the
    // processes under it instead, and it exits as soon as its child has.
    if (leader_is_runuser_) {
      for (pid_t p : group_members())
        if (p != pid_) kill(p, SIGTERM);
    } else {
      kill(-pid_, SIGTERM);
    }
    for (int i = 0; i < 150 && running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (pid_ > 0) {
      kill(-pid_, SIGKILL);
      int st = 0;
      waitpid(pid_, &st, 0);
      pid_ = -1;
    }
  }

 private:
  GpsdProcess() = default;

  // Processes in our process group (from /proc/<pid>/stat: pid (comm) state ppid pgrp ...).
  std::vector<pid_t> group_members() const {
    std::vector<pid_t> out;
    DIR* dp = opendir("/proc");
    if (dp == nullptr) return out;
    while (dirent* e = readdir(dp)) {
      const pid_t p = static_cast<pid_t>(std::atoi(e->d_name));
      if (p <= 0) continue;
      const std::string stat = read_file("/proc/" + std::string(e->d_name) + "/stat");
      const size_t rp = stat.rfind(')');
      if (rp == std::string::npos) continue;
      std::istringstream ss(stat.substr(rp + 1));
      std::string state;
      long ppid = 0, pgrp = 0;
      if (ss >> state >> ppid >> pgrp && pgrp == pid_) out.push_back(p);
    }
    closedir(dp);
    return out;
  }

  GpsdProcess failed(std::string msg) {
    error_ = std::move(msg);
    return std::move(*this);
  }

  bool make_dir() {
    char tmpl[] = "/tmp/mpgc-gpsd-XXXXXX";
    if (mkdtemp(tmpl) == nullptr) {
      error_ = std::string("mkdtemp: ") + std::strerror(errno);
      return false;
    }
    dir_ = tmpl;
    if (geteuid() == 0) chmod(dir_.c_str(), 0777);  // gpsd runs as nobody and writes its socket here
    return true;
  }

  void remove_dir() {
    if (dir_.empty()) return;
    const std::string d = std::exchange(dir_, std::string());
    // Only what the processes could have put here: our two output files and sockets.
    if (DIR* dp = opendir(d.c_str())) {
      while (dirent* e = readdir(dp)) {
        const std::string n = e->d_name;
        if (n != "." && n != "..") unlink((d + "/" + n).c_str());
      }
      closedir(dp);
    }
    rmdir(d.c_str());
  }

  // `n` consecutive free ports (TCP for the first, UDP for the rest) from a pid-derived base.
  bool pick_ports(int attempt, int n) {
    const int slots = 130;  // 29500..29889 in triples
    const int slot = (static_cast<int>(getpid()) + attempt * 37) % slots;
    port_ = 29500 + slot * 3;
    udp_.clear();
    if (!port_free(port_, true)) return fail_port(port_);
    for (int i = 1; i < n; ++i) {
      const int p = port_ + i;
      if (!port_free(p, false)) return fail_port(p);
      udp_.push_back(p);
    }
    return true;
  }
  bool fail_port(int p) {
    error_ = "port " + std::to_string(p) + " in use";
    return false;
  }

  bool spawn(const std::vector<std::string>& cmd) {
    std::vector<std::string> full;
    leader_is_runuser_ = geteuid() == 0;
    if (leader_is_runuser_) full = {find_exe("runuser"), "-u", "nobody", "--"};
    full.insert(full.end(), cmd.begin(), cmd.end());
    if (full.front().find('/') == std::string::npos) full.front() = find_exe(full.front());  // execv: no PATH
    if (full.front().empty()) {
      error_ = "runuser/env not found";
      return false;
    }
    std::vector<char*> argv;
    for (auto& a : full) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const std::string out = dir_ + "/stdout", err = dir_ + "/stderr";
    const pid_t pid = fork();
    if (pid < 0) {
      error_ = std::string("fork: ") + std::strerror(errno);
      return false;
    }
    if (pid == 0) {
      setpgid(0, 0);
      const int o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int i = open("/dev/null", O_RDONLY);
      if (o >= 0) dup2(o, 1);
      if (e >= 0) dup2(e, 2);
      if (i >= 0) dup2(i, 0);
      execv(argv[0], argv.data());
      _exit(127);
    }
    setpgid(pid, pid);  // also here: no race with the kill in stop()
    pid_ = pid;
    return true;
  }

  bool wait_listening(int timeout_ms) { return wait_bound(port_, true, timeout_ms); }

  bool wait_bound(int port, bool tcp, int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (std::chrono::steady_clock::now() < end) {
      if (!running()) {
        error_ = "exited (rc " + std::to_string(rc_) + ") before binding port " + std::to_string(port) + ": " +
                 stderr_text();
        return false;
      }
      if (port_bound(port, tcp)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    error_ = "port " + std::to_string(port) + " not bound after " + std::to_string(timeout_ms) + " ms: " + stderr_text();
    return false;
  }

  pid_t pid_ = -1;
  int port_ = 0;
  std::vector<int> udp_;
  std::string dir_;
  std::string error_;
  int rc_ = -1;
  bool leader_is_runuser_ = false;
};

// A JSON watch on gpsd's TCP port (127.0.0.1): ?WATCH={"enable":true,"json":true[,"nmea":true]}.
class GpsdWatch {
 public:
  explicit GpsdWatch(int port, bool nmea = false) {
    fd_ = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      error_ = "connect 127.0.0.1:" + std::to_string(port) + ": " + std::strerror(errno);
      close_fd();
      return;
    }
    const std::string w = std::string("?WATCH={\"enable\":true,\"json\":true") + (nmea ? ",\"nmea\":true" : "") + "};\n";
    if (send(fd_, w.data(), w.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(w.size())) {
      error_ = "send WATCH failed";
      close_fd();
    }
  }
  ~GpsdWatch() { close_fd(); }
  GpsdWatch(const GpsdWatch&) = delete;
  GpsdWatch& operator=(const GpsdWatch&) = delete;

  bool ok() const { return fd_ >= 0; }
  const std::string& error() const { return error_; }
  bool closed() const { return eof_; }

  // The next line (without CR/LF), or nullopt after timeout_ms or at end of stream.
  std::optional<std::string> line(int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    for (;;) {
      const size_t nl = buf_.find('\n');
      if (nl != std::string::npos) {
        std::string l = buf_.substr(0, nl);
        buf_.erase(0, nl + 1);
        if (!l.empty() && l.back() == '\r') l.pop_back();
        return l;
      }
      if (fd_ < 0 || eof_) return std::nullopt;
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) return std::nullopt;
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, static_cast<int>(left)) <= 0) continue;
      char tmp[4096];
      const ssize_t n = recv(fd_, tmp, sizeof tmp, 0);
      if (n <= 0) {
        eof_ = true;
        continue;
      }
      buf_.append(tmp, static_cast<size_t>(n));
    }
  }

  // Reads (and drops) lines up to gpsd's WATCH answer: only from then on does gpsd send this client
  // the reports of what arrives, so a feeder waits for it before sending.
  bool await_watch(int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    for (;;) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) return false;
      const auto l = line(static_cast<int>(left));
      if (!l) return false;
      if (l->find("\"class\":\"WATCH\"") != std::string::npos) return true;
    }
  }

  // Up to n lines within timeout_ms in all (fewer at timeout or end of stream).
  std::vector<std::string> lines(size_t n, int timeout_ms) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    std::vector<std::string> out;
    while (out.size() < n) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      auto l = line(static_cast<int>(std::max<long long>(0, left)));
      if (!l) break;
      out.push_back(std::move(*l));
    }
    return out;
  }

 private:
  void close_fd() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }
  int fd_ = -1;
  bool eof_ = false;
  std::string buf_;
  std::string error_;
};

// Datagrams to gpsd's udp:// devices, on 127.0.0.1 only.
class UdpSender {
 public:
  UdpSender() : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {}
  ~UdpSender() {
    if (fd_ >= 0) close(fd_);
  }
  UdpSender(const UdpSender&) = delete;
  UdpSender& operator=(const UdpSender&) = delete;
  // One datagram to 127.0.0.1:port (never anywhere else).
  bool send(int port, const std::string& data) const {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return sendto(fd_, data.data(), data.size(), 0, reinterpret_cast<const sockaddr*>(&a), sizeof a) ==
           static_cast<ssize_t>(data.size());
  }

 private:
  int fd_;
};

// Connects, watches and reads n JSON lines with a timeout (gpspipe -w -n N).
inline std::vector<std::string> read_json_lines(int port, size_t n, int timeout_ms, std::string* why = nullptr) {
  GpsdWatch w(port);
  if (!w.ok()) {
    if (why != nullptr) *why = w.error();
    return {};
  }
  return w.lines(n, timeout_ms);
}

// ---- gpsd's JSON lines are flat objects: a field by key, no general parser needed ----

// The raw text of "key":value (a number, true/false, or a string without its quotes).
inline std::optional<std::string> json_raw(const std::string& line, const std::string& key) {
  const std::string k = "\"" + key + "\":";
  size_t pos = line.find(k);
  if (pos == std::string::npos) return std::nullopt;
  pos += k.size();
  if (pos < line.size() && line[pos] == '"') {
    std::string s;
    for (size_t i = pos + 1; i < line.size(); ++i) {
      if (line[i] == '\\' && i + 1 < line.size()) s += line[++i];
      else if (line[i] == '"') return s;
      else s += line[i];
    }
    return std::nullopt;
  }
  const size_t end = line.find_first_of(",}", pos);
  return line.substr(pos, end == std::string::npos ? std::string::npos : end - pos);
}
inline std::optional<double> json_number(const std::string& line, const std::string& key) {
  const auto r = json_raw(line, key);
  if (!r || r->empty()) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(r->c_str(), &end);
  if (end != r->c_str() + r->size()) return std::nullopt;
  return v;
}
inline std::optional<std::string> json_string(const std::string& line, const std::string& key) {
  return json_raw(line, key);
}
inline std::string json_class(const std::string& line) { return json_raw(line, "class").value_or(""); }

// gpsd's TPV time for a UTC instant [ns]: "YYYY-MM-DDTHH:MM:SS.mmmZ".
inline std::string iso_ms(int64_t ns) {
  const time_t s = static_cast<time_t>(ns / 1000000000);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char buf[80];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ns / 1000000 % 1000));
  return buf;
}

// |a - b| of two angles in degrees (gpsd's track/heading/course against what was sent), 0..180.
inline double angle_diff(double a, double b) { return std::fabs(std::remainder(a - b, 360.0)); }

// A line gpsd 3.22 can get wrong (§5: ATT after AIS gives `,,` and `"...Z""heading"`): flat-object
// shape, no empty member, no two strings without a comma between them (`:""` is an empty value).
inline bool json_plausible(const std::string& line) {
  if (line.size() < 2 || line.front() != '{' || line.back() != '}' || line.find(",,") != std::string::npos)
    return false;
  for (size_t i = line.find("\"\""); i != std::string::npos; i = line.find("\"\"", i + 2))
    if (i == 0 || line[i - 1] != ':') return false;
  return true;
}

}  // namespace mpgc::hil

// In a gtest test body: `gpsd_var`, a gpsd reading n_udp UDP devices, and `watch_var`, a JSON watch
// on it that gpsd has answered, so what is sent from now on is reported to it. Fails the test
// with what is missing or went wrong (nothing is skipped).
#define MPGC_HIL_GPSD_WITH_WATCH(gpsd_var, watch_var, n_udp)                                           \
  ASSERT_FALSE(::mpgc::hil::find_exe("gpsd").empty()) << "gpsd is not installed: apt-get install gpsd gpsd-clients"; \
  auto gpsd_var = ::mpgc::hil::GpsdProcess::udp(n_udp);                                                \
  ASSERT_TRUE(gpsd_var.ok()) << "gpsd did not start: " << gpsd_var.error();                            \
  ::mpgc::hil::GpsdWatch watch_var(gpsd_var.port());                                                   \
  ASSERT_TRUE(watch_var.ok()) << watch_var.error();                                                    \
  ASSERT_TRUE(watch_var.await_watch(5000)) << "gpsd did not answer ?WATCH"
