// ./mpgc bench chain (issue 20 part 4): the latency of the autonomy chain on the wall clock over
// loopback DDS, next to ddsperf's one-hop latency measured in the same command, and the cost of
// copying a large sample (1e5-point FixedObstacles) through the C++ layer.
//
// The chain: this process plays the sensors (sensors/ais; also nav/own_state and mission/goal, so
// that opp has a plan and guidance_control follows it) and the ship (it reads control/actuators):
//
//   sensors/ais -> situational_awareness -> sa/tracks -> obstacle_manager -> obstacles/moving
//     -> opp -> plan/path -> guidance_control -> control/actuators (+ guidance/status)
//
// The four components are the real processes (mpgc_<name> from --bin-dir), on the wall clock. The
// bench listens to every intermediate topic and stamps each sample's arrival here (one clock,
// CLOCK_MONOTONIC); a hop is the time between the arrivals of the outputs of two stages, so each
// contains one DDS hop, the receiving component's wait for its timer and its work.
//
// Attributing outputs to inputs (every component is timer-driven, so outputs are not 1:1 with
// inputs): each injected sample is an AIS report of a ship never seen before (a fresh MMSI), so
// the first output of each stage that reflects it is identified by content, not by timing:
//   1. sa/tracks: the first TrackList holding a track with that MMSI (AIS tracks are confirmed at
//      once, mpgc/situational_awareness/tracker.cpp);
//   2. obstacles/moving: the first MovingObstacles holding an obstacle with that MMSI;
//   3. plan/path: opp re-plans on a new target ("new target", replan.hpp); the first Path stamped
//      at or after that MovingObstacles sample. To make that plan the only one, opp runs with
//      replan.period = 3600 s (no periodic plan) and replan.min_interval = 0 (by default an
//      event-triggered plan waits 2 s after the last one: a policy delay, not latency);
//   4. control/actuators: the first GuidanceStatus following that plan_id, and the ActuatorCommand
//      guidance_control wrote in the same cycle (same header stamp).
// The bench injects the next sample only when the previous one reached the actuators, after a
// random pause up to the slowest timer period (so injections fall at every phase of the timers).
// Old targets are deleted by situational_awareness after tracker.delete_after (set short), so the
// planning problem does not grow; a vanished target triggers no plan.
//
// opp runs its planner (rrtstar at its default budget) on each new target; the plan's own
// planning_time is reported, and the chain without it is "with a cached plan": what the chain
// costs when opp's answer is ready at once.
//
// Rows: "default" with every component's own timer periods (0.5 s each), "fast" with them at their
// minimum (situational_awareness period 0.01 s, obstacle_manager moving.period 0.01 s, opp
// replan.check_period 0.01 s, guidance_control rate 50 Hz). The components' defaults are unchanged.
// Each row's samples are shared out over several fresh starts of the components (--starts), started
// at random offsets: see run_start.
//
// Every process of the bench, ddsperf included, uses the loopback configuration (the embedded
// deploy/cyclonedds/loopback.xml), whatever CYCLONEDDS_URI says.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "mpgc/dds/dds.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/geo/geodesy.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/core.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/runtime/process.hpp"
#include "mpgc/topics.hpp"

namespace dds = mpgc::dds;
namespace msg = mpgc::msg;
namespace geo = mpgc::geo;
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

double mono_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
int64_t mono_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
int64_t wall_ns() {  // header stamps: the components run on the wall clock
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

struct Stats {
  double median = NAN, p99 = NAN;
  std::size_t n = 0;
};
Stats stats(std::vector<double> v) {
  Stats s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  s.median = v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(v.size())));  // nearest rank
  s.p99 = v[std::max<std::size_t>(rank, 1) - 1];
  return s;
}
json to_json(const Stats& s) {
  return {{"median", s.median}, {"p99", s.p99}, {"n", s.n}};
}

// A DDS domain no concurrent test or bench uses: the tests' lock files (tests/support/testing.cpp).
int lock_domain() {
  for (int id = 1 + getpid() % 200, n = 0; n < 200; ++n, id = id % 200 + 1) {
    const std::string path = "/tmp/mpgc-test-domain-" + std::to_string(id) + ".lock";
    const int fd = open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0666);
    if (fd < 0) continue;
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) return id;  // held until exit
    close(fd);
  }
  throw std::runtime_error("no free DDS domain in 1..200");
}

