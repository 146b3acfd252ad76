// mpgc_run: sails scenarios closed-loop. For each scenario it writes the simulator's world file and
// a launch file, starts the five components through mpgc_launch on loopback DDS (lockstep as fast
// as possible, or a real-time factor), publishes the goal, records ground truth, plans and
// guidance status as a lockstep participant, stops at the goal or the time limit, and evaluates
// the run independently of the planner (metrics.json, timeseries.csv, trajectory.svg, dtc.svg).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/null_sink.h>

#include "deployment.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/json/json.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/runtime/health_board.hpp"
#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/scenario_runner/fault_run.hpp"
#include "mpgc/scenario_runner/report.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/topics.hpp"
#include "netns.hpp"

namespace fs = std::filesystem;
namespace sr = mpgc::scenario_runner;
namespace msg = mpgc::msg;
namespace rt = mpgc::rt;
namespace dds = mpgc::dds;
namespace dp = mpgc::deploy;
using Steady = std::chrono::steady_clock;

namespace {

constexpr const char* kAutonomy[] = {"situational_awareness", "obstacle_manager", "opp", "guidance_control"};

struct Options {
  double realtime_factor = 0.0;  // 0: lockstep as fast as possible
  std::string out = "out";
  double record_period = 1.0;    // [s] simulated
  bool quiet = false;
  bool hil = false;              // hardware in the loop: simulator -> NMEA -> gpsd -> ship_bridge
  // Across a ship's network: the components on the hosts of a deployment, as network namespaces.
  std::optional<dp::Deployment> hosts;
  std::map<std::string, dp::LinkSpec> links;  // each host's egress
  uint64_t link_seed = 1;
  std::vector<dp::LinkCut> cuts;
  bool capture = false;          // tcpdump of every host to <run>/network/<host>.pcap
  std::string secure;            // DDS Security: the folder made by deploy/security/make-pki.sh
  int domain = -1;               // -1: a free one in 201..230
  bool containers = false;       // with hosts: each host a podman container (deploy/container)
  std::string image = "localhost/mpgc:bookworm";
  double plan_latency = 0.0;     // [s] per planner iteration: plans take effect late (opp plan.latency_per_iteration)
};

std::string mpgc_source_dir() {
  const char* src = std::getenv("MPGC_SOURCE_DIR");
  return fs::weakly_canonical(src != nullptr ? src : ".").string();
}
std::string shared_data_dir() {
  const char* d = std::getenv("MPGC_SHARED_DATA");
  const fs::path p = d != nullptr ? fs::path(d) : fs::path(mpgc_source_dir()) / ".." / "shared" / "data";
  return fs::exists(p) ? fs::canonical(p).string() : "";
}

// Hardware in the loop: the default real-time factor (gpsd runs on the wall clock) and an MMSI for
// the own ship's transponder when the scenario gives none.
constexpr double kHilFactor = 20.0;
constexpr uint32_t kHilOwnMmsi = 257999990;

// The UDP/TCP ports of one HIL run, distinct per DDS domain so concurrent runs do not meet.
struct HilPorts {
  int gpsd, gnss, ais, gyro, feedback, orders;
  explicit HilPorts(int domain) {
    const int b = 20000 + 10 * domain;
    gpsd = b, gnss = b + 1, ais = b + 2, gyro = b + 3, feedback = b + 4, orders = b + 5;
  }
};

// A DDS domain no other run on this machine holds (201..230; tests use 1..200), locked until the
// lease is destroyed. Successive runs of a suite take successive ids, so that a run never starts
// on the domain the previous one has just left.
class DomainLease {
 public:
  // A given domain (mpgc_run --domain): locked the same way, or an error when another run holds it.
  explicit DomainLease(int id) : id_(id) {
    const std::string path = "/tmp/mpgc-run-domain-" + std::to_string(id) + ".lock";
    fd_ = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
    if (fd_ < 0 || flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw std::runtime_error("DDS domain " + std::to_string(id) + " is held by another run on this machine");
  }
  DomainLease() {
    static int next = 0;
    for (int k = 0; k < 30; ++k) {
      const int id = 201 + (next + k) % 30;
      const std::string path = "/tmp/mpgc-run-domain-" + std::to_string(id) + ".lock";
      const int fd = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
      if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0) {
        fd_ = fd, id_ = id, next = (next + k + 1) % 30;
        return;
      }
      if (fd >= 0) close(fd);
    }
    throw std::runtime_error("no free DDS domain in 201..230 (too many runs at once)");
  }
  ~DomainLease() { close(fd_); }  // releases the lock
  DomainLease(const DomainLease&) = delete;
  DomainLease& operator=(const DomainLease&) = delete;
  int id() const { return id_; }

