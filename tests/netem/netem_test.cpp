// mpgc_netem on a real link: two network namespaces A and B joined by a veth pair on a subnet
// that exists only inside them, the NFQUEUE rule on A's egress, mpgc_netem bound to it in A.
// UDP datagrams, sent by this process through sockets created inside A and inside B (setns), carry
// their send time: both ends read the same monotonic clock, so the one-way delay is exact. Nothing
// is sent outside the namespaces (they hold only lo and the veth ends).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "link_model.hpp"
#include "mpgc/testing.hpp"

namespace {

constexpr std::int64_t kMs = 1000000;

std::int64_t now_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

int sh(const std::string& cmd) {
  const int status = std::system((cmd + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string netem_bin() { return mpgc::testing::bin_dir() + "/mpgc_netem"; }

// Namespaces A and B, the veth created inside A with its peer inside B (never in the root
// namespace); removed when destroyed, whatever the test did.
class TwoHosts {
 public:
  TwoHosts() {
    const std::string id = std::to_string(getpid() % 100000);
    a = "mpgcNetemA" + id;
    b = "mpgcNetemB" + id;
    ia = "nta" + id;
    ib = "ntb" + id;
    subnet = "10.79." + std::to_string(getpid() % 250 + 1);
    ok_ = sh("ip netns add " + a) == 0 && sh("ip netns add " + b) == 0 &&
          sh("ip -n " + a + " link add " + ia + " type veth peer name " + ib + " netns " + b) == 0 &&
          sh("ip -n " + a + " addr add " + subnet + ".1/24 dev " + ia) == 0 &&
          sh("ip -n " + b + " addr add " + subnet + ".2/24 dev " + ib) == 0 &&
          sh("ip -n " + a + " link set lo up") == 0 && sh("ip -n " + b + " link set lo up") == 0 &&
          sh("ip -n " + a + " link set " + ia + " up") == 0 && sh("ip -n " + b + " link set " + ib + " up") == 0;
  }
  ~TwoHosts() {
    sh("ip netns del " + a);  // the veth pair and the iptables rule go with the namespaces
    sh("ip netns del " + b);
  }
  bool ok() const { return ok_; }
  std::string a, b, ia, ib, subnet;

 private:
  bool ok_ = false;
};

// A UDP socket created inside namespace `ns` (it stays there), bound to addr:port.
int udp_socket_in(const std::string& ns, const std::string& addr, int port) {
  const int self = open("/proc/self/ns/net", O_RDONLY | O_CLOEXEC);
  const int target = open(("/run/netns/" + ns).c_str(), O_RDONLY | O_CLOEXEC);
  int s = -1;
  if (self >= 0 && target >= 0 && setns(target, CLONE_NEWNET) == 0) {
    s = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(static_cast<std::uint16_t>(port));
    inet_pton(AF_INET, addr.c_str(), &sa.sin_addr);
    if (s >= 0 && bind(s, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0) {
      close(s);
      s = -1;
    }
    if (setns(self, CLONE_NEWNET) != 0) std::abort();  // never go on in the wrong namespace
  }
  if (self >= 0) close(self);
  if (target >= 0) close(target);
  return s;
}

// mpgc_netem run inside a namespace; stdout and stderr on pipes; SIGKILLed if still running at the end.
class Netem {
 public:
  Netem(const std::string& ns, const std::vector<std::string>& args) {
    int out[2], err[2];
    if (pipe2(out, O_CLOEXEC) != 0 || pipe2(err, O_CLOEXEC) != 0) return;
    const int nsfd = ns.empty() ? -1 : open(("/run/netns/" + ns).c_str(), O_RDONLY | O_CLOEXEC);
    std::vector<std::string> argv_s = {netem_bin()};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      if ((nsfd >= 0 && setns(nsfd, CLONE_NEWNET) != 0) || dup2(out[1], 1) < 0 || dup2(err[1], 2) < 0) _exit(127);
      execv(argv[0], argv.data());
      _exit(127);
    }
    if (nsfd >= 0) close(nsfd);
    close(out[1]);
    close(err[1]);
    out_ = out[0];
    err_ = err[0];
  }
  ~Netem() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    if (out_ >= 0) close(out_);
    if (err_ >= 0) close(err_);
  }
  // The next line on stdout (false: stderr) within `timeout_ms`, or nullopt.
  std::optional<std::string> line(bool on_stdout, int timeout_ms) {
    std::string& buf = on_stdout ? out_buf_ : err_buf_;
    const int fd = on_stdout ? out_ : err_;
    const std::int64_t end = now_ns() + timeout_ms * kMs;
    for (;;) {
      if (const auto nl = buf.find('\n'); nl != std::string::npos) {
        std::string l = buf.substr(0, nl);
        buf.erase(0, nl + 1);
        return l;
      }
      const std::int64_t left = end - now_ns();
      if (left <= 0) return std::nullopt;
      pollfd p{fd, POLLIN, 0};
      if (poll(&p, 1, static_cast<int>(left / kMs) + 1) <= 0) continue;
      char tmp[4096];
      const ssize_t n = read(fd, tmp, sizeof tmp);
      if (n <= 0) return std::nullopt;  // EOF: the process is gone
      buf.append(tmp, static_cast<std::size_t>(n));
    }
  }
  bool signal(int sig) const { return pid_ > 0 && kill(pid_, sig) == 0; }
  // Waits up to timeout_ms for the exit; its exit code, or -1.
  int wait(int timeout_ms) {
    for (std::int64_t end = now_ns() + timeout_ms * kMs; pid_ > 0 && now_ns() < end;) {
      int st = 0;
      if (waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
      }
      usleep(5000);
    }
    return -1;
  }
  std::string rest_of_stderr() {
    std::string all;
    while (auto l = line(false, 200)) all += *l + "\n";
    return all + err_buf_;
  }

 private:
  pid_t pid_ = -1;
  int out_ = -1, err_ = -1;
  std::string out_buf_, err_buf_;
};

struct Summary {
  long passed = -1, dropped = -1, overflow = -1, errors = -1;
  double pct = -1, mean = -1, max = -1;
};
std::optional<Summary> parse_summary(const std::string& l, int queue) {
  Summary s;
  int q = -1;
  if (std::sscanf(l.c_str(), "netem: queue %d passed %ld dropped %ld (%lf%%) delayed mean %lf ms max %lf ms overflow %ld errors %ld",
                  &q, &s.passed, &s.dropped, &s.pct, &s.mean, &s.max, &s.overflow, &s.errors) != 8 ||
      q != queue)
    return std::nullopt;
  return s;
}

// One direction of datagrams: sent on `tx` to `to`, received on `rx`. Payload: seq, send time.
struct Flow {
  int tx, rx;
  sockaddr_in to;
  std::uint32_t next_seq = 0;
  std::map<std::uint32_t, double> delay_ms;  // received: seq -> one-way delay

  void send() {
    std::int64_t msg[2] = {next_seq++, now_ns()};
    sendto(tx, msg, sizeof msg, 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  }
  void drain() {
    std::int64_t msg[2];
    while (recv(rx, msg, sizeof msg, MSG_DONTWAIT) == static_cast<ssize_t>(sizeof msg))
      delay_ms[static_cast<std::uint32_t>(msg[0])] = static_cast<double>(now_ns() - msg[1]) / 1e6;
  }
  // Delays of the datagrams seq in [from, to) that arrived, sorted.
  std::vector<double> delays(std::uint32_t from, std::uint32_t until) const {
    std::vector<double> d;
    for (auto it = delay_ms.lower_bound(from); it != delay_ms.end() && it->first < until; ++it) d.push_back(it->second);
    std::sort(d.begin(), d.end());
    return d;
  }
  std::set<std::uint32_t> lost(std::uint32_t from, std::uint32_t until) const {
    std::set<std::uint32_t> l;
    for (std::uint32_t s = from; s < until; ++s)
      if (!delay_ms.count(s)) l.insert(s);
    return l;
  }
};

sockaddr_in address(const std::string& ip, int port) {
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, ip.c_str(), &sa.sin_addr);
  return sa;
}

// Sends `count` datagrams on every flow, one per `period_ns`, receiving in between; then receives
// for `drain_ns` more.
void exchange(std::vector<Flow*> flows, int count, std::int64_t period_ns, std::int64_t drain_ns) {
  std::vector<pollfd> fds;
  for (Flow* f : flows) fds.push_back({f->rx, POLLIN, 0});
  const std::int64_t start = now_ns();
  const std::int64_t end = start + (count - 1) * period_ns + drain_ns;
  int sent = 0;
  for (;;) {
    const std::int64_t now = now_ns();
    if (sent < count && now >= start + sent * period_ns) {
      for (Flow* f : flows) f->send();
      ++sent;
      continue;
    }
    if (sent == count && now >= end) break;
    const std::int64_t wake = sent < count ? start + sent * period_ns : end;
    timespec ts{(wake - now) / 1000000000, (wake - now) % 1000000000};
    ppoll(fds.data(), fds.size(), &ts, nullptr);
    for (Flow* f : flows) f->drain();
  }
  for (Flow* f : flows) f->drain();
}

double median(const std::vector<double>& sorted) { return sorted.empty() ? -1 : sorted[sorted.size() / 2]; }

std::string figures(const char* what, std::size_t sent, const std::vector<double>& d) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s: %zu sent, %zu received (%.1f%% lost), delay min %.2f median %.2f max %.2f ms", what,
                sent, d.size(), 100.0 * static_cast<double>(sent - d.size()) / static_cast<double>(sent),
                d.empty() ? -1 : d.front(), median(d), d.empty() ? -1 : d.back());
  return buf;
}

}  // namespace

