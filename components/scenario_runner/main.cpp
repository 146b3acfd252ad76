// mpgc_run: sails scenarios closed-loop. For each scenario it writes the simulator's world file and
// a launch file, starts the five components through mpgc_launch on loopback DDS (lockstep as fast
// as possible, or a real-time factor), publishes the goal, records ground truth, plans and
// guidance status as a lockstep participant, stops at the goal or the time limit, and evaluates
// the run independently of the planner (metrics.json, timeseries.csv, trajectory.svg, dtc.svg).
// The runner's logic is mpgc/scenario_runner/runner.hpp; this is its wiring (processes, DDS, clocks).
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <spdlog/sinks/null_sink.h>

#include "deployment.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/opp/registry.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/runtime/process.hpp"
#include "mpgc/scenario_runner/baseline.hpp"
#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/scenario_runner/fault_run.hpp"
#include "mpgc/scenario_runner/report.hpp"
#include "mpgc/scenario_runner/runner.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/scenario_runner/scenario_obstacles.hpp"
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

std::string mpgc_source_dir() {
  const char* src = std::getenv("MPGC_SOURCE_DIR");
  return fs::weakly_canonical(src != nullptr ? src : ".").string();
}
std::string shared_data_dir() {
  const char* d = std::getenv("MPGC_SHARED_DATA");
  const fs::path p = d != nullptr ? fs::path(d) : fs::path(mpgc_source_dir()) / ".." / "shared" / "data";
  return fs::exists(p) ? fs::canonical(p).string() : "";
}

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

// [s] user + system CPU time of this process so far.
double own_cpu_s() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return static_cast<double>(r.ru_utime.tv_sec + r.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(r.ru_utime.tv_usec + r.ru_stime.tv_usec);
}

