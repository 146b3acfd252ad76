// A deployment description (deploy/hosts/*.yaml): the hosts of a ship's network, which components
// run on each, and the network's properties; and what is generated from it for every host — its
// Cyclone DDS configuration, its launch file, the systemd units. Parsed and validated in one place.
// No DDS, no clock: text in, text out.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace mpgc::deploy {

// The emulated or expected properties of a host's link (applied on its egress in the tests).
struct LinkSpec {
  double loss_pct = 0.0;   // [%] packets dropped
  double delay_ms = 0.0;   // [ms] one-way delay added
  double jitter_ms = 0.0;  // [ms] uniform extra delay in [0, jitter]
  bool impaired() const { return loss_pct > 0.0 || delay_ms > 0.0 || jitter_ms > 0.0; }
  std::string text() const;  // "loss 20% delay 50ms"
};

// "loss 20% delay 50ms [jitter 5ms]" (any order, each at most once). Throws naming the bad word.
LinkSpec parse_link(const std::string& spec);

// A link cut: HOST@T+D, T in simulated seconds from the start, D in wall-clock seconds (the
// network knows no simulated time; in lockstep the simulated clock stands still while it lasts).
struct LinkCut {
  std::string host;
  double at_s = 0.0;        // [s] simulated
  double duration_s = 0.0;  // [s] wall clock
};
LinkCut parse_cut(const std::string& spec);

struct Host {
  std::string name;       // [a-z0-9-], also the network namespace's suffix in tests
  std::string address;    // IPv4, inside the network's subnet
  std::string interface;  // the host's interface on the ship's network (eth0 in the namespaces too)
  std::vector<std::string> components;
  LinkSpec link;          // its egress (the network's link unless the host gives its own)
};

struct Deployment {
  std::string name;
  std::string origin;              // file it came from (for messages)
  std::string subnet;              // a.b.c.d/prefix
  int prefix = 24;
  double spdp_interval_s = 1.0;    // [s] discovery resend: 1 s holds up under loss (deployment note)
  double lease_duration_s = 10.0;  // [s] a participant silent this long is dropped
  LinkSpec link;                   // every host's link unless it gives its own
  std::vector<Host> hosts;

  const Host* host(const std::string& name) const;
  const Host* host_of(const std::string& component) const;  // nullptr: not deployed
};

// Each host's link after command-line overrides: "SPEC" for every host, "HOST: SPEC" for one
// (later ones win). Throws naming an unknown host or a bad spec.
std::map<std::string, LinkSpec> host_links(const Deployment& d, const std::vector<std::string>& overrides);

// The components a deployment may place (scenario_runner: the evaluator of mpgc_run).
const std::vector<std::string>& known_components();

// Throws std::runtime_error naming the file, line and field of any problem.
Deployment load(const std::string& path);
Deployment parse(const std::string& yaml, const std::string& origin);

// The host's Cyclone DDS configuration: its interface only, multicast off, every host a unicast
// peer, discovery settings for a lossy link.
std::string cyclone_config(const Deployment& d, const Host& h);

struct LaunchOptions {
  std::string bin_dir = "/opt/mpgc/bin";     // executables
  std::string params_dir = "/etc/mpgc/params"; // <component>.yaml, when present
  std::string cyclone_uri = "file:///etc/mpgc/cyclonedds.xml";
  std::string security_dir;  // non-empty: DDS Security from <dir>/security.xml (deploy/security)
  std::string full_cyclone_uri() const;  // the network file, then security when enabled
};
// The host's launch file for mpgc_launch: its components on the wall clock, restarted always.
std::string host_launch(const Deployment& d, const Host& h, const LaunchOptions& o);

// One systemd unit per component, the same on every host (what differs lives in /etc/mpgc/).
std::string systemd_unit(const std::string& component, const LaunchOptions& o);
std::string systemd_target();

}  // namespace mpgc::deploy
