#include "netns.hpp"

#include "mpgc/runtime/process.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

namespace fs = std::filesystem;

namespace mpgc::deploy {
namespace {

constexpr const char* kNetnsDir = "/run/netns";

std::string joined(const std::vector<std::string>& a) {
  std::string s;
  for (const auto& x : a) s += (s.empty() ? "" : " ") + x;
  return s;
}

void must(const std::vector<std::string>& argv) {
  std::string out;
  const int rc = run_command(argv, &out);
  if (rc != 0) throw std::runtime_error("network lab: '" + joined(argv) + "' failed (" + std::to_string(rc) + "): " + out);
}

// Namespaces of labs whose process is gone ("mpgc<pid>-<host>").
void remove_stale_labs() {
  std::error_code ec;
  if (!fs::is_directory(kNetnsDir, ec)) return;
  for (const auto& e : fs::directory_iterator(kNetnsDir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("mpgc", 0) != 0) continue;
    const auto dash = n.find('-');
    if (dash == std::string::npos || dash == 4) continue;
    const std::string pid = n.substr(4, dash - 4);
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    if (!fs::exists("/proc/" + pid)) run_command({"ip", "netns", "del", n});
  }
}

// IPv6 off before any interface exists: no router solicitations or MLD reports, so every packet
// on the links is the deployment's own IPv4 (and ARP).
void without_ipv6(const std::string& ns) {
  for (const char* k : {"all", "default"})
    must({"ip", "netns", "exec", ns, "sh", "-c", std::string("echo 1 > /proc/sys/net/ipv6/conf/") + k + "/disable_ipv6"});
}

}  // namespace

bool NetnsLab::available() { return geteuid() == 0 && run_command({"ip", "netns", "list"}) == 0; }

NetnsLab::NetnsLab(const Deployment& d, const LabOptions& o) : d_(d), prefix_("mpgc" + std::to_string(getpid()) + "-") {
  if (geteuid() != 0) throw std::runtime_error("network lab: network namespaces need root");
  for (const auto& [host, link] : o.links)
    if (link.impaired() && o.netem_exe.empty()) throw std::runtime_error("network lab: an impaired link needs mpgc_netem");
  remove_stale_labs();
  try {
    const std::string br = prefix_ + "br";
    must({"ip", "netns", "add", br});
    created_.push_back(br);
    without_ipv6(br);
    // No multicast snooping: the bridge would send IGMP queries and reports of its own.
    must({"ip", "-n", br, "link", "add", "br0", "type", "bridge", "mcast_snooping", "0"});
    must({"ip", "-n", br, "link", "set", "br0", "up"});
    for (size_t i = 0; i < d_.hosts.size(); ++i) {
      const Host& h = d_.hosts[i];
      const std::string n = prefix_ + h.name, port = "p" + std::to_string(i);
      must({"ip", "netns", "add", n});
      created_.push_back(n);
      ns_[h.name] = n;
      without_ipv6(n);
      // The veth is made inside the namespaces, never in this one; it keeps the host's real name.
      must({"ip", "-n", n, "link", "add", h.interface, "type", "veth", "peer", "name", port, "netns", br});
      must({"ip", "-n", br, "link", "set", port, "master", "br0", "up"});
      must({"ip", "-n", n, "addr", "add", h.address + "/" + std::to_string(d_.prefix), "dev", h.interface});
      must({"ip", "-n", n, "link", "set", h.interface, "up"});
      must({"ip", "-n", n, "link", "set", "lo", "up"});
    }
    for (size_t i = 0; i < d_.hosts.size(); ++i) {
      const Host& h = d_.hosts[i];
      const std::string& n = ns_[h.name];
      if (!o.capture_dir.empty()) {
        // -U: written packet by packet, so a capture stopped by SIGTERM is complete.
        start_helper(h.name, "tcpdump",
                     {"ip", "netns", "exec", n, "tcpdump", "-i", "any", "-n", "-U", "-w", o.capture_dir + "/" + h.name + ".pcap"},
                     o.capture_dir + "/tcpdump-" + h.name + ".log");
      }
      const auto li = o.links.find(h.name);
      const LinkSpec link = li != o.links.end() ? li->second : LinkSpec{};
      if (link.impaired()) {
        must({"ip", "netns", "exec", n, "iptables", "-A", "OUTPUT", "-o", h.interface, "-j", "NFQUEUE", "--queue-num", "0",
              "--queue-bypass"});
        std::vector<std::string> a = {"ip", "netns", "exec", n, o.netem_exe, "--queue", "0",
                                      "--delay-ms", std::to_string(link.delay_ms), "--loss", std::to_string(link.loss_pct),
                                      "--seed", std::to_string(o.seed + i)};
        if (link.jitter_ms > 0) a.insert(a.end(), {"--jitter-ms", std::to_string(link.jitter_ms)});
        start_helper(h.name, "netem", a, o.log_dir.empty() ? "" : o.log_dir + "/netem-" + h.name + ".log");
      }
    }
    // tcpdump and netem take a moment to attach; packets before that would go uncaptured/undelayed.
    if (!helpers_.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(700));
    for (const auto& hp : helpers_) {
      int status = 0;
      if (waitpid(hp.pid, &status, WNOHANG) == hp.pid) {
        std::ifstream in(hp.log);
        std::stringstream ss;
        ss << in.rdbuf();
        throw std::runtime_error("network lab: " + hp.what + " on " + hp.host + " exited at once: " + ss.str());
      }
    }
  } catch (...) {
    stop_helpers();
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) run_command({"ip", "netns", "del", *it});
    throw;
  }
}