pid_t start_launcher(const std::string& launch, int domain, const std::string& log_path, const std::string& secure) {
  const std::string exe = (fs::canonical("/proc/self/exe").parent_path() / "mpgc_launch").string();
  std::vector<std::string> argv{exe, launch, "--domain", std::to_string(domain)};
  if (!secure.empty()) argv.insert(argv.end(), {"--secure", secure});
  return mpgc::rt::spawn_logged(argv, log_path);
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

// The Cyclone configuration this process was started with (./mpgc exports loopback.xml).
std::string base_cyclone_uri() {
  static const std::string uri = [] {
    const char* u = std::getenv("CYCLONEDDS_URI");
    return std::string(u != nullptr ? u : "");
  }();
  return uri;
}

sr::RunRecorder::Ship ship_of(const msg::ShipTruth& t) {
  return {t.id, t.length, {t.x, t.y, t.heading, t.cog, t.sog}};
}

sr::PlanRecord plan_of(const msg::Path& p, double t) {
  sr::PlanRecord r;
  r.t = t;
  r.plan_id = p.plan_id;
  r.status = p.status == msg::PlanStatus::PLAN_OK        ? sr::PlanStatus::kOk
             : p.status == msg::PlanStatus::PLAN_RELAXED ? sr::PlanStatus::kRelaxed
                                                         : sr::PlanStatus::kNoPath;
  for (const auto& w : p.waypoints) r.waypoints.push_back({w.x, w.y, w.t});
  r.planning_time = p.planning_time;
  return r;
}

msg::FaultKind kind_of(sr::Fault::Kind k) {
  return k == sr::Fault::Kind::kSilence       ? msg::FaultKind::FAULT_SILENCE_TOPIC
         : k == sr::Fault::Kind::kAisOutage   ? msg::FaultKind::FAULT_AIS_OUTAGE
         : k == sr::Fault::Kind::kGnssDropout ? msg::FaultKind::FAULT_GNSS_DROPOUT
                                              : msg::FaultKind::FAULT_POSITION_JUMP;
}

sr::LaunchContext launch_context() {
  sr::LaunchContext ctx;
  ctx.bin_dir = fs::canonical("/proc/self/exe").parent_path().string();
  ctx.source_dir = mpgc_source_dir();
  ctx.shared_dir = shared_data_dir();
  ctx.cwd = fs::current_path().string();
  ctx.root = geteuid() == 0;
  for (const char* v : {"MPGC_SHARED_DATA", "MPGC_SOURCE_DIR"})
    if (std::getenv(v) != nullptr) ctx.env.emplace_back(v, std::getenv(v));
  return ctx;
}

sr::Outcome run_one(const sr::Scenario& s, const sr::RunOptions& o) {
  // The run is judged against the scenario's own chart and shapes (read first: a chart that cannot
  // be read is the run's error before anything starts).
  const char* shared = std::getenv("MPGC_SHARED_DATA");
  sr::FixedObstacles obstacles = sr::scenario_obstacles(s, shared != nullptr ? shared : "");
  sr::Outcome out;
  const fs::path dir = fs::path(o.out) / (o.hil ? s.name + "-hil" : s.name);
  fs::create_directories(dir);
  const std::string world_path = fs::absolute(dir / "world.yaml").string();
  std::ofstream(world_path) << sr::world_file(s, o.hil);
  // A fresh run: no journal or memory of an earlier one to resume from.
  for (const char* f : {"sim_journal.bin", "opp_memory.yaml"}) fs::remove(dir / f);
  // Released when this run is over (a suite used to run out after 30).
  const auto lease = o.domain >= 0 ? std::make_unique<DomainLease>(o.domain) : std::make_unique<DomainLease>();
  const int domain = lease->id();

  // On a deployment's hosts: the namespaces, each host's Cyclone configuration, and this process
  // (the evaluator) moved onto its own host before it joins the bus.
  std::unique_ptr<dp::NetnsLab> lab;
  sr::Placement where;
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
    where.on_hosts = true;
    for (const auto& h : o.hosts->hosts) where.ns[h.name] = lab->ns(h.name);
    where.network_dir = net_dir.string();
    cyclone_uri = "file://" + (net_dir / runner_host / "cyclonedds.xml").string();
  }
  if (!o.secure.empty()) {
    cyclone_uri += ",file://" + o.secure + "/security.xml";
    setenv("MPGC_SECURITY_ID", "scenario_runner", 1);
  }
  setenv("CYCLONEDDS_URI", cyclone_uri.c_str(), 1);
  const std::string launch_path = fs::absolute(dir / "launch.yaml").string();
  // dijkstra-sv's turning-circle tables of this own ship, made for the run when none are given.
  const sr::LaunchContext ctx = launch_context();
  sr::Scenario launched = s;
  const std::string tables = fs::absolute(dir / "turning_tables.csv").string();
  if (const auto cmd = sr::turning_tables_command(s, o.planner, ctx.bin_dir, tables); !cmd.empty()) {
    std::string text;
    if (rt::run_command(cmd, &text) != 0) throw std::runtime_error("dijkstra-sv's turning-circle tables: " + text);
    launched.params["opp"]["plan.dsv.tables"] = tables;
  }
  std::ofstream(launch_path) << sr::launch_file(launched, world_path, o, domain, where, ctx);

  rt::RuntimeParams rp;
  rp.domain = domain;
  rp.clock = "sim";
  rp.lockstep_ack = o.realtime_factor <= 0;
  auto log = std::make_shared<spdlog::logger>("scenario_runner", std::make_shared<spdlog::sinks::null_sink_mt>());
  rt::Component c("scenario_runner", rp, log);

  sr::RunRecorder rec(s, std::move(obstacles));
  msg::GroundTruth truth;
  bool have_truth = false;

  auto& goal_w = c.publisher<msg::MissionGoal>(mpgc::topics::kGoal, dds::QosProfile::latched());
  c.subscribe<msg::GroundTruth>(mpgc::topics::kTruth, dds::QosProfile::state(), [&](const msg::GroundTruth& t) {
    truth = t;
    have_truth = true;
  });
  c.subscribe<msg::Path>(mpgc::topics::kPath, dds::QosProfile::latched(),
                         [&](const msg::Path& p) { rec.plan(plan_of(p, c.clock().now_s())); });
  c.subscribe<msg::GuidanceStatus>(mpgc::topics::kGuidanceStatus, dds::QosProfile::state(),
                                   [&](const msg::GuidanceStatus& g) {
                                     rec.guidance({c.clock().now_s(), g.plan_id, g.active_waypoint, g.cross_track_error});
                                   });

  // Faults of the scenario and the health of the components: which is down, degraded or back.
  pid_t launcher = -1;
  std::mutex fault_mutex;  // `faults`: the record timer, the health samples and the wall-clock watchdog
  // Only a run with faults has the fault topic (a secured bus grants it to nobody).
  dds::Writer<msg::FaultCommand>* fault_w =
      s.faults.empty() ? nullptr : &c.publisher<msg::FaultCommand>(mpgc::topics::kFaults, dds::QosProfile::command(16));
  // The system's health on the wall clock; its news is printed.
  std::mutex health_mutex;  // the executor feeds it, the wall-clock watchdog reads it
  // The health view runs on the simulated clock, as the components' health periods do: in lockstep
  // nobody is stale while the step waits for a plan, and a hung one is once the step goes on without it.
  auto health_ns = [&c] { return c.now_ns(); };
  auto say = [&](const std::string& what) {
    if (!o.quiet) std::fputs(sr::say_line(s.name, c.clock().now_s(), what).c_str(), stdout);
    std::fflush(stdout);
  };
  auto say_all = [&](const std::vector<std::string>& lines) {
    for (const auto& l : lines) say(l);
  };
  const auto run_start = Steady::now();
  auto wall_s = [run_start] { return std::chrono::duration<double>(Steady::now() - run_start).count(); };
  sr::HealthNews health(sr::kRunComponents, health_ns());
  sr::FaultEffects fx;
  fx.pid_of = [&](const std::string& component) { return static_cast<int>(component_pid(launcher, component)); };
  fx.signal = [](int pid, int sig) { kill(pid, sig); };
  fx.command = [&](const sr::Fault& f) {
    msg::FaultCommand fc;
    fc.header = c.header();
    fc.kind = kind_of(f.kind);
    fc.topic = f.topic;
    fc.mmsi = f.mmsi;
    fc.duration = f.duration_s;
    fc.dx = f.dx;
    fc.dy = f.dy;
    fault_w->write(fc);
  };
  fx.killed = [&](const std::string& component) {
    std::lock_guard<std::mutex> hg(health_mutex);
    health.killed(component, health_ns());
  };
  fx.say = say;
  sr::FaultRun faults(s.faults, fx);
  c.subscribe<msg::ComponentHealth>(mpgc::topics::kHealth, dds::QosProfile::latched(), [&](const msg::ComponentHealth& h) {
    const double now = c.clock().now_s();
    bool restarted = false;
    {
      std::lock_guard<std::mutex> g(health_mutex);
      say_all(health.sample(h.component, h.header.seq, static_cast<rt::Reported>(static_cast<int>(h.state)), h.detail,
                            health_ns(), &restarted));
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

  sr::CutSchedule cuts(o.cuts);
  std::mutex cut_mutex;

  std::string end_reason;
  const auto wall_start = Steady::now();
  const double cpu_start = own_cpu_s();
  auto last_print = wall_start;
  c.every(o.record_period, [&] {
    if (!have_truth) return;
    const double t = c.clock().now_s();
    if (!rec.fresh(t)) return;
    {
      std::lock_guard<std::mutex> g(cut_mutex);
      for (const sr::CutState* k : cuts.begin(t, wall_s())) {
        lab->set_cut(k->cut.host, true);
        if (!o.quiet) std::fputs(sr::cut_line(s.name, t, k->cut).c_str(), stdout);
      }
    }
    if (!s.faults.empty()) {
      std::lock_guard<std::mutex> g(fault_mutex);
      faults.at_sim(t, wall_s());
    }
    std::vector<sr::RunRecorder::Ship> targets;
    for (const auto& tt : truth.targets) targets.push_back(ship_of(tt));
    const auto to_goal = rec.record(t, ship_of(truth.own), targets);
    if (!to_goal) return;
    if (!o.quiet && Steady::now() - last_print > std::chrono::seconds(2)) {
      last_print = Steady::now();
      std::fputs(sr::progress_line(s.name, t, *to_goal, rec.run().plans.size(),
                                   std::chrono::duration<double>(last_print - wall_start).count())
                     .c_str(),
                 stdout);
      std::fflush(stdout);
    }
    end_reason = rec.end_reason(t, *to_goal);
    if (!end_reason.empty()) c.stop(0);
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
        for (const sr::CutState* k : cuts.end(wall_s(), c.clock().now_s())) {
          lab->set_cut(k->cut.host, false);
          last_progress = Steady::now();  // a stalled clock during the cut is the cut's doing
        }
      }
      {
        std::lock_guard<std::mutex> g(fault_mutex);
        if (faults.at_wall(wall_s(), c.clock().now_s())) last_progress = Steady::now();  // the stalled clock was the stop's doing
      }
      {
        std::lock_guard<std::mutex> g(health_mutex);
        say_all(health.changes(health_ns()));  // stale ones, which no sample announces
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
  sr::RunRecord& run = rec.run();
  run.faults = faults.records();
  const double wall = std::chrono::duration<double>(Steady::now() - wall_start).count();
  if (lab) {
    for (const sr::CutState* k : cuts.end_all(c.clock().now_s())) lab->set_cut(k->cut.host, false);
    const auto netem = lab->stop_helpers();
    std::ofstream(dir / "network.json") << sr::network_json(o, cuts.cuts(), run, netem);
    out.notes = sr::network_notes(cuts.cuts(), run, netem);
  }
  if (rc != 0 || run.t.size() < 2) {
    out.error = end_reason.empty() ? "run aborted" : end_reason;
    return out;
  }

  out.metrics = rec.evaluate(wall);
  {
    std::ifstream components_log(dir / "components.log");
    std::stringstream text;
    text << components_log.rdbuf();
    out.metrics.components = sr::component_usage(text.str());
    // The runner itself (lockstep clock, recording for the evaluation) during this scenario; its
    // peak is the process's so far (a suite runs in one process).
    rusage self{};
    getrusage(RUSAGE_SELF, &self);
    out.metrics.components.push_back({"scenario_runner", static_cast<double>(self.ru_maxrss) / 1024.0, own_cpu_s() - cpu_start});
  }
  sr::ReportOptions ro;
  ro.scenario = s.name;
  ro.length_unit = s.plot_in_lpp ? s.lpp : 1.0;
  ro.length_unit_name = s.plot_in_lpp ? "Lpp" : "m";
  sr::write_report(dir.string(), run, out.metrics, ro);
  std::ofstream(dir / "end.txt") << end_reason << "\n";
  out.ran = true;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc_run: sail scenarios closed-loop and evaluate them"};
  std::vector<std::string> files;
  std::string suite;
  sr::RunOptions o;
  sr::RunCommandLine cl;
  app.add_option("scenarios", files, "scenario files (scenarios/*.yaml, or DNV traffic-generator situations *.json)");
  app.add_option("--suite", suite, "a folder of scenarios/ to run (paper, chart, faults, rules), dnv (the 55 DNV situations), all");
  app.add_option("--out", o.out, "output folder (one sub-folder per scenario)");
  app.add_option("--realtime-factor", o.realtime_factor, "watch it: simulated seconds per wall second (0 = lockstep, as fast as possible)")
      ->check(CLI::Range(0.0, 1000.0));
  app.add_flag("--quiet", o.quiet, "no progress lines");
  app.add_flag("--no-record{false}", o.record,
               "no recording of the bus (<run>/run.mcap): one process fewer, for runs judged by their metrics only");
  app.add_option("--planner", o.planner, "the planner behind opp's planning interface (sets opp plan.planner)")
      ->check(CLI::IsMember(mpgc::opp::planner_names()));
  std::string baseline_file;
  app.add_option("--baseline", baseline_file,
                 "judge against a ratchet (scenarios/baseline.json): fail only when a scenario listed as passing, or "
                 "not listed, does not pass or a run breaks; known failures and new passes are reported");
  app.add_flag("--view", cl.view,
               "watch it live: the recorder serves a web page and Foxglove's WebSocket on 127.0.0.1:8765 (at "
               "--realtime-factor 10 unless one is given)");
  app.add_flag("--late-plans", cl.late_plans,
               "lockstep: a plan takes effect after its computing time in simulated time, at the paper's 0.5 s per "
               "20000 iterations (seed 000 §6: the ship follows the old path meanwhile); = --plan-latency 25e-6");
  app.add_option("--plan-latency", o.plan_latency, "lockstep: simulated seconds one planner iteration takes (late plans)")
      ->check(CLI::Range(0.0, 1e-2));
  app.add_option("--domain", o.domain, "DDS domain of the run (default: a free one in 201..230)")->check(CLI::Range(0, 230));
  app.add_flag("--hil", o.hil,
               "hardware in the loop: the simulator as the ship's devices (NMEA/AIS to gpsd, orders on the actuator "
               "wire), mpgc_ship_bridge in its place; at a real-time factor (default 20), outputs in out/<scenario>-hil/");
  app.add_option("--hosts", cl.hosts_file,
                 "across a ship's network: run the components on the hosts of a deployment (deploy/hosts/*.yaml) as "
                 "network namespaces made for the run (root)");
  app.add_option("--link", cl.links,
                 "with --hosts: every host's link, e.g. \"loss 20% delay 50ms\" (jitter 5ms too), or one host's: "
                 "\"autonomy: loss 5%\" (repeatable, later ones win; default: the deployment's)");
  app.add_option("--link-seed", o.link_seed, "with --link: seed of the loss and jitter draws");
  app.add_option("--cut", cl.cuts, "with --hosts: cut HOST off the network at simulated T s for D wall s: HOST@T+D (repeatable)");
  app.add_flag("--containers", o.containers,
               "with --hosts: each host as its own podman container (deploy/container/build-image.sh makes the image)");
  app.add_option("--image", o.image, "with --containers: the runtime image");
  app.add_flag("--capture", o.capture, "with --hosts: tcpdump every host to out/<scenario>/network/<host>.pcap");
  app.add_option("--secure", o.secure,
                 "DDS Security: authenticated, access-controlled, encrypted bus with the certificates and documents of "
                 "this folder (deploy/security/make-pki.sh DIR)");
  CLI11_PARSE(app, argc, argv);
  try {
    sr::resolve_options(o, cl);
    if (o.containers && dp::run_command({"podman", "image", "exists", o.image}) != 0)
      throw std::invalid_argument("--containers: no image " + o.image + " (make it with deploy/container/build-image.sh)");
    if (o.hosts && !dp::NetnsLab::available())
      throw std::invalid_argument("--hosts needs root and ip netns (network namespaces)");
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
  std::vector<sr::Scenario> scenarios;
  try {
    for (const auto& f : sr::scenario_files(files, suite, scen_dir.string(), data_dir.string())) {
      scenarios.push_back(sr::load_scenario(f));
      if (!scenarios.back().faults.empty() && (!o.secure.empty() || o.containers))
        throw std::invalid_argument(f + " injects faults: not with --secure (a secured bus takes none) or --containers");
    }
  } catch (const std::exception& e) {
    std::cerr << "mpgc_run: " << e.what() << "\n";
    return 2;
  }
  std::optional<sr::Baseline> baseline;
  try {
    if (!baseline_file.empty()) baseline = sr::read_baseline(baseline_file);
  } catch (const std::exception& e) {
    std::cerr << "mpgc_run: --baseline " << e.what() << "\n";
    return 2;
  }
  if (o.view_port > 0)
    std::printf("live view: http://127.0.0.1:%d/  (Foxglove: Open connection, ws://127.0.0.1:%d)\n", o.view_port, o.view_port);
  int failed = 0;
  std::vector<std::pair<std::string, sr::Outcome>> results;
  for (const auto& s : scenarios) {
    if (!o.quiet) std::printf("running %s (%s)\n", s.name.c_str(), s.path.c_str());
    sr::Outcome r;
    try {
      r = run_one(s, o);
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    failed += r.passed() ? 0 : 1;
    results.emplace_back(s.name, std::move(r));
  }
  std::fputs(sr::summary(results, o.out).c_str(), stdout);
  if (!baseline) return failed == 0 ? 0 : 1;
  std::vector<sr::Judged> judged;
  // Another planner's run of a scenario is its own entry of the ratchet: NAME@PLANNER.
  const std::string suffix = o.planner.empty() ? "" : "@" + o.planner;
  for (const auto& [name, r] : results)
    judged.push_back({name + suffix,
                      !r.error.empty() || !r.ran ? sr::Result::kError : (r.passed() ? sr::Result::kPassed : sr::Result::kFailed),
                      r.metrics.failures});
  const sr::Ratchet ratchet = sr::judge(*baseline, judged);
  std::fputs(sr::describe(ratchet, baseline_file).c_str(), stdout);
  return ratchet.ok() ? 0 : 1;
}