// A child process in its own group, ended (SIGTERM, then SIGKILL) when this goes out of scope.
class Child {
 public:
  Child(const std::vector<std::string>& argv, const std::string& log) : name_(argv.at(0)) {
    pid_ = mpgc::rt::spawn_logged(argv, log);
    if (pid_ <= 0) throw std::runtime_error("cannot start " + name_);
  }
  ~Child() { stop(); }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  bool running() {
    if (pid_ <= 0) return false;
    int st = 0;
    if (waitpid(pid_, &st, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }
  void stop() {
    if (pid_ <= 0) return;
    kill(-pid_, SIGTERM);
    for (int i = 0; i < 300; ++i) {  // 3 s
      int st = 0;
      if (waitpid(pid_, &st, WNOHANG) == pid_) {
        pid_ = -1;
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    kill(-pid_, SIGKILL);
    mpgc::rt::wait_exit(pid_);
    pid_ = -1;
  }
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  pid_t pid_ = -1;
};

// Readers on one waitset: wait() returns when any has data (or after the timeout).
class Pump {
 public:
  explicit Pump(dds::Participant& p) : ws_(dds_create_waitset(p.handle())) {
    if (ws_ < 0) throw std::runtime_error("dds_create_waitset failed");
  }
  ~Pump() { dds_delete(ws_); }
  template <class T>
  void add(dds::Reader<T>& r) {
    const dds_entity_t cond = dds_create_readcondition(r.handle(), DDS_ANY_STATE);
    dds::check(cond, "read condition on " + r.topic());
    dds::check(dds_waitset_attach(ws_, cond, 0), "waitset attach");
  }
  void wait(double timeout_s) {
    dds_attach_t xs[8];
    dds_waitset_wait(ws_, xs, 8, static_cast<dds_duration_t>(timeout_s * 1e9));
  }

 private:
  dds_entity_t ws_;
};

// State samples: the writers are best-effort keep-last 1; a deeper reader loses none to a slow take.
dds::QosProfile state_reader() {
  dds::QosProfile q = dds::QosProfile::state();
  q.depth = 32;
  return q;
}

struct Row {
  std::string name;
  double sa_period, om_period, opp_check, gc_rate;  // [s] [s] [s] [Hz]
  double delete_after;                               // [s] situational_awareness tracker.delete_after
  double max_period() const { return std::max({sa_period, om_period, opp_check, 1.0 / gc_rate}); }
};

struct RowResult {
  std::vector<double> hop[4];   // [ms] ais->tracks, tracks->moving, moving->path, path->actuators
  std::vector<double> e2e;      // [ms]
  std::vector<double> planning;  // [ms] opp's planning_time of the plan in the chain
  std::vector<double> cached;    // [ms] e2e - planning
  int lost = 0;
};

const char* kHopNames[4] = {"sensors/ais -> sa/tracks", "sa/tracks -> obstacles/moving", "obstacles/moving -> plan/path",
                            "plan/path -> control/actuators"};
const char* kHopKeys[4] = {"ais_to_tracks", "tracks_to_moving", "moving_to_path", "path_to_actuators"};
constexpr int kChainDdsHops = 5;  // bench->sa, sa->om, om->opp, opp->gc, gc->bench

// The scene: own ship at the origin sailing north at 5 m/s towards a goal 10 km north, open water
// (no chart: obstacle_manager publishes an empty region). Targets are stationary ships 2 km ahead
// and 3 km to starboard of the own ship, clear of its route.
constexpr double kOriginLat = 59.0, kOriginLon = 10.6;  // [deg] Oslofjord, any open water does
constexpr double kSpeed = 5.0;                         // [m/s]

// One start of the four components: `samples` samples measured into `res`. The components are
// started at random offsets (up to the slowest period) from each other: timers of equal period in
// different processes keep their relative phase for the life of the processes, so the hops between
// them are set by these offsets, and only several starts sample them.
void run_start(const Row& row, int start, int samples, int domain, const std::string& bin, const std::string& logs,
               uint32_t seed, bool verbose, RowResult& res) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pause(0.0, row.max_period());
  auto stagger = [&] { std::this_thread::sleep_for(std::chrono::duration<double>(pause(rng))); };
  const std::string tag = logs + "/" + row.name + "-" + std::to_string(start) + "-";
  const std::string d = std::to_string(domain);
  const std::string lat = std::to_string(kOriginLat), lon = std::to_string(kOriginLon);
  auto args = [&](const std::string& exe, std::vector<std::string> sets) {
    std::vector<std::string> a = {bin + "/" + exe, "--domain", d, "--log-level", "warn"};
    for (auto& s : sets) a.insert(a.end(), {"--set", s});
    return a;
  };
  auto num = [](double x) {
    std::ostringstream os;
    os << x;
    return os.str();
  };
  std::vector<std::unique_ptr<Child>> procs;
  procs.push_back(std::make_unique<Child>(
      args("mpgc_situational_awareness", {"origin.source=param", "origin.lat=" + lat, "origin.lon=" + lon,
                                          "period=" + num(row.sa_period), "tracker.delete_after=" + num(row.delete_after),
                                          "tracker.coast_after=" + num(0.5 * row.delete_after)}),
      tag + "situational_awareness.log"));
  stagger();
  procs.push_back(std::make_unique<Child>(
      args("mpgc_obstacle_manager", {"chart.origin_lat=" + lat, "chart.origin_lon=" + lon, "moving.period=" + num(row.om_period)}),
      tag + "obstacle_manager.log"));
  stagger();
  procs.push_back(std::make_unique<Child>(
      args("mpgc_opp", {"replan.period=3600", "replan.min_interval=0", "replan.check_period=" + num(row.opp_check)}),
      tag + "opp.log"));
  stagger();
  procs.push_back(std::make_unique<Child>(args("mpgc_guidance_control", {"rate=" + num(row.gc_rate)}),
                                          tag + "guidance_control.log"));

  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::NavState> nav_t(part, mpgc::topics::kOwnState);
  dds::Topic<msg::MissionGoal> goal_t(part, mpgc::topics::kGoal);
  dds::Topic<msg::AisReport> ais_t(part, mpgc::topics::kAis);
  dds::Topic<msg::TrackList> tracks_t(part, mpgc::topics::kTracks);
  dds::Topic<msg::MovingObstacles> moving_t(part, mpgc::topics::kMovingObstacles);
  dds::Topic<msg::Path> path_t(part, mpgc::topics::kPath);
  dds::Topic<msg::ActuatorCommand> act_t(part, mpgc::topics::kActuators);
  dds::Topic<msg::GuidanceStatus> status_t(part, mpgc::topics::kGuidanceStatus);
  dds::Writer<msg::NavState> nav_w(part, nav_t, dds::QosProfile::state());
  dds::Writer<msg::MissionGoal> goal_w(part, goal_t, dds::QosProfile::latched());
  dds::Writer<msg::AisReport> ais_w(part, ais_t, dds::QosProfile::command(64));
  dds::Reader<msg::TrackList> tracks_r(part, tracks_t, state_reader());
  dds::Reader<msg::MovingObstacles> moving_r(part, moving_t, state_reader());
  dds::Reader<msg::Path> path_r(part, path_t, dds::QosProfile::latched(8));
  dds::Reader<msg::ActuatorCommand> act_r(part, act_t, dds::QosProfile::command(64));
  dds::Reader<msg::GuidanceStatus> status_r(part, status_t, state_reader());
  Pump pump(part);
  pump.add(tracks_r);
  pump.add(moving_r);
  pump.add(path_r);
  pump.add(act_r);
  pump.add(status_r);

  const geo::LocalNed ned({geo::deg2rad(kOriginLat), geo::deg2rad(kOriginLon)});
  const double t_start = mono_s();
  auto own_x = [&] { return kSpeed * (mono_s() - t_start); };

  // nav/own_state at 20 Hz from a thread of its own (the own ship's navigation sensors).
  std::atomic<bool> feeding{true};
  std::thread feeder([&] {
    while (feeding && !g_stop) {
      msg::NavState s{};
      s.header.stamp_ns = wall_ns();
      s.header.source = "bench_chain";
      s.x = own_x();
      const geo::LatLon ll = ned.to_latlon({s.x, 0.0});
      s.lat = ll.lat;
      s.lon = ll.lon;
      s.heading = s.cog = 0.0;
      s.sog = s.u = kSpeed;
      s.valid_mask = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID | msg::NAV_RATE_VALID;
      nav_w.write(s);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  struct Join {
    std::atomic<bool>& flag;
    std::thread& t;
    ~Join() {
      flag = false;
      t.join();
    }
  } join{feeding, feeder};

  msg::MissionGoal g{};
  g.header.stamp_ns = wall_ns();
  g.header.source = "bench_chain";
  g.goal_id = 1;
  g.x = 10000.0;
  g.y = 0.0;
  g.heading = NAN;
  g.heading_tolerance = 0.0;
  g.cruise_speed = kSpeed;
  g.safety_distance = 500.0;
  g.colreg = true;
  goal_w.write(g);

  // What arrived, by topic; the stages below look for the sample they wait for.
  std::map<int64_t, double> act_arrival;  // actuator command header stamp -> arrival [s]
  auto check_alive = [&] {
    for (auto& p : procs)
      if (!p->running()) throw std::runtime_error(p->name() + " exited (log in " + logs + ")");
  };

  // Warm-up: the first plan is followed (guidance/status names it) and the AIS writer is matched.
  uint32_t followed = 0;
  const double warm_until = mono_s() + 60.0;
  while (!g_stop && (followed == 0 || ais_w.matched() == 0)) {
    if (mono_s() > warm_until) throw std::runtime_error("no plan followed within 60 s (logs in " + logs + ")");
    check_alive();
    pump.wait(0.1);
    tracks_r.take();
    moving_r.take();
    path_r.take();
    act_r.take();
    for (const auto& s : status_r.take())
      if (s.value.plan_id > 0 && s.value.mode == msg::GuidanceMode::GUIDANCE_FOLLOWING) followed = s.value.plan_id;
  }
  if (verbose) std::cerr << row.name << " start " << start << ": warm after " << mono_s() - t_start << " s, following plan " << followed << "\n";

  const double sample_timeout = std::max(5.0, 6.0 * row.max_period() + 2.0);  // + opp's 0.5 s budget
  for (int k = 0; k < samples && !g_stop; ++k) {
    // Settle: a random pause, draining everything.
    const double settle_until = mono_s() + 0.01 + pause(rng);
    while (mono_s() < settle_until) {
      pump.wait(std::max(0.0, settle_until - mono_s()));
      tracks_r.take(), moving_r.take(), path_r.take(), act_r.take(), status_r.take();
    }
    act_arrival.clear();
    check_alive();

    const uint32_t mmsi = 257000000u + static_cast<uint32_t>(k) + 10000u * static_cast<uint32_t>(start);
    msg::AisReport r{};
    r.header.source = "bench_chain";
    r.mmsi = mmsi;
    r.ais_class = msg::AisClass::AIS_CLASS_A;
    const geo::LatLon ll = ned.to_latlon({own_x() + 2000.0, 3000.0});
    r.lat = ll.lat;
    r.lon = ll.lon;
    r.cog = 0.0;
    r.sog = 0.0;
    r.heading = r.rot = NAN;
    r.nav_status = 15;
    r.length = 100.0;
    r.beam = NAN;
    r.ship_type = -1;
    r.header.stamp_ns = r.report_time_ns = wall_ns();
    const double t0 = mono_s();
    ais_w.write(r);

    double a[4] = {NAN, NAN, NAN, NAN};
    int64_t moving_stamp = 0;
    uint32_t plan_id = 0;
    double planning_s = NAN;
    int64_t status_stamp = 0;  // the guidance cycle that first followed the plan
    int stage = 0;
    const double give_up = t0 + sample_timeout;
    while (stage < 4 && !g_stop && mono_s() < give_up) {
      pump.wait(0.05);
      const double now = mono_s();  // arrival: the wake-up that took the sample
      for (const auto& s : tracks_r.take())
        if (stage == 0)
          for (const auto& t : s.value.tracks)
            if (t.mmsi == mmsi) a[0] = now, stage = 1;
      for (const auto& s : moving_r.take())
        if (stage == 1)
          for (const auto& o : s.value.obstacles)
            if (o.mmsi == mmsi) a[1] = now, moving_stamp = s.value.header.stamp_ns, stage = 2;
      for (const auto& s : path_r.take())
        if (stage == 2 && s.value.header.stamp_ns >= moving_stamp)
          a[2] = now, plan_id = s.value.plan_id, planning_s = s.value.planning_time, stage = 3;
      for (const auto& s : act_r.take()) act_arrival[s.value.header.stamp_ns] = now;
      for (const auto& s : status_r.take())
        if (stage == 3 && status_stamp == 0 && s.value.plan_id == plan_id) status_stamp = s.value.header.stamp_ns;
      if (stage == 3 && status_stamp != 0)
        if (const auto it = act_arrival.find(status_stamp); it != act_arrival.end()) a[3] = it->second, stage = 4;
    }
    if (stage < 4) {
      ++res.lost;
      if (verbose) std::cerr << row.name << ": sample " << k << " lost at stage " << stage << "\n";
      continue;
    }
    const double e2e = (a[3] - t0) * 1e3;
    res.hop[0].push_back((a[0] - t0) * 1e3);
    for (int h = 1; h < 4; ++h) res.hop[h].push_back((a[h] - a[h - 1]) * 1e3);
    res.e2e.push_back(e2e);
    res.planning.push_back(planning_s * 1e3);
    res.cached.push_back(e2e - planning_s * 1e3);
    if (verbose)
      std::cerr << row.name << " " << k << ": " << (a[0] - t0) * 1e3 << " " << (a[1] - a[0]) * 1e3 << " "
                << (a[2] - a[1]) * 1e3 << " " << (a[3] - a[2]) * 1e3 << " ms (plan " << plan_id << ", "
                << planning_s * 1e3 << " ms planning)\n";
  }
}

// ddsperf ping/pong over the same configuration: round trip of 12-byte samples [us]. The median
// and the 99 % of each one-second report after the first (warm-up) are taken; their medians are
// returned.
std::optional<Stats> ddsperf_rtt(int domain, int seconds, const std::string& logs) {
  const std::string d = std::to_string(domain);
  Child pong({"ddsperf", "-i", d, "-D", std::to_string(seconds + 2), "pong"}, logs + "/ddsperf-pong.log");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::string out;
  const int rc = mpgc::rt::run_command({"ddsperf", "-i", d, "-D", std::to_string(seconds), "ping"}, &out);
  pong.stop();
  std::ofstream(logs + "/ddsperf-ping.log") << out;
  if (rc != 0) return std::nullopt;
  const std::regex line(R"(size 12 mean [0-9.]+us min [0-9.]+us 50% ([0-9.]+)us 90% [0-9.]+us 99% ([0-9.]+)us)");
  std::vector<double> med, p99;
  std::istringstream is(out);
  std::string l;
  while (std::getline(is, l)) {
    std::smatch m;
    if (!std::regex_search(l, m, line)) continue;
    med.push_back(std::stod(m[1]));
    p99.push_back(std::stod(m[2]));
  }
  if (med.size() > 1) {  // the first second is the warm-up
    med.erase(med.begin());
    p99.erase(p99.begin());
  }
  if (med.empty()) return std::nullopt;
  Stats s;
  s.median = stats(med).median;
  s.p99 = stats(p99).median;
  s.n = med.size();
  return s;
}

// --- the copy of a large sample ---------------------------------------------------------------
constexpr const char* kCopyTopic = "bench/fixed";
constexpr const char* kCopyAck = "bench/fixed_ack";

// The other end of the write -> take: takes each FixedObstacles (Reader::take converts it to the
// C++ type) and answers with the CLOCK_MONOTONIC time after the take (msg::Clock: time_ns, step =
// the sample's version). Version 0 ends it.
int copy_sink(int domain) {
  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::FixedObstacles> t(part, kCopyTopic);
  dds::Topic<msg::Clock> ack_t(part, kCopyAck);
  dds::Reader<msg::FixedObstacles> r(part, t, dds::QosProfile::latched());
  dds::Writer<msg::Clock> w(part, ack_t, dds::QosProfile::command());
  Pump pump(part);
  pump.add(r);
  const double until = mono_s() + 600.0;
  while (!g_stop && mono_s() < until) {
    pump.wait(0.5);
    for (const auto& s : r.take(4)) {
      const int64_t done = mono_ns();
      if (s.value.version == 0) return 0;
      if (s.value.points.empty()) return 3;
      msg::Clock c{};
      c.time_ns = done;
      c.step = s.value.version;
      w.write(c);
    }
  }
  return g_stop ? 0 : 2;
}

struct CopyResult {
  std::size_t points = 0;
  double mbytes = 0;
  Stats to_c, from_c, write, write_take;  // [ms]
};

CopyResult copy_cost(int domain, std::size_t points, int reps, const std::string& self, const std::string& logs) {
  CopyResult res;
  res.points = points;
  msg::FixedObstacles v{};
  v.header.stamp_ns = wall_ns();
  v.header.source = "bench_chain";
  v.chart = "bench";
  v.point_spacing = 20.0;
  v.region_min_x = v.region_min_y = -1e4;
  v.region_max_x = v.region_max_y = 1e4;
  v.points.resize(points);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  for (auto& p : v.points) p = {u(rng), u(rng)};
  res.mbytes = static_cast<double>(points * 2 * sizeof(double)) / 1e6;

  // Conversion to and from the C type idlc generates (what every write and take does).
  std::vector<double> to_c_ms, from_c_ms;
  for (int i = 0; i < reps; ++i) {
    dds::Arena arena;
    msg::FixedObstacles::CType c{};
    const int64_t t0 = mono_ns();
    to_c(v, c, arena);
    const int64_t t1 = mono_ns();
    msg::FixedObstacles back;
    from_c(c, back);
    const int64_t t2 = mono_ns();
    if (back.points.size() != points || back.points.back().x != v.points.back().x)
      throw std::runtime_error("copy: the conversion lost points");
    to_c_ms.push_back((t1 - t0) * 1e-6);
    from_c_ms.push_back((t2 - t1) * 1e-6);
  }
  res.to_c = stats(to_c_ms);
  res.from_c = stats(from_c_ms);

  // write -> take in another process over loopback (reliable, transient-local: obstacles/fixed's QoS).
  Child sink({self, "--copy-sink", "--domain", std::to_string(domain)}, logs + "/copy-sink.log");
  dds::Participant part(static_cast<uint32_t>(domain));
  dds::Topic<msg::FixedObstacles> t(part, kCopyTopic);
  dds::Topic<msg::Clock> ack_t(part, kCopyAck);
  dds::Writer<msg::FixedObstacles> w(part, t, dds::QosProfile::latched());
  dds::Reader<msg::Clock> ack_r(part, ack_t, dds::QosProfile::command());
  Pump pump(part);
  pump.add(ack_r);
  const double match_until = mono_s() + 20.0;
  while (!g_stop && (w.matched() == 0 || ack_r.matched() == 0)) {
    if (mono_s() > match_until || !sink.running()) throw std::runtime_error("copy: the sink did not match");
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // both directions discovered
  std::vector<double> write_ms, take_ms;
  for (int i = 0; i < reps && !g_stop; ++i) {
    v.version = static_cast<uint32_t>(i + 1);
    const int64_t t0 = mono_ns();
    w.write(v);
    const int64_t t1 = mono_ns();
    const double give_up = mono_s() + 10.0;
    std::optional<int64_t> done;
    while (!done && mono_s() < give_up) {
      pump.wait(0.5);
      for (const auto& s : ack_r.take())
        if (s.value.step == v.version) done = s.value.time_ns;
    }
    if (!done) throw std::runtime_error("copy: sample " + std::to_string(v.version) + " not taken within 10 s");
    write_ms.push_back((t1 - t0) * 1e-6);
    take_ms.push_back((*done - t0) * 1e-6);
  }
  v.version = 0;  // ends the sink
  v.points.resize(1);
  w.write(v);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  res.write = stats(write_ms);
  res.write_take = stats(take_ms);
  return res;
}

std::string fmt(double x, int prec = 2) {
  if (!std::isfinite(x)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", prec, x);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc_bench_chain: latency of sensors/ais -> situational_awareness -> obstacle_manager -> opp -> "
               "guidance_control -> control/actuators on the wall clock over loopback DDS, beside ddsperf's one hop, "
               "and the cost of copying a 1e5-point FixedObstacles through the C++ layer"};
  int samples = 200;
  int starts = 5;
  std::string rows_arg = "default,fast";
  int ddsperf_s = 5;
  int copy_reps = 15;
  std::size_t points = 100000;
  std::string bin_dir;
  std::string logs;
  int domain = -1;
  uint32_t seed = 1;
  bool verbose = false;
  bool sink = false;
  app.add_option("--samples", samples, "injected samples per row")->check(CLI::PositiveNumber);
  app.add_option("--starts", starts, "fresh starts of the components per row (the samples are shared out)")
      ->check(CLI::PositiveNumber);
  app.add_option("--rows", rows_arg, "rows: default (the components' own timer periods), fast (their minimum)");
  app.add_option("--ddsperf-seconds", ddsperf_s, "ddsperf ping duration [s]; 0 skips it")->check(CLI::NonNegativeNumber);
  app.add_option("--copy-reps", copy_reps, "repetitions of the large-sample copy; 0 skips it")->check(CLI::NonNegativeNumber);
  app.add_option("--points", points, "points of the large FixedObstacles")->check(CLI::PositiveNumber);
  app.add_option("--bin-dir", bin_dir, "where the component executables are (default: this program's folder)");
  app.add_option("--logs", logs, "folder for the processes' logs (default: a new folder under /tmp)");
  app.add_option("--domain", domain, "DDS domain (default: a free one of 1..200)");
  app.add_option("--seed", seed, "seed of the pauses between samples and between the components' starts");
  app.add_flag("-v,--verbose", verbose, "every sample on stderr");
  app.add_flag("--copy-sink", sink, "(internal) the taking end of the copy measurement")->group("");
  CLI11_PARSE(app, argc, argv);

  // Loopback only, for this process and everything it starts (ddsperf too).
  setenv("CYCLONEDDS_URI", dds::loopback_config(), 1);
  signal(SIGINT, on_signal);
  signal(SIGTERM, on_signal);
  signal(SIGPIPE, SIG_IGN);
  if (sink) return copy_sink(domain < 0 ? 0 : domain);

  try {
    const std::string self = fs::canonical("/proc/self/exe").string();
    if (bin_dir.empty()) bin_dir = fs::path(self).parent_path().string();
    if (domain < 0) domain = lock_domain();
    if (logs.empty()) {
      char tmpl[] = "/tmp/mpgc-bench-chain.XXXXXX";
      if (mkdtemp(tmpl) == nullptr) throw std::runtime_error("mkdtemp failed");
      logs = tmpl;
    }
    fs::create_directories(logs);

    std::vector<Row> rows;
    std::stringstream ss(rows_arg);
    for (std::string r; std::getline(ss, r, ',');) {
      if (r == "default") rows.push_back({"default", 0.5, 0.5, 0.5, 2.0, 3.0});
      else if (r == "fast") rows.push_back({"fast", 0.01, 0.01, 0.01, 50.0, 1.0});
      else throw std::runtime_error("unknown row '" + r + "' (default, fast)");
    }

    std::cout << "chain: sensors/ais -> situational_awareness -> obstacle_manager -> opp -> guidance_control -> "
                 "control/actuators\n  wall clock, loopback DDS (deploy/cyclonedds/loopback.xml), domain "
              << domain << ", logs in " << logs << "\n";
    std::cout.flush();

    json out;
    out["bench"] = "chain";
    out["domain"] = domain;
    out["dds_hops_in_chain"] = kChainDdsHops;

    // ddsperf first, on the same domain, before the components add their traffic.
    std::optional<Stats> rtt;
    if (ddsperf_s > 0) {
      rtt = ddsperf_rtt(domain, ddsperf_s, logs);
      if (!rtt) std::cout << "ddsperf: no result (is cyclonedds-tools installed? " << logs << "/ddsperf-ping.log)\n";
    }
    const double one_hop_us = rtt ? rtt->median / 2.0 : NAN;
    const double one_hop_p99_us = rtt ? rtt->p99 / 2.0 : NAN;
    out["ddsperf"] = rtt ? json{{"size_bytes", 12},
                                {"rtt_us_median", rtt->median},
                                {"rtt_us_p99", rtt->p99},
                                {"one_hop_us_median", one_hop_us},
                                {"one_hop_us_p99", one_hop_p99_us},
                                {"reports", rtt->n}}
                         : json(nullptr);

    json jrows = json::array();
    bool ok = true;
    for (const Row& row : rows) {
      if (g_stop) break;
      std::cout << "\nrow " << row.name << ": situational_awareness period " << row.sa_period
                << " s, obstacle_manager moving.period " << row.om_period << " s, opp replan.check_period "
                << row.opp_check << " s, guidance_control rate " << row.gc_rate << " Hz; " << samples
                << " samples over " << starts << " starts\n";
      std::cout.flush();
      RowResult r;
      for (int i = 0; i < starts && !g_stop; ++i) {
        const int n = samples / starts + (i < samples % starts ? 1 : 0);
        if (n > 0) run_start(row, i, n, domain, bin_dir, logs, seed * 1000u + static_cast<uint32_t>(i), verbose, r);
      }
      char line[160];
      std::snprintf(line, sizeof line, "  %-36s %10s %10s\n", "hop", "median ms", "p99 ms");
      std::cout << "\n" << line;
      json hops;
      for (int h = 0; h < 4; ++h) {
        const Stats s = stats(r.hop[h]);
        std::snprintf(line, sizeof line, "  %-36s %10s %10s\n", kHopNames[h], fmt(s.median).c_str(), fmt(s.p99).c_str());
        std::cout << line;
        hops[kHopKeys[h]] = to_json(s);
      }
      const Stats e2e = stats(r.e2e), plan = stats(r.planning), cached = stats(r.cached);
      std::snprintf(line, sizeof line, "  %-36s %10s %10s\n", "end to end", fmt(e2e.median).c_str(), fmt(e2e.p99).c_str());
      std::cout << line;
      std::snprintf(line, sizeof line, "  %-36s %10s %10s\n", "  of which opp's planning", fmt(plan.median).c_str(),
                    fmt(plan.p99).c_str());
      std::cout << line;
      std::snprintf(line, sizeof line, "  %-36s %10s %10s\n", "end to end, cached plan (- planning)",
                    fmt(cached.median).c_str(), fmt(cached.p99).c_str());
      std::cout << line;
      // A sample waits on average half a period at each of the four timers it passes.
      const double timers_ms = 1e3 * 0.5 * (row.sa_period + row.om_period + row.opp_check + 1.0 / row.gc_rate);
      std::snprintf(line, sizeof line, "  %-36s %10s\n", "  the timers' mean wait (half periods)", fmt(timers_ms).c_str());
      std::cout << line;
      const double hops_ms = kChainDdsHops * one_hop_us * 1e-3;
      const double ratio = e2e.median / hops_ms, ratio_cached = cached.median / hops_ms;
      std::cout << "  samples " << e2e.n << ", lost " << r.lost << "; chain / (" << kChainDdsHops
                << " x ddsperf one hop " << fmt(one_hop_us, 1) << " us): " << fmt(ratio, 0) << " (cached plan "
                << fmt(ratio_cached, 0) << "; goal <= 1.5)\n";
      std::cout.flush();
      jrows.push_back({{"name", row.name},
                       {"periods_s", {{"situational_awareness", row.sa_period},
                                      {"obstacle_manager", row.om_period},
                                      {"opp_check", row.opp_check},
                                      {"guidance_control", 1.0 / row.gc_rate}}},
                       {"starts", starts},
                       {"samples", e2e.n},
                       {"lost", r.lost},
                       {"hop_ms", hops},
                       {"end_to_end_ms", to_json(e2e)},
                       {"planning_ms", to_json(plan)},
                       {"end_to_end_cached_plan_ms", to_json(cached)},
                       {"timers_mean_wait_ms", timers_ms},
                       {"ratio_vs_ddsperf_hops", std::isfinite(ratio) ? json(ratio) : json(nullptr)},
                       {"ratio_cached_plan_vs_ddsperf_hops", std::isfinite(ratio_cached) ? json(ratio_cached) : json(nullptr)}});
      if (e2e.n == 0 || r.lost > static_cast<int>(e2e.n)) ok = false;  // more lost than measured: broken
    }
    out["rows"] = jrows;

    if (copy_reps > 0 && !g_stop) {
      const CopyResult c = copy_cost(domain, points, copy_reps, self, logs);
      std::cout << "\ncopy of a " << c.points << "-point FixedObstacles (" << fmt(c.mbytes, 1) << " MB of points), median of "
                << copy_reps << " [ms]:\n"
                << "  to the C type (to_c)   " << fmt(c.to_c.median, 3) << "  (p99 " << fmt(c.to_c.p99, 3) << ")\n"
                << "  from the C type        " << fmt(c.from_c.median, 3) << "  (p99 " << fmt(c.from_c.p99, 3) << ")\n"
                << "  write (to_c + dds_write) " << fmt(c.write.median, 3) << "  (p99 " << fmt(c.write.p99, 3) << ")\n"
                << "  write -> take in another process (loopback, reliable) " << fmt(c.write_take.median, 3) << "  (p99 "
                << fmt(c.write_take.p99, 3) << ")\n";
      out["copy"] = {{"points", c.points},       {"mbytes", c.mbytes},          {"reps", copy_reps},
                     {"to_c_ms", to_json(c.to_c)}, {"from_c_ms", to_json(c.from_c)}, {"write_ms", to_json(c.write)},
                     {"write_to_take_ms", to_json(c.write_take)}};
    }
    if (g_stop) {
      std::cerr << "interrupted\n";
      return 130;
    }
    std::cout << "\n" << out.dump() << std::endl;
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "mpgc_bench_chain: " << e.what() << "\n";
    return 1;
  }
}