// mpgc_netem --delay-ms 50 --loss 20 --seed 7 on A's egress. Criteria, from those options:
//  - A->B, 350 datagrams at 50 Hz: the lost ones are exactly those LinkModel(seed 7) drops (the
//    datagrams are the only IPv4 packets leaving A, so the queue sees them in sending order), and
//    the loss is within 20 % +- 8 points (12..28 %: +-3.7 binomial standard deviations for 350);
//    every one that arrives took >= 50 ms (held 50 ms after it reached the queue), median < 80 ms
//    (50 ms + scheduling on two shared cores);
//  - B->A at the same time (no rule on B): 0 lost, median < 5 ms;
//  - SIGUSR1: the summary line, the process goes on; a second mpgc_netem on the same queue: exit 1;
//  - SIGTERM right after a burst still held: every datagram it would pass arrives (no black hole),
//    the summary counts every packet, exit 0;
//  - after it stopped (the rule stays, --queue-bypass): 0 lost, median < 5 ms.
TEST(Netem, DelayAndSeededLossOnOneNamespaceEgress) {
  if (geteuid() != 0) GTEST_SKIP() << "network namespaces and NFQUEUE need root (CI runs as root)";
  ASSERT_EQ(access(netem_bin().c_str(), X_OK), 0) << netem_bin() << " not built";
  TwoHosts hosts;
  ASSERT_TRUE(hosts.ok()) << "could not create the network namespaces (ip netns)";
  ASSERT_EQ(sh("ip netns exec " + hosts.a + " iptables -A OUTPUT -o " + hosts.ia +
               " -j NFQUEUE --queue-num 0 --queue-bypass"),
            0);
  const std::string ip_a = hosts.subnet + ".1", ip_b = hosts.subnet + ".2";
  const int port = 47000;
  Flow ab{udp_socket_in(hosts.a, ip_a, 0), udp_socket_in(hosts.b, ip_b, port), address(ip_b, port)};
  Flow ba{udp_socket_in(hosts.b, ip_b, 0), udp_socket_in(hosts.a, ip_a, port), address(ip_a, port)};
  ASSERT_TRUE(ab.tx >= 0 && ab.rx >= 0 && ba.tx >= 0 && ba.rx >= 0) << "sockets in the namespaces";

  const std::uint64_t seed = 7;
  Netem netem(hosts.a, {"--queue", "0", "--delay-ms", "50", "--loss", "20", "--seed", std::to_string(seed)});
  const auto ready = netem.line(false, 5000);
  ASSERT_TRUE(ready && ready->find("netem: queue 0 bound") == 0) << (ready ? *ready : netem.rest_of_stderr());

  {  // the queue is taken: a second one says so and exits 1
    Netem second(hosts.a, {"--queue", "0", "--delay-ms", "1", "--loss", "0", "--seed", "1"});
    EXPECT_EQ(second.wait(5000), 1);
    EXPECT_NE(second.rest_of_stderr().find("cannot bind NFQUEUE 0"), std::string::npos);
  }

  // What the link must do with the datagrams 0..369 (queue packets 1..370), from the seed alone.
  mpgc::netem::LinkModel model(50, 0, 20, seed);
  std::set<std::uint32_t> predicted_lost;
  for (std::uint32_t s = 0; s < 370; ++s)
    if (model.on_packet(s + 1, 0)) predicted_lost.insert(s);
  const auto predicted_in = [&](std::uint32_t from, std::uint32_t until) {
    return std::set<std::uint32_t>(predicted_lost.lower_bound(from), predicted_lost.lower_bound(until));
  };

  const int n = 350;
  exchange({&ab, &ba}, n, 20 * kMs, 400 * kMs);
  const auto d_ab = ab.delays(0, n), d_ba = ba.delays(0, n);
  const double loss = 100.0 * static_cast<double>(n - static_cast<int>(d_ab.size())) / n;
  std::printf("[ figures  ] %s\n[ figures  ] %s\n", figures("A->B netem 50 ms 20 %", n, d_ab).c_str(),
              figures("B->A no rule", n, d_ba).c_str());
  RecordProperty("ab_loss_pct", std::to_string(loss));
  RecordProperty("ab_delay_median_ms", std::to_string(median(d_ab)));
  EXPECT_EQ(ab.lost(0, n), predicted_in(0, n)) << "the seed's decisions, packet for packet";
  EXPECT_GE(loss, 12.0);
  EXPECT_LE(loss, 28.0);
  ASSERT_FALSE(d_ab.empty());
  EXPECT_GE(d_ab.front(), 50.0);
  EXPECT_LT(median(d_ab), 80.0);
  EXPECT_EQ(d_ba.size(), static_cast<std::size_t>(n));
  EXPECT_LT(median(d_ba), 5.0);

  ASSERT_TRUE(netem.signal(SIGUSR1));
  const auto usr1 = netem.line(true, 3000);
  ASSERT_TRUE(usr1) << netem.rest_of_stderr();
  std::printf("[ figures  ] SIGUSR1: %s\n", usr1->c_str());
  const auto s1 = parse_summary(*usr1, 0);
  ASSERT_TRUE(s1) << *usr1;
  EXPECT_EQ(s1->passed, n - static_cast<long>(predicted_in(0, n).size()));
  EXPECT_EQ(s1->dropped, static_cast<long>(predicted_in(0, n).size()));
  EXPECT_EQ(s1->overflow + s1->errors, 0);
  EXPECT_GE(s1->mean, 50.0);

  // A burst of 20 in 10 ms, then SIGTERM while all of it is still held (50 ms).
  for (int i = 0; i < 20; ++i) {
    ab.send();
    usleep(500);
  }
  ASSERT_TRUE(netem.signal(SIGTERM));
  const auto last = netem.line(true, 3000);
  EXPECT_EQ(netem.wait(3000), 0);
  ASSERT_TRUE(last) << netem.rest_of_stderr();
  std::printf("[ figures  ] SIGTERM: %s\n", last->c_str());
  exchange({&ab}, 0, 20 * kMs, 300 * kMs);
  EXPECT_EQ(ab.lost(n, n + 20), predicted_in(n, n + 20)) << "held packets must be accepted at exit";
  const auto s2 = parse_summary(*last, 0);
  ASSERT_TRUE(s2) << *last;
  EXPECT_EQ(s2->passed + s2->dropped, n + 20);
  EXPECT_EQ(s2->dropped, static_cast<long>(predicted_in(0, n + 20).size()));

  // netem gone: the rule stays and --queue-bypass lets everything through at once.
  const std::uint32_t from = ab.next_seq;
  exchange({&ab}, 100, 10 * kMs, 200 * kMs);
  const auto d_after = ab.delays(from, from + 100);
  std::printf("[ figures  ] %s\n", figures("A->B after netem stopped", 100, d_after).c_str());
  EXPECT_EQ(d_after.size(), 100u);
  EXPECT_LT(median(d_after), 5.0);
  for (int fd : {ab.tx, ab.rx, ba.tx, ba.rx}) close(fd);
}

