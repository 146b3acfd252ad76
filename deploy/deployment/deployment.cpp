#include "deployment.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "mpgc/yaml/fields.hpp"

namespace mpgc::deploy {
namespace {

using mpgc::yaml::fail;
using mpgc::yaml::get;
using mpgc::yaml::only_keys;

uint32_t ipv4(const std::string& s) {
  in_addr a{};
  if (inet_pton(AF_INET, s.c_str(), &a) != 1) throw std::invalid_argument("'" + s + "' is not an IPv4 address");
  return ntohl(a.s_addr);
}

// std::stod of a string the caller's regex made all digits: too many of them (1e310) throw
// std::out_of_range, which is the caller's documented std::invalid_argument here.
double decimal(const std::string& digits, const std::string& what) {
  try {
    return std::stod(digits);
  } catch (const std::out_of_range&) {
    throw std::invalid_argument(what + ": the number is out of range");
  }
}

double number_with_unit(const std::string& word, const std::string& unit, const std::string& what) {
  static const std::regex re(R"(^([0-9]+(\.[0-9]+)?)([a-z%]*)$)");
  std::smatch m;
  if (!std::regex_match(word, m, re) || m[3].str() != unit)
    throw std::invalid_argument(what + " '" + word + "' is not a number in " + unit);
  return decimal(m[1].str(), what + " '" + word + "'");
}

std::string num(double v) {
  std::ostringstream o;
  o << v;
  return o.str();
}

}  // namespace

std::string LaunchOptions::full_cyclone_uri() const {
  return security_dir.empty() ? cyclone_uri : cyclone_uri + ",file://" + security_dir + "/security.xml";
}

std::string LinkSpec::text() const {
  std::string s;
  if (loss_pct > 0) s += "loss " + num(loss_pct) + "%";
  if (delay_ms > 0) s += (s.empty() ? "" : " ") + std::string("delay ") + num(delay_ms) + "ms";
  if (jitter_ms > 0) s += (s.empty() ? "" : " ") + std::string("jitter ") + num(jitter_ms) + "ms";
  return s.empty() ? "clean" : s;
}

LinkSpec parse_link(const std::string& spec) {
  std::istringstream in(spec);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  LinkSpec l;
  std::set<std::string> seen;
  if (w.size() % 2 != 0) throw std::invalid_argument("link '" + spec + "': expected pairs like 'loss 20% delay 50ms'");
  for (size_t i = 0; i < w.size(); i += 2) {
    if (!seen.insert(w[i]).second) throw std::invalid_argument("link '" + spec + "': '" + w[i] + "' given twice");
    if (w[i] == "loss") l.loss_pct = number_with_unit(w[i + 1], "%", "loss");
    else if (w[i] == "delay") l.delay_ms = number_with_unit(w[i + 1], "ms", "delay");
    else if (w[i] == "jitter") l.jitter_ms = number_with_unit(w[i + 1], "ms", "jitter");
    else throw std::invalid_argument("link '" + spec + "': unknown property '" + w[i] + "' (loss, delay, jitter)");
  }
  if (l.loss_pct >= 100.0) throw std::invalid_argument("link '" + spec + "': loss must be below 100% (a cut is --cut)");
  if (l.delay_ms > 10000.0 || l.jitter_ms > 10000.0) throw std::invalid_argument("link '" + spec + "': delay and jitter at most 10000ms");
  return l;
}

LinkCut parse_cut(const std::string& spec) {
  static const std::regex re(R"(^([a-z0-9][a-z0-9-]*)@([0-9]+(\.[0-9]+)?)\+([0-9]+(\.[0-9]+)?)$)");
  std::smatch m;
  if (!std::regex_match(spec, m, re))
    throw std::invalid_argument("cut '" + spec + "': expected HOST@T+D (T simulated seconds, D wall seconds), e.g. autonomy@600+5");
  LinkCut c{m[1].str(), decimal(m[2].str(), "cut '" + spec + "'"), decimal(m[4].str(), "cut '" + spec + "'")};
  if (c.duration_s <= 0.0 || c.duration_s > 3600.0) throw std::invalid_argument("cut '" + spec + "': D must be in (0, 3600] s");
  return c;
}

std::map<std::string, LinkSpec> host_links(const Deployment& d, const std::vector<std::string>& overrides) {
  std::map<std::string, LinkSpec> links;
  for (const auto& h : d.hosts) links[h.name] = h.link;
  static const std::regex one_host(R"(^\s*([a-z0-9][a-z0-9-]*)\s*:(.*)$)");
  for (const auto& o : overrides) {
    std::smatch m;
    if (std::regex_match(o, m, one_host)) {
      if (!d.host(m[1].str())) throw std::invalid_argument("link '" + o + "': no host '" + m[1].str() + "' in " + d.origin);
      links[m[1].str()] = parse_link(m[2].str());
    } else {
      const LinkSpec l = parse_link(o);
      for (auto& [name, link] : links) link = l;
    }
  }
  return links;
}

const std::vector<std::string>& known_components() {
  static const std::vector<std::string> k{"ship_simulator",  "ship_bridge", "situational_awareness", "obstacle_manager",
                                          "opp",             "guidance_control", "scenario_runner"};
  return k;
}

const Host* Deployment::host(const std::string& n) const {
  for (const auto& h : hosts)
    if (h.name == n) return &h;
  return nullptr;
}

const Host* Deployment::host_of(const std::string& component) const {
  for (const auto& h : hosts)
    if (std::find(h.components.begin(), h.components.end(), component) != h.components.end()) return &h;
  return nullptr;
}

Deployment parse(const std::string& yaml, const std::string& origin) {
  const YAML::Node root = mpgc::yaml::load(yaml, origin);
  if (!root.IsMap()) throw std::runtime_error(origin + ": a deployment is a mapping with 'network' and 'hosts'");
  only_keys(origin, root, {"name", "network", "hosts"}, "the deployment");
  Deployment d;
  d.origin = origin;
  d.name = root["name"] ? get<std::string>(origin, root["name"], "name") : "deployment";

  const YAML::Node net = root["network"];
  if (!net) throw std::runtime_error(origin + ": no 'network'");
  only_keys(origin, net, {"subnet", "spdp_interval", "lease_duration", "link"}, "network");
  if (!net["subnet"]) fail(origin, net, "network has no 'subnet' (a.b.c.d/prefix)");
  d.subnet = get<std::string>(origin, net["subnet"], "subnet");
  uint32_t base = 0, mask = 0;
  {
    const auto slash = d.subnet.find('/');
    try {
      if (slash == std::string::npos) throw std::invalid_argument("no prefix length");
      d.prefix = std::stoi(d.subnet.substr(slash + 1));
      if (d.prefix < 8 || d.prefix > 30) throw std::invalid_argument("prefix length must be in [8, 30]");
      base = ipv4(d.subnet.substr(0, slash));
      mask = ~0u << (32 - d.prefix);
      if ((base & ~mask) != 0) throw std::invalid_argument("host bits set");
    } catch (const std::exception& e) {
      fail(origin, net["subnet"], "subnet '" + d.subnet + "': " + e.what());
    }
  }
  auto seconds = [&](const char* key, double& v, double lo, double hi) {
    if (!net[key]) return;
    v = get<double>(origin, net[key], key);
    if (!(v >= lo && v <= hi)) fail(origin, net[key], std::string(key) + " must be in [" + num(lo) + ", " + num(hi) + "] s");
  };
  seconds("spdp_interval", d.spdp_interval_s, 0.1, 60.0);
  seconds("lease_duration", d.lease_duration_s, 1.0, 600.0);
  if (d.lease_duration_s < 2.0 * d.spdp_interval_s) fail(origin, net, "lease_duration must be at least twice spdp_interval");
  if (net["link"]) {
    try {
      d.link = parse_link(get<std::string>(origin, net["link"], "link"));
    } catch (const std::invalid_argument& e) {
      fail(origin, net["link"], e.what());
    }
  }

  const YAML::Node hosts = root["hosts"];
  if (!hosts || !hosts.IsSequence() || hosts.size() == 0) throw std::runtime_error(origin + ": 'hosts' must be a non-empty list");
  static const std::regex name_re("^[a-z0-9][a-z0-9-]{0,15}$"), if_re("^[a-zA-Z0-9_.-]{1,15}$");
  std::set<std::string> names, addresses, placed;
  for (const auto& hn : hosts) {
    only_keys(origin, hn, {"name", "address", "interface", "components", "link"}, "a host");
    Host h;
    if (!hn["name"]) fail(origin, hn, "host without 'name'");
    h.name = get<std::string>(origin, hn["name"], "name");
    if (!std::regex_match(h.name, name_re)) fail(origin, hn["name"], "host name '" + h.name + "': 1-16 of [a-z0-9-]");
    if (!names.insert(h.name).second) fail(origin, hn["name"], "duplicate host '" + h.name + "'");
    if (!hn["address"]) fail(origin, hn, "host '" + h.name + "' has no 'address'");
    h.address = get<std::string>(origin, hn["address"], "address");
    try {
      const uint32_t a = ipv4(h.address);
      if ((a & mask) != base) throw std::invalid_argument("outside the subnet " + d.subnet);
      if (a == base || a == (base | ~mask)) throw std::invalid_argument("the subnet's network or broadcast address");
    } catch (const std::invalid_argument& e) {
      fail(origin, hn["address"], "address of '" + h.name + "': " + e.what());
    }
    if (!addresses.insert(h.address).second) fail(origin, hn["address"], "address " + h.address + " used twice");
    h.interface = hn["interface"] ? get<std::string>(origin, hn["interface"], "interface") : "eth0";
    if (!std::regex_match(h.interface, if_re)) fail(origin, hn["interface"], "interface '" + h.interface + "' is not an interface name");
    h.link = d.link;
    if (hn["link"]) {
      try {
        h.link = parse_link(get<std::string>(origin, hn["link"], "link"));
      } catch (const std::invalid_argument& e) {
        fail(origin, hn["link"], e.what());
      }
    }
    if (!hn["components"]) fail(origin, hn, "host '" + h.name + "' has no 'components'");
    h.components = get<std::vector<std::string>>(origin, hn["components"], "components");
    for (const auto& c : h.components) {
      const auto& k = known_components();
      if (std::find(k.begin(), k.end(), c) == k.end()) fail(origin, hn["components"], "unknown component '" + c + "' on '" + h.name + "'");
      if (!placed.insert(c).second) fail(origin, hn["components"], "component '" + c + "' is placed on two hosts");
    }
    d.hosts.push_back(std::move(h));
  }
  return d;
}

Deployment load(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read deployment '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

std::string cyclone_config(const Deployment& d, const Host& h) {
  std::ostringstream x;
  x << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<!-- Generated by mpgc_deploy from " << d.origin << " for host " << h.name << " (" << h.address << ").\n"
    << "     Its own interface only, no multicast (switches on ships often drop it), every host a unicast\n"
    << "     peer; SPDP every " << num(d.spdp_interval_s) << " s so that discovery survives a lossy link. -->\n"
    << "<CycloneDDS xmlns=\"https://cdds.io/config\">\n  <Domain Id=\"any\">\n    <General>\n"
    << "      <Interfaces><NetworkInterface name=\"" << h.interface << "\"/></Interfaces>\n"
    << "      <AllowMulticast>false</AllowMulticast>\n    </General>\n    <Discovery>\n"
    << "      <ParticipantIndex>auto</ParticipantIndex>\n      <MaxAutoParticipantIndex>50</MaxAutoParticipantIndex>\n"
    << "      <SPDPInterval>" << num(d.spdp_interval_s) << "s</SPDPInterval>\n      <Peers>\n";
  for (const auto& o : d.hosts) x << "        <Peer address=\"" << o.address << "\"/>  <!-- " << o.name << " -->\n";
  x << "      </Peers>\n"
    << "      <LeaseDuration>" << num(d.lease_duration_s) << "s</LeaseDuration>\n    </Discovery>\n"
    << "  </Domain>\n</CycloneDDS>\n";
  return x.str();
}

std::string host_launch(const Deployment& d, const Host& h, const LaunchOptions& o) {
  std::ostringstream y;
  y << "# Generated by mpgc_deploy from " << d.origin << " for host " << h.name << ": mpgc_launch THIS_FILE\n"
    << "components:\n";
  for (const auto& c : h.components) {
    if (c == "scenario_runner") continue;  // the evaluator of mpgc_run, not a ship's process
    y << "  - name: " << c << "\n    executable: " << o.bin_dir << "/mpgc_" << c << "\n"
      << "    params: [" << o.params_dir << "/" << c << ".yaml]\n"
      << "    restart: always\n    max_restarts: 1000\n    restart_delay: 1.0\n"
      << "    env: {CYCLONEDDS_URI: '" << o.full_cyclone_uri() << "'"
      << (o.security_dir.empty() ? "" : ", MPGC_SECURITY_ID: " + c) << "}\n";
  }
  return y.str();
}

std::string systemd_unit(const std::string& c, const LaunchOptions& o) {
  std::ostringstream u;
  u << "# Generated by mpgc_deploy (./mpgc deploy units): one unit per component, the same on every host;\n"
    << "# what differs between hosts is in /etc/mpgc/ (mpgc.env, cyclonedds.xml, params/).\n"
    << "[Unit]\nDescription=mpgc " << c << "\nDocumentation=file:///opt/mpgc/README.md\n"
    << "Wants=network-online.target\nAfter=network-online.target" << (c == "ship_bridge" ? " gpsd.service" : "") << "\n"
    << "PartOf=mpgc.target\n"
    << "# a component that keeps dying is still restarted: a ship must not lose its autonomy for good\n"
    << "StartLimitIntervalSec=0\n\n[Service]\nType=simple\nUser=mpgc\nGroup=mpgc\n"
    << "EnvironmentFile=/etc/mpgc/mpgc.env\n"
    << "Environment=MPGC_SECURITY_ID=" << c << "\n"
    << "ExecStart=" << o.bin_dir << "/mpgc_" << c << " --params " << o.params_dir << "/" << c << ".yaml\n"
    << "Restart=always\nRestartSec=1\nTimeoutStopSec=5\nKillMode=mixed\n\n[Install]\nWantedBy=mpgc.target\n";
  return u.str();
}

std::string systemd_target() {
  return "# Generated by mpgc_deploy: every mpgc unit of this host (systemctl start mpgc.target)\n"
         "[Unit]\nDescription=mpgc components of this host\nWants=network-online.target\n"
         "After=network-online.target\n\n[Install]\nWantedBy=multi-user.target\n";
}

}  // namespace mpgc::deploy
