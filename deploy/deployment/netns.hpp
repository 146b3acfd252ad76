// A deployment's hosts as Linux network namespaces on one machine, for tests and `mpgc_run
// --hosts`: one namespace per host with its interface (named as on the real host) on a bridge in
// a namespace of its own, addresses on the deployment's subnet, which exists only inside them.
// Loss and delay on a host's egress through mpgc_netem (this kernel has no netem), link cuts by
// iptables, packet captures by tcpdump. Everything is removed when the lab is destroyed; labs
// left behind by a dead process are removed by the next one. Needs root.
#pragma once

#include "mpgc/runtime/process.hpp"

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "deployment.hpp"

namespace mpgc::deploy {

struct LabOptions {
  std::map<std::string, LinkSpec> links;  // per host, on its egress (host_links); absent = clean
  uint64_t seed = 1;            // netem's loss and jitter draws (host i uses seed + i)
  std::string netem_exe;        // mpgc_netem; required when a link is impaired
  std::string capture_dir;      // non-empty: tcpdump of every host's namespace to <dir>/<host>.pcap
  std::string log_dir;          // netem's output goes to <dir>/netem-<host>.log
};

class NetnsLab {
 public:
  NetnsLab(const Deployment& d, const LabOptions& o);  // throws naming the command that failed
  ~NetnsLab();
  NetnsLab(const NetnsLab&) = delete;
  NetnsLab& operator=(const NetnsLab&) = delete;

  const std::string& ns(const std::string& host) const;  // namespace of a host
  // Moves the calling thread (and the threads it starts later) into a host's namespace.
  void enter(const std::string& host) const;
  // Cuts a host off the network (every packet in and out of its interface dropped) or restores it.
  void set_cut(const std::string& host, bool cut);
  // Stops netem and tcpdump (flushing the captures); returns netem's summary line per host.
  std::map<std::string, std::string> stop_helpers();

  static bool available();  // root and `ip netns` work

 private:
  struct Helper {
    std::string host, what;
    pid_t pid = -1;
    std::string log;
  };
  void start_helper(const std::string& host, const std::string& what, const std::vector<std::string>& argv,
                    const std::string& log);
  Deployment d_;
  std::string prefix_;
  std::map<std::string, std::string> ns_;
  std::vector<std::string> created_;
  std::vector<Helper> helpers_;
  std::map<std::string, bool> cut_;
};

// Runs a command (no shell): mpgc::rt::run_command, named here for the lab's users.
using rt::run_command;

}  // namespace mpgc::deploy