 private:
  int fd_ = -1, id_ = 0;
};

std::string yaml_str(const std::string& s) {
  YAML::Emitter e;
  e << YAML::DoubleQuoted << s;
  return e.c_str();
}

// The launch file for one run: the simulator plus the four autonomy components on simulated time.
// Where a component runs when the run is spread over a deployment's hosts: its network namespace
// and its host's Cyclone configuration.
struct Placement {
  const dp::NetnsLab* lab = nullptr;
  std::string network_dir;  // <run>/network: <host>/cyclonedds.xml
};

std::string launch_file(const sr::Scenario& s, const std::string& world_path, const Options& o, int domain,
                        const Placement& where) {
  std::map<std::string, std::map<std::string, std::string>> set;
  auto& sim = set["ship_simulator"];
  sim["world.file"] = world_path;
  const HilPorts hp(domain);
  if (o.hil) {
    sim["hil.enabled"] = "true";
    sim["hil.gnss_port"] = std::to_string(hp.gnss);
    sim["hil.ais_port"] = std::to_string(hp.ais);
    sim["hil.gyro_port"] = std::to_string(hp.gyro);
    sim["hil.feedback_port"] = std::to_string(hp.feedback);
    sim["hil.orders_port"] = std::to_string(hp.orders);
    auto& b = set["ship_bridge"];
    b["clock.source"] = "sim";
    b["clock.lockstep_ack"] = "false";
    b["gpsd.port"] = std::to_string(hp.gpsd);
    b["gyro.port"] = std::to_string(hp.gyro);
    b["actuators.port"] = std::to_string(hp.orders);
    b["actuators.feedback_port"] = std::to_string(hp.feedback);
    b["origin.source"] = "param";
    b["origin.lat"] = std::to_string(s.origin_lat_deg);
    b["origin.lon"] = std::to_string(s.origin_lon_deg);
    // Timeouts run on simulated time but the jitter is the wall clock's (gpsd, UDP, a loaded
    // machine): at 20x a 60 ms stall is 1.2 s simulated. Widen them to 0.15 s of wall time.
    const double f = o.realtime_factor > 0 ? o.realtime_factor : kHilFactor;
    const std::string jitter = std::to_string(std::max(1.0, 0.15 * f));
    b["nav.heading_timeout"] = jitter;
    b["actuators.command_timeout"] = jitter;
    sim["hil.order_timeout"] = std::to_string(std::max(2.0, 0.2 * f));
    const YAML::Node mmsi = s.world["own_ship"]["mmsi"];
    b["own.mmsi"] = std::to_string(mmsi && mmsi.as<uint32_t>() != 0 ? mmsi.as<uint32_t>() : kHilOwnMmsi);
  }
  if (o.realtime_factor > 0) {
    sim["time.mode"] = "factor";
    sim["time.factor"] = std::to_string(o.realtime_factor);
    // The actuator watchdog runs on simulated time but the orders' jitter is the wall clock's:
    // at 20x, 0.1 s of wall time is 2 s simulated. Give it 0.2 s of wall time at least.
    sim["watchdog.timeout"] = std::to_string(std::max(2.0, 0.2 * o.realtime_factor));
  } else {
    sim["time.mode"] = "lockstep";
    std::string participants = "scenario_runner";
    for (const char* c : kAutonomy) participants += std::string(",") + c;
    sim["lockstep.participants"] = participants;
  }
  sim["truth.period"] = std::to_string(o.record_period);
  for (const char* c : kAutonomy) set[c]["clock.source"] = "sim";
  const std::string lat = std::to_string(s.origin_lat_deg), lon = std::to_string(s.origin_lon_deg);
  set["situational_awareness"]["origin.source"] = "param";
  set["situational_awareness"]["origin.lat"] = lat;
  set["situational_awareness"]["origin.lon"] = lon;
  auto& om = set["obstacle_manager"];
  om["chart.origin_lat"] = lat;
  om["chart.origin_lon"] = lon;
  if (!s.chart_shapes.empty()) om["chart.shapes"] = s.chart_shapes;
  std::string files;
  for (const auto& f : s.chart_files) files += (files.empty() ? "" : ",") + f;
  if (!files.empty()) om["chart.files"] = files;
  // Planning in lockstep is deterministic only when the iteration budget, not wall time, ends it;
  // at a real-time factor the planner keeps its own wall-clock budget.
  set["opp"]["plan.safety_distance"] = std::to_string(s.safety_distance);
  if (o.realtime_factor <= 0) set["opp"]["plan.time_budget"] = "30";
  if (o.plan_latency > 0) set["opp"]["plan.latency_per_iteration"] = std::to_string(o.plan_latency);
  // What a restarted component resumes from (issue 15): the simulator's step journal, opp's memory.
  const fs::path run_dir = fs::path(world_path).parent_path();
  sim["resume.journal"] = (run_dir / "sim_journal.bin").string();
  set["opp"]["memory.file"] = (run_dir / "opp_memory.yaml").string();
  // A participant that is alive but silent (deadlocked) is dropped after this; above opp's budget.
  if (o.realtime_factor <= 0) sim["lockstep.hang_timeout"] = "45";
  if (!s.faults.empty())
    for (const char* c : {"ship_simulator", "situational_awareness", "obstacle_manager", "opp", "guidance_control"})
      set[c]["faults.accept"] = "true";
  for (const auto& [comp, kv] : s.params)
    for (const auto& [k, v] : kv) set[comp][k] = v;

  std::ostringstream y;
  y << "# Generated by mpgc_run for scenario " << s.name << "\ncomponents:\n";
  if (o.hil) {
    // gpsd on the wall clock, fed by the simulated devices over UDP; GNSS and AIS on two devices
    // (gpsd 3.22 writes invalid ATT JSON when HDT and AIS share one). Never as root: gpsd would
    // drop to its own user and leave its socket and SHM behind (../shared/notes/gpsd.md).
    char key[16];
    std::snprintf(key, sizeof key, "0x4770%04X", hp.gpsd & 0xffff);  // gpsd's SHM key, one per run
    std::vector<std::string> cmd = {"env", "GPSD_SHM_KEY=" + std::string(key), "gpsd", "-N", "-n",
                                    "-S", std::to_string(hp.gpsd), "-F", "/tmp/mpgc-gpsd-" + std::to_string(domain) + ".sock",
                                    "udp://127.0.0.1:" + std::to_string(hp.gnss), "udp://127.0.0.1:" + std::to_string(hp.ais)};
    if (geteuid() == 0) cmd.insert(cmd.begin(), {"runuser", "-u", "nobody", "--"});
    y << "  - name: gpsd\n    executable: " << cmd[0] << "\n    args: [";
    for (size_t i = 1; i < cmd.size(); ++i) y << (i > 1 ? ", " : "") << yaml_str(cmd[i]);
    y << "]\n";
  }
  std::vector<std::string> comps = {"ship_simulator", "situational_awareness", "obstacle_manager", "opp", "guidance_control"};
  if (o.hil) comps.insert(comps.begin() + 1, "ship_bridge");
  const std::string bin = fs::canonical("/proc/self/exe").parent_path().string();
  // One component's entry; on a host (`in_ns`: its namespace, else its container) with the host's
  // Cyclone configuration.
  auto entry = [&](std::ostream& f, const std::string& c, bool in_ns) {
    f << "  - name: " << c << "\n    executable: " << (o.containers ? bin + "/" : "") << "mpgc_" << c << "\n";
    if (where.lab != nullptr) {
      const dp::Host* h = o.hosts->host_of(c);
      if (in_ns) f << "    host: " << where.lab->ns(h->name) << "\n";
      f << "    env: {CYCLONEDDS_URI: " << yaml_str("file://" + where.network_dir + "/" + h->name + "/cyclonedds.xml") << "}\n";
    }
    // A component that dies is restarted and recovers from its journal or memory file and the
    // latched topics (issue 15); a clean exit (code 0) is the end of the run.
    f << "    restart: on-failure\n    max_restarts: 20\n    restart_delay: 0.2\n";
    f << "    set:\n";
    for (const auto& [k, v] : set[c]) f << "      " << k << ": " << yaml_str(v) << "\n";
  };
  if (!o.containers) {
    for (const auto& c : comps) entry(y, c, true);
    return y.str();
  }
  // Each host its own podman container on its namespace, running mpgc_launch with the host's own
  // launch file; the executables, sources, data and outputs mounted at their own paths.
  const std::string cwd = fs::current_path().string();  // relative paths in parameters resolve from here
  std::vector<std::string> mounts = {bin, mpgc_source_dir(), shared_data_dir(), cwd};
  if (!o.secure.empty()) mounts.push_back(o.secure);
  for (const auto& h : o.hosts->hosts) {
    const std::string host_launch = where.network_dir + "/" + h.name + "/launch.yaml";
    std::ofstream f(host_launch);
    f << "# Generated by mpgc_run: host " << h.name << " of " << o.hosts->origin << "\ncomponents:\n";
    int n = 0;
    for (const auto& c : comps)
      if (o.hosts->host_of(c) == &h) entry(f, c, false), ++n;
    if (n == 0) continue;  // a host with only the evaluator (this process)
    std::vector<std::string> a = {"run", "--rm", "--name", where.lab->ns(h.name), "--stop-timeout", "15",
                                  "--network", "ns:/run/netns/" + where.lab->ns(h.name)};
    for (const auto& m : mounts)
      if (!m.empty()) a.insert(a.end(), {"-v", m + ":" + m + ":ro"});
    for (const char* v : {"MPGC_SHARED_DATA", "MPGC_SOURCE_DIR"})
      if (std::getenv(v) != nullptr) a.insert(a.end(), {"-e", std::string(v) + "=" + std::getenv(v)});
    a.insert(a.end(), {"-w", cwd, "-v", fs::absolute(o.out).string() + ":" + fs::absolute(o.out).string(), o.image,
                       bin + "/mpgc_launch", host_launch, "--domain", std::to_string(domain)});
    if (!o.secure.empty()) a.insert(a.end(), {"--secure", o.secure});
    y << "  - name: " << h.name << "\n    executable: podman\n    env: {CONTAINERS_CONF: "
      << yaml_str(mpgc_source_dir() + "/deploy/container/containers.conf") << "}\n    args: [";
    for (size_t i = 0; i < a.size(); ++i) y << (i ? ", " : "") << yaml_str(a[i]);
    y << "]\n";
  }
  return y.str();
}

pid_t start_launcher(const std::string& launch, int domain, const std::string& log_path, const std::string& secure) {
  const std::string exe = (fs::canonical("/proc/self/exe").parent_path() / "mpgc_launch").string();
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    const int fd = open(log_path.c_str(), O_CREAT | O_WRONLY | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    const std::string d = std::to_string(domain);
    if (secure.empty()) execl(exe.c_str(), exe.c_str(), launch.c_str(), "--domain", d.c_str(), nullptr);
    else execl(exe.c_str(), exe.c_str(), launch.c_str(), "--domain", d.c_str(), "--secure", secure.c_str(), nullptr);
    _exit(127);
  }
  return pid;
}

int stop_launcher(pid_t pid) {
  kill(pid, SIGTERM);
  const auto end = Steady::now() + std::chrono::seconds(20);
  int status = 0;
  while (Steady::now() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(-pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

sr::ShipState state_of(const msg::ShipTruth& t) { return {t.x, t.y, t.heading, t.cog, t.sog}; }

// The process of `component` among the launcher's children (its argv[0] is mpgc_<component>), or -1.
pid_t component_pid(pid_t launcher, const std::string& component) {
  const std::string exe = "mpgc_" + component;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator("/proc", ec)) {
    const std::string name = e.path().filename().string();
    if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream st(e.path() / "stat");
    std::string line;
    std::getline(st, line);
    const auto close = line.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream rest(line.substr(close + 2));
    char state = 0;
    pid_t ppid = 0;
    rest >> state >> ppid;
    if (ppid != launcher) continue;
    std::ifstream cl(e.path() / "cmdline");
    std::string argv0;
    std::getline(cl, argv0, '\0');
    if (fs::path(argv0).filename() == exe) return static_cast<pid_t>(std::stoi(name));
  }
  return -1;
}



struct Outcome {
  bool ran = false;
  sr::Metrics metrics;
  std::string error;
  std::vector<std::string> notes;  // what the network did (cuts, netem)
};

std::string num_text(double v, const char* f = "%.0f");

int plans_between(const sr::RunRecord& run, double t0, double t1) {
  return static_cast<int>(std::count_if(run.plans.begin(), run.plans.end(),
                                        [&](const sr::PlanRecord& p) { return p.t > t0 && p.t < t1; }));
}

// The Cyclone configuration this process was started with (./mpgc exports loopback.xml).
std::string base_cyclone_uri() {
  static const std::string uri = [] {
    const char* u = std::getenv("CYCLONEDDS_URI");
    return std::string(u != nullptr ? u : "");
  }();
  return uri;
}

Outcome run_one(const sr::Scenario& s, const Options& o) {
  Outcome out;
  const fs::path dir = fs::path(o.out) / (o.hil ? s.name + "-hil" : s.name);
  fs::create_directories(dir);
  const std::string world_path = fs::absolute(dir / "world.yaml").string();
  {
    YAML::Node world = YAML::Clone(s.world);
    if (o.hil && (!world["own_ship"]["mmsi"] || world["own_ship"]["mmsi"].as<uint32_t>() == 0))
      world["own_ship"]["mmsi"] = kHilOwnMmsi;
    YAML::Emitter e;
    e << world;
    std::ofstream(world_path) << "# Generated by mpgc_run from " << s.path << "\n" << e.c_str() << "\n";
  }
  // A fresh run: no journal or memory of an earlier one to resume from.
  for (const char* f : {"sim_journal.bin", "opp_memory.yaml"}) fs::remove(dir / f);
  // Released when this run is over (a suite used to run out after 30).
  const auto lease = o.domain >= 0 ? std::make_unique<DomainLease>(o.domain) : std::make_unique<DomainLease>();
  const int domain = lease->id();

  // On a deployment's hosts: the namespaces, each host's Cyclone configuration, and this process
  // (the evaluator) moved onto its own host before it joins the bus.
  std::unique_ptr<dp::NetnsLab> lab;
  Placement where;
  std::string cyclone_uri = base_cyclone_uri();
  const fs::path net_dir = fs::absolute(dir / "network");
  if (o.hosts) {
    fs::create_directories(net_dir);
    for (const auto& h : o.hosts->hosts) {
      fs::create_directories(net_dir / h.name);
      std::ofstream(net_dir / h.name / "cyclonedds.xml") << dp::cyclone_config(*o.hosts, h);
    }
    dp::LabOptions lo;
    lo.links = o.links;
    lo.seed = o.link_seed;
    lo.netem_exe = (fs::canonical("/proc/self/exe").parent_path() / "mpgc_netem").string();
    lo.capture_dir = o.capture ? net_dir.string() : "";
    lo.log_dir = net_dir.string();
    lab = std::make_unique<dp::NetnsLab>(*o.hosts, lo);
    const std::string runner_host = o.hosts->host_of("scenario_runner")->name;
    lab->enter(runner_host);
    where = {lab.get(), net_dir.string()};
    cyclone_uri = "file://" + (net_dir / runner_host / "cyclonedds.xml").string();
  }
  if (!o.secure.empty()) {
    cyclone_uri += ",file://" + o.secure + "/security.xml";
    setenv("MPGC_SECURITY_ID", "scenario_runner", 1);
  }
  setenv("CYCLONEDDS_URI", cyclone_uri.c_str(), 1);
  const std::string launch_path = fs::absolute(dir / "launch.yaml").string();
  std::ofstream(launch_path) << launch_file(s, world_path, o, domain, where);

  rt::RuntimeParams rp;
  rp.domain = domain;
  rp.clock = "sim";
  rp.lockstep_ack = o.realtime_factor <= 0;
  auto log = std::make_shared<spdlog::logger>("scenario_runner", std::make_shared<spdlog::sinks::null_sink_mt>());
  rt::Component c("scenario_runner", rp, log);

  sr::RunRecord run;
  run.safety_distance = s.safety_distance;
  run.goal = s.goal;
  msg::GroundTruth truth;
  bool have_truth = false;
  // Every fixed obstacle obstacle_manager published during the run: it sends the region around the
  // own ship, so the union of all versions, not the last one, is what the ship sailed past.
  std::map<std::tuple<uint32_t, std::size_t, double, double>, sr::Polygon> fixed_polygons;
  std::set<std::pair<double, double>> fixed_points;
  std::vector<uint32_t> target_ids;

  auto& goal_w = c.publisher<msg::MissionGoal>(mpgc::topics::kGoal, dds::QosProfile::latched());
  c.subscribe<msg::GroundTruth>(mpgc::topics::kTruth, dds::QosProfile::state(), [&](const msg::GroundTruth& t) {
    truth = t;
    have_truth = true;
  });
  c.subscribe<msg::FixedObstacles>(mpgc::topics::kFixedObstacles, dds::QosProfile::latched(),
                                   [&](const msg::FixedObstacles& f) {
                                     for (const auto& p : f.polygons) {
                                       if (p.ring.size() < 3) continue;
                                       const auto key = std::make_tuple(p.feature_id, p.ring.size(), p.ring[0].x, p.ring[0].y);
                                       if (fixed_polygons.count(key)) continue;
                                       sr::Polygon poly;
                                       for (const auto& q : p.ring) poly.vertices.push_back({q.x, q.y});
                                       fixed_polygons.emplace(key, std::move(poly));
                                     }
                                     for (const auto& q : f.points) fixed_points.insert({q.x, q.y});
                                   });
  c.subscribe<msg::Path>(mpgc::topics::kPath, dds::QosProfile::latched(), [&](const msg::Path& p) {
    sr::PlanRecord r;
    r.t = c.clock().now_s();
    r.plan_id = p.plan_id;
    r.status = p.status == msg::PlanStatus::PLAN_OK        ? sr::PlanStatus::kOk
               : p.status == msg::PlanStatus::PLAN_RELAXED ? sr::PlanStatus::kRelaxed
                                                           : sr::PlanStatus::kNoPath;
    for (const auto& w : p.waypoints) r.waypoints.push_back({w.x, w.y, w.t});
    if (r.status != sr::PlanStatus::kNoPath && r.waypoints.size() < 2) r.status = sr::PlanStatus::kNoPath;
    r.planning_time = p.planning_time;
    if (run.plans.empty() || r.t >= run.plans.back().t) run.plans.push_back(std::move(r));
  });
  c.subscribe<msg::GuidanceStatus>(mpgc::topics::kGuidanceStatus, dds::QosProfile::state(),
                                   [&](const msg::GuidanceStatus& g) {
                                     sr::GuidanceRecord r;
                                     r.t = c.clock().now_s();
                                     r.plan_id = g.plan_id;
                                     r.active_waypoint = g.active_waypoint;
                                     r.cross_track_error = g.cross_track_error;
                                     if (run.guidance.empty() || r.t > run.guidance.back().t) run.guidance.push_back(r);
                                   });

  // Faults of the scenario and the health of the components: which is down, degraded or back.
  pid_t launcher = -1;
  std::mutex fault_mutex;  // `faults`: the record timer, the health samples and the wall-clock watchdog
  // Only a run with faults has the fault topic (a secured bus grants it to nobody).
  dds::Writer<msg::FaultCommand>* fault_w =
      s.faults.empty() ? nullptr : &c.publisher<msg::FaultCommand>(mpgc::topics::kFaults, dds::QosProfile::command(16));
  // The system's health (one view, mpgc::rt::HealthBoard on the wall clock): a component's change
  // to down, stale, degraded or back is printed; a new incarnation (its health seq starts again)
  // marks the recovery of a killed or stopped one.
  std::mutex health_mutex;  // the board: the executor feeds it, the wall-clock watchdog reads it
  rt::HealthBoard board;
  std::map<std::string, uint32_t> health_seq;
  auto wall_ns = [] { return std::chrono::duration_cast<std::chrono::nanoseconds>(Steady::now().time_since_epoch()).count(); };
  auto say = [&](const std::string& what) {
    if (!o.quiet) std::printf("  %-28s sim %6.0f s  %s\n", s.name.c_str(), c.clock().now_s(), what.c_str());
    std::fflush(stdout);
  };
  const auto run_start = Steady::now();
  auto wall_s = [run_start] { return std::chrono::duration<double>(Steady::now() - run_start).count(); };
  sr::FaultEffects fx;
  fx.pid_of = [&](const std::string& component) { return static_cast<int>(component_pid(launcher, component)); };
  fx.signal = [](int pid, int sig) { kill(pid, sig); };
  fx.command = [&](const sr::Fault& f) {
    msg::FaultCommand fc;
    fc.header = c.header();
    fc.kind = f.kind == sr::Fault::Kind::kSilence      ? msg::FaultKind::FAULT_SILENCE_TOPIC
              : f.kind == sr::Fault::Kind::kAisOutage   ? msg::FaultKind::FAULT_AIS_OUTAGE
              : f.kind == sr::Fault::Kind::kGnssDropout ? msg::FaultKind::FAULT_GNSS_DROPOUT
                                                        : msg::FaultKind::FAULT_POSITION_JUMP;
    fc.topic = f.topic;
    fc.mmsi = f.mmsi;
    fc.duration = f.duration_s;
    fc.dx = f.dx;
    fc.dy = f.dy;
    fault_w->write(fc);
  };
  fx.killed = [&](const std::string& component) {
    std::lock_guard<std::mutex> hg(health_mutex);
    board.process_gone(component, "killed (fault injected)", wall_ns());
  };
  fx.say = say;
  sr::FaultRun faults(s.faults, fx);
  std::map<std::string, rt::Status> said;  // "up" is news only after something else was said
  auto print_health_changes = [&] {  // health_mutex held
    for (const auto& v : board.changes(wall_ns())) {
      if (!v.expected || v.status == rt::Status::kStarting) continue;
      const auto before = said.find(v.name);
      if (v.status == rt::Status::kUp && (before == said.end() || before->second == rt::Status::kUp)) continue;
      said[v.name] = v.status;
      say("health: " + v.name + " " + rt::to_string(v.status) + (v.detail.empty() ? "" : ": " + v.detail));
    }
  };
  {
    std::lock_guard<std::mutex> g(health_mutex);
    for (const char* n : {"ship_simulator", "situational_awareness", "obstacle_manager", "opp", "guidance_control"})
      board.expect(n, wall_ns());
    board.changes(wall_ns());  // nothing to say before the start
  }
  c.subscribe<msg::ComponentHealth>(mpgc::topics::kHealth, dds::QosProfile::latched(), [&](const msg::ComponentHealth& h) {
    const double now = c.clock().now_s();
    const auto seq = health_seq.find(h.component);
    const bool restarted = seq != health_seq.end() && h.header.seq < seq->second;
    health_seq[h.component] = h.header.seq;
    {
      std::lock_guard<std::mutex> g(health_mutex);
      if (restarted) board.process_started(h.component, wall_ns()), say("health: " + h.component + " is back (a new process)");
      board.sample(h, wall_ns());
      print_health_changes();
    }
    std::lock_guard<std::mutex> g(fault_mutex);
    faults.on_health(h.component, restarted, now, wall_s());
  });

  msg::MissionGoal goal;
  goal.header.source = "scenario_runner";
  goal.goal_id = 1;
  goal.x = s.goal.x;
  goal.y = s.goal.y;
  goal.heading = s.goal_heading;
  goal.heading_tolerance = s.goal_heading_tolerance;
  goal.cruise_speed = s.cruise_speed;
  goal.safety_distance = s.safety_distance;
  goal.colreg = s.colreg;
  goal_w.write(goal);

  // Link cuts: each begins when the simulated clock reaches it and lasts its wall-clock time.
  struct CutState {
    dp::LinkCut cut;
    bool begun = false, ended = false;
    Steady::time_point wall_begin{};
    double sim_begin = 0, sim_end = 0;
  };
  std::vector<CutState> cuts;
  for (const auto& k : o.cuts) cuts.push_back({k});
  std::mutex cut_mutex;

  std::string end_reason;
  const auto wall_start = Steady::now();
  auto last_print = wall_start;
  c.every(o.record_period, [&] {
    if (!have_truth) return;
    const double t = c.clock().now_s();
    if (!run.t.empty() && t <= run.t.back()) return;
    {
      std::lock_guard<std::mutex> g(cut_mutex);
      for (auto& k : cuts)
        if (!k.begun && t >= k.cut.at_s) {
          lab->set_cut(k.cut.host, true);
          k.begun = true, k.wall_begin = Steady::now(), k.sim_begin = t;
          if (!o.quiet) std::printf("  %-28s sim %6.0f s  network: %s cut off for %.1f s\n", s.name.c_str(), t,
                                    k.cut.host.c_str(), k.cut.duration_s);
        }
    }
    if (!s.faults.empty()) {
      std::lock_guard<std::mutex> g(fault_mutex);
      faults.at_sim(t, wall_s());
    }
    if (run.t.empty()) {
      run.own.id = 0;
      run.own.length = truth.own.length > 0 ? truth.own.length : s.lpp;
      for (const auto& tt : truth.targets) {
        target_ids.push_back(tt.id);
        sr::ShipTrack tr;
        tr.id = tt.id;
        tr.length = tt.length > 0 ? tt.length : 100.0;
        run.targets.push_back(tr);
      }
    }
    if (truth.targets.size() != target_ids.size()) return;  // the scene is fixed for a run
    run.t.push_back(t);
    run.own.states.push_back(state_of(truth.own));
    for (size_t i = 0; i < truth.targets.size(); ++i) run.targets[i].states.push_back(state_of(truth.targets[i]));
    const double to_goal = std::hypot(truth.own.x - s.goal.x, truth.own.y - s.goal.y);
    if (!o.quiet && Steady::now() - last_print > std::chrono::seconds(2)) {
      last_print = Steady::now();
      std::printf("  %-28s sim %6.0f s  to goal %7.0f m  plans %3zu  wall %5.1f s\n", s.name.c_str(), t, to_goal,
                  run.plans.size(), std::chrono::duration<double>(last_print - wall_start).count());
      std::fflush(stdout);
    }
    if (to_goal <= s.goal.radius) {
      end_reason = "goal reached";
      c.stop(0);
    } else if (t >= s.time_limit) {
      end_reason = "time limit";
      c.stop(0);
    }
  });

  launcher = start_launcher(launch_path, domain, (dir / "components.log").string(), o.secure);
  // A wall-clock watchdog: the simulated clock stops if a component dies, so only wall time can tell.
  std::atomic<bool> done{false};
  std::thread watchdog([&] {
    double last_sim = -1;
    auto last_progress = Steady::now();
    while (!done) {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      {
        std::lock_guard<std::mutex> g(cut_mutex);
        for (auto& k : cuts)
          if (k.begun && !k.ended && Steady::now() - k.wall_begin >= std::chrono::duration<double>(k.cut.duration_s)) {
            lab->set_cut(k.cut.host, false);
            k.ended = true, k.sim_end = c.clock().now_s();
            last_progress = Steady::now();  // a stalled clock during the cut is the cut's doing
          }
      }
      {
        std::lock_guard<std::mutex> g(fault_mutex);
        if (faults.at_wall(wall_s(), c.clock().now_s())) last_progress = Steady::now();  // the stalled clock was the stop's doing
      }
      {
        std::lock_guard<std::mutex> g(health_mutex);
        print_health_changes();  // stale ones, which no sample announces
      }
      int status = 0;
      if (waitpid(launcher, &status, WNOHANG) == launcher) {
        end_reason = "the components stopped (see components.log)";
        c.stop(1);
        return;
      }
      const double sim = c.clock().now_s();
      if (sim != last_sim) {
        last_sim = sim;
        last_progress = Steady::now();
      } else if (Steady::now() - last_progress > std::chrono::seconds(60)) {
        end_reason = "simulated time stalled for 60 s of wall time (see components.log)";
        c.stop(1);
        return;
      }
    }
  });
  const int rc = c.spin();
  done = true;
  watchdog.join();
  faults.release();  // a stopped process cannot stop
  stop_launcher(launcher);
  run.faults = faults.records();
  const double wall = std::chrono::duration<double>(Steady::now() - wall_start).count();
  if (lab) {
    for (auto& k : cuts)
      if (k.begun && !k.ended) lab->set_cut(k.cut.host, false), k.ended = true, k.sim_end = c.clock().now_s();
    const auto netem = lab->stop_helpers();
    // What the network did, beside metrics.json: the hosts, the link, every cut and netem's counts.
    mpgc::json::Json nj;
    nj["deployment"] = o.hosts->origin;
    nj["hosts"] = mpgc::json::Json::object();
    for (const auto& h : o.hosts->hosts) nj["hosts"][h.name] = {{"address", h.address}, {"components", h.components}};
    nj["links"] = mpgc::json::Json::object();
    for (const auto& [h, l] : o.links) nj["links"][h] = l.text();
    nj["link_seed"] = o.link_seed;
    nj["secure"] = !o.secure.empty();
    nj["cuts"] = mpgc::json::Json::array();
    for (const auto& k : cuts)
      nj["cuts"].push_back({{"host", k.cut.host},
                            {"at_s", mpgc::json::number(k.cut.at_s)},
                            {"wall_s", mpgc::json::number(k.cut.duration_s)},
                            {"happened", k.begun},
                            {"sim_begin_s", mpgc::json::number(k.sim_begin)},
                            {"sim_end_s", mpgc::json::number(k.sim_end)},
                            {"plans_during", plans_between(run, k.sim_begin, k.sim_end)}});
    nj["netem"] = mpgc::json::Json::object();
    for (const auto& [h, line] : netem) nj["netem"][h] = line;
    std::ofstream(dir / "network.json") << nj.dump(2) << "\n";
    for (const auto& k : cuts)
      if (k.begun) out.notes.push_back("cut " + k.cut.host + " at sim " + num_text(k.sim_begin) + " s for " +
                                       num_text(k.cut.duration_s, "%.1f") + " s wall (sim " + num_text(k.sim_begin) +
                                       "-" + num_text(k.sim_end) + " s): " +
                                       std::to_string(plans_between(run, k.sim_begin, k.sim_end)) +
                                       " plans arrived meanwhile");
      else out.notes.push_back("cut " + k.cut.host + " at sim " + num_text(k.cut.at_s) + " s never happened (run ended first)");
    for (const auto& [h, line] : netem) out.notes.push_back(h + ": " + line);
  }
  if (rc != 0 || run.t.size() < 2) {
    out.error = end_reason.empty() ? "run aborted" : end_reason;
    return out;
  }

  for (auto& [key, poly] : fixed_polygons) run.obstacles.polygons.push_back(std::move(poly));
  std::vector<mpgc::geom::Vec2> points;
  for (const auto& [x, y] : fixed_points) points.push_back({x, y});
  sr::add_point_obstacles(run.obstacles, points, 0.5);  // point features; boundary points are dropped
  const auto params = sr::evaluation_params(s, run.own.length);
  out.metrics = sr::evaluate(run, params, s.criteria);
  out.metrics.wall_s = wall;
  sr::ReportOptions ro;
  ro.scenario = s.name;
  ro.length_unit = s.plot_in_lpp ? s.lpp : 1.0;
  ro.length_unit_name = s.plot_in_lpp ? "Lpp" : "m";
  sr::write_report(dir.string(), run, out.metrics, ro);
  std::ofstream(dir / "end.txt") << end_reason << "\n";
  out.ran = true;
  return out;
}

std::string num_text(double v, const char* f) {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc_run: sail scenarios closed-loop and evaluate them"};
  std::vector<std::string> files;
  std::string suite;
  Options o;
  app.add_option("scenarios", files, "scenario files (scenarios/*.yaml, or DNV traffic-generator situations *.json)");
  app.add_option("--suite", suite, "a folder of scenarios/ to run (paper, chart), dnv (the 55 DNV situations), all");
  app.add_option("--out", o.out, "output folder (one sub-folder per scenario)");
  app.add_option("--realtime-factor", o.realtime_factor, "watch it: simulated seconds per wall second (0 = lockstep, as fast as possible)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_flag("--quiet", o.quiet, "no progress lines");
  bool late_plans = false;
  app.add_flag("--late-plans", late_plans,
               "lockstep: a plan takes effect after its computing time in simulated time, at the paper's 0.5 s per "
               "20000 iterations (seed 000 §6: the ship follows the old path meanwhile); = --plan-latency 25e-6");
  app.add_option("--plan-latency", o.plan_latency, "lockstep: simulated seconds one planner iteration takes (late plans)")
      ->check(CLI::Range(0.0, 1e-2));
  app.add_option("--domain", o.domain, "DDS domain of the run (default: a free one in 201..230)")->check(CLI::Range(0, 230));
  app.add_flag("--hil", o.hil,
               "hardware in the loop: the simulator as the ship's devices (NMEA/AIS to gpsd, orders on the actuator "
               "wire), mpgc_ship_bridge in its place; at a real-time factor (default 20), outputs in out/<scenario>-hil/");
  std::string hosts_file;
  std::vector<std::string> link;
  std::vector<std::string> cuts;
  app.add_option("--hosts", hosts_file,
                 "across a ship's network: run the components on the hosts of a deployment (deploy/hosts/*.yaml) as "
                 "network namespaces made for the run (root)");
  app.add_option("--link", link,
                 "with --hosts: every host's link, e.g. \"loss 20% delay 50ms\" (jitter 5ms too), or one host's: "
                 "\"autonomy: loss 5%\" (repeatable, later ones win; default: the deployment's)");
  app.add_option("--link-seed", o.link_seed, "with --link: seed of the loss and jitter draws");
  app.add_option("--cut", cuts, "with --hosts: cut HOST off the network at simulated T s for D wall s: HOST@T+D (repeatable)");
  app.add_flag("--containers", o.containers,
               "with --hosts: each host as its own podman container (deploy/container/build-image.sh makes the image)");
  app.add_option("--image", o.image, "with --containers: the runtime image");
  app.add_flag("--capture", o.capture, "with --hosts: tcpdump every host to out/<scenario>/network/<host>.pcap");
  app.add_option("--secure", o.secure,
                 "DDS Security: authenticated, access-controlled, encrypted bus with the certificates and documents of "
                 "this folder (deploy/security/make-pki.sh DIR)");
  CLI11_PARSE(app, argc, argv);
  if (o.hil && o.realtime_factor <= 0) o.realtime_factor = kHilFactor;
  if (late_plans && o.plan_latency == 0.0) o.plan_latency = 25e-6;  // 0.5 s / 20000 iterations
  try {
    if (hosts_file.empty() && (!link.empty() || !cuts.empty() || o.capture || o.containers))
      throw std::invalid_argument("--link, --cut, --capture and --containers need --hosts");
    if (o.containers && dp::run_command({"podman", "image", "exists", o.image}) != 0)
      throw std::invalid_argument("--containers: no image " + o.image + " (make it with deploy/container/build-image.sh)");
    if (!hosts_file.empty()) {
      if (o.hil) throw std::invalid_argument("--hosts and --hil together are not supported yet");
      o.hosts = dp::load(hosts_file);
      for (const char* c : {"ship_simulator", "situational_awareness", "obstacle_manager", "opp", "guidance_control", "scenario_runner"})
        if (!o.hosts->host_of(c)) throw std::invalid_argument(hosts_file + " places no host for " + c);
      o.links = dp::host_links(*o.hosts, link);
      for (const auto& k : cuts) {
        o.cuts.push_back(dp::parse_cut(k));
        if (!o.hosts->host(o.cuts.back().host)) throw std::invalid_argument("--cut " + k + ": no host '" + o.cuts.back().host + "' in " + hosts_file);
      }
      if (!dp::NetnsLab::available()) throw std::invalid_argument("--hosts needs root and ip netns (network namespaces)");
    }
    if (!o.secure.empty()) {
      o.secure = fs::absolute(o.secure).string();
      if (!fs::exists(fs::path(o.secure) / "security.xml"))
        throw std::invalid_argument("--secure " + o.secure + ": no security.xml (make it with deploy/security/make-pki.sh)");
      if (base_cyclone_uri().empty()) throw std::invalid_argument("--secure needs CYCLONEDDS_URI (./mpgc sets it)");
    }
  } catch (const std::exception& e) {
    std::cerr << "mpgc_run: " << e.what() << "\n";
    return 2;
  }

  const char* src = std::getenv("MPGC_SOURCE_DIR");
  const fs::path scen_dir = fs::path(src != nullptr ? src : ".") / "scenarios";
  const char* shared = std::getenv("MPGC_SHARED_DATA");
  const fs::path data_dir = shared != nullptr ? fs::path(shared) : scen_dir.parent_path() / ".." / "shared" / "data";
  if (!suite.empty()) {
    // A suite is a folder of scenario files: scenarios/<suite>/*.yaml, or for dnv the 55 generated
    // DNV situations (*.json, converted on loading); all = paper, chart and dnv.
    std::vector<std::pair<fs::path, std::string>> dirs;
    const std::pair<fs::path, std::string> dnv{data_dir / "encounters" / "dnv" / "baseline_situations_generated", ".json"};
    if (suite == "all") dirs = {{scen_dir / "paper", ".yaml"}, {scen_dir / "chart", ".yaml"}, dnv};
    else if (suite == "dnv") dirs = {dnv};
    else dirs = {{scen_dir / suite, ".yaml"}};
    for (const auto& [d, ext] : dirs) {
      if (!fs::is_directory(d)) {
        std::cerr << "mpgc_run: no suite folder " << d << "\n";
        return 2;
      }
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(d))
        if (e.path().extension() == ext) found.push_back(e.path().string());
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    }
  }
  if (files.empty()) files.push_back((scen_dir / "paper" / "s1_colreg.yaml").string());

  std::vector<sr::Scenario> scenarios;
  for (const auto& f : files) {
    try {
      scenarios.push_back(sr::load_scenario(f));
      if (!scenarios.back().faults.empty() && (!o.secure.empty() || o.containers))
        throw std::invalid_argument(f + " injects faults: not with --secure (a secured bus takes none) or --containers");
    } catch (const std::exception& e) {
      std::cerr << "mpgc_run: " << e.what() << "\n";
      return 2;
    }
  }
  int failed = 0;
  std::vector<std::pair<std::string, Outcome>> results;
  for (const auto& s : scenarios) {
    if (!o.quiet) std::printf("running %s (%s)\n", s.name.c_str(), s.path.c_str());
    Outcome r;
    try {
      r = run_one(s, o);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    failed += (r.ran && r.metrics.passed) ? 0 : 1;
    results.emplace_back(s.name, std::move(r));
  }

  std::printf("\n%-30s %-6s %-5s %9s %9s %8s %7s %7s %8s %7s %7s\n", "scenario", "result", "goal", "min_d_m",
              "d_safe_m", "viol_s", "replans", "relaxed", "plan_p95", "sim_s", "wall_s");
  for (const auto& [name, r] : results) {
    if (!r.ran) {
      std::printf("%-30s %-6s %s\n", name.c_str(), "ERROR", r.error.c_str());
      continue;
    }
    const auto& m = r.metrics;
    std::printf("%-30s %-6s %-5s %9s %9s %8s %7d %7d %8s %7s %7s\n", name.c_str(), m.passed ? "pass" : "FAIL",
                m.goal_reached ? "yes" : "no", num_text(m.min_distance).c_str(), num_text(m.safety_distance).c_str(),
                num_text(m.safety_violation_s).c_str(), m.replans, m.relaxed_plans, num_text(m.planning.p95_ms, "%.1f").c_str(),
                num_text(m.sim_s).c_str(), num_text(m.wall_s, "%.1f").c_str());
    for (const auto& f : m.failures) std::printf("    why: %s\n", f.c_str());
    if (const std::string c = sr::close_calls_text(m); !c.empty()) std::printf("    close: %s\n", c.c_str());
    for (const auto& n : r.notes) std::printf("    network: %s\n", n.c_str());
  }
  std::printf("%zu passed, %d failed   (outputs in %s/<scenario>/: metrics.json, timeseries.csv, trajectory.svg, dtc.svg)\n",
              results.size() - failed, failed, o.out.c_str());
  return failed == 0 ? 0 : 1;
}