// Bad options: a clear message naming the option and its unit, exit 2 (no root needed).
TEST(Netem, BadOptionsExitTwo) {
  ASSERT_EQ(access(netem_bin().c_str(), X_OK), 0) << netem_bin() << " not built";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--queue", "0", "--delay-ms", "50", "--loss", "120", "--seed", "1"}, "--loss"},
      {{"--queue", "0", "--delay-ms", "50ms", "--loss", "20", "--seed", "1"}, "milli"},
      {{"--queue", "70000", "--delay-ms", "50", "--loss", "20", "--seed", "1"}, "--queue"},
      {{"--queue", "0", "--delay-ms", "50", "--loss", "20"}, "--seed"},
      {{"--bogus"}, "--bogus"},
  };
  for (const auto& [args, expect] : cases) {
    Netem p("", args);
    EXPECT_EQ(p.wait(5000), 2) << args[0];
    const std::string err = p.rest_of_stderr();
    EXPECT_NE(err.find(expect), std::string::npos) << err;
    EXPECT_NE(err.find("usage: mpgc_netem"), std::string::npos) << err;
  }
  Netem help("", {"--help"});
  EXPECT_EQ(help.wait(5000), 0);
  const auto first = help.line(true, 1000);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->rfind("usage: mpgc_netem", 0), 0u) << *first;
}