NetnsLab::~NetnsLab() {
  stop_helpers();
  for (auto it = created_.rbegin(); it != created_.rend(); ++it) run_command({"ip", "netns", "del", *it});
}

void NetnsLab::start_helper(const std::string& host, const std::string& what, const std::vector<std::string>& argv,
                            const std::string& log) {
  helpers_.push_back({host, what, rt::spawn_logged(argv, log), log});
}

std::map<std::string, std::string> NetnsLab::stop_helpers() {
  std::map<std::string, std::string> summary;
  for (auto& h : helpers_) {
    if (h.pid <= 0) continue;
    kill(-h.pid, SIGTERM);
    int status = 0;
    for (int i = 0; i < 50 && waitpid(h.pid, &status, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (waitpid(h.pid, &status, WNOHANG) == 0) {
      kill(-h.pid, SIGKILL);
      waitpid(h.pid, &status, 0);
    }
    h.pid = -1;
    if (h.what == "netem" && !h.log.empty()) {
      std::ifstream in(h.log);
      std::string line, last;
      while (std::getline(in, line))
        if (line.rfind("netem:", 0) == 0) last = line;
      summary[h.host] = last;
    }
  }
  return summary;
}

const std::string& NetnsLab::ns(const std::string& host) const {
  const auto it = ns_.find(host);
  if (it == ns_.end()) throw std::invalid_argument("network lab: no host '" + host + "'");
  return it->second;
}

void NetnsLab::enter(const std::string& host) const {
  const std::string path = std::string(kNetnsDir) + "/" + ns(host);
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0 || setns(fd, CLONE_NEWNET) != 0) {
    const std::string e = std::strerror(errno);
    if (fd >= 0) close(fd);
    throw std::runtime_error("network lab: cannot enter " + path + ": " + e);
  }
  close(fd);
}

void NetnsLab::set_cut(const std::string& host, bool cut) {
  if (cut_[host] == cut) return;
  const Host* h = d_.host(host);
  if (h == nullptr) throw std::invalid_argument("network lab: no host '" + host + "' to cut");
  const std::string& n = ns(host);
  // First in each chain, ahead of netem's queue, so nothing leaves or arrives while cut.
  if (cut) {
    must({"ip", "netns", "exec", n, "iptables", "-I", "OUTPUT", "1", "-o", h->interface, "-j", "DROP"});
    must({"ip", "netns", "exec", n, "iptables", "-I", "INPUT", "1", "-i", h->interface, "-j", "DROP"});
  } else {
    must({"ip", "netns", "exec", n, "iptables", "-D", "OUTPUT", "-o", h->interface, "-j", "DROP"});
    must({"ip", "netns", "exec", n, "iptables", "-D", "INPUT", "-i", h->interface, "-j", "DROP"});
  }
  cut_[host] = cut;
}

}  // namespace mpgc::deploy
