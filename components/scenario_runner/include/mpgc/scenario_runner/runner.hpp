// The closed-loop runner's logic without DDS, processes or a clock (mpgc_run's main.cpp is wiring
// around it): its options, the scenario files of a suite, the world and launch files of a run, the
// recording of a run from what it heard, the health news it prints, the link cuts of a deployment
// run, and the texts it writes (network.json, the progress lines, the summary table).
//
//   RunOptions o;  resolve_options(o, cl);                  // throws std::invalid_argument
//   files = scenario_files(files, suite, scen_dir, data_dir);
//   std::string y = launch_file(s, world_path, o, domain, placement, launch_context);
//   RunRecorder rec(s);  rec.plan(...);  if (rec.fresh(t)) { ... rec.record(t, truth) ... }
//   Metrics m = rec.evaluate(wall_s);
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "deployment.hpp"
#include "mpgc/runtime/health_board.hpp"
#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace mpgc::scenario_runner {

// The simulator and the four autonomy components of a run, in launch order.
inline const std::vector<std::string> kRunComponents = {"ship_simulator", "situational_awareness", "obstacle_manager",
                                                        "opp", "guidance_control"};
inline const std::vector<std::string> kAutonomy = {"situational_awareness", "obstacle_manager", "opp",
                                                   "guidance_control"};

// Hardware in the loop: the default real-time factor (gpsd runs on the wall clock) and an MMSI for
// the own ship's transponder when the scenario gives none.
inline constexpr double kHilFactor = 20.0;
// --view: the recorder's live view (Foxglove WebSocket and web page) on 127.0.0.1 at this port, and
// the real-time factor of a run that gives none (lockstep would be over before the page is open).
inline constexpr int kViewPort = 8765;
inline constexpr double kViewFactor = 10.0;
inline constexpr uint32_t kHilOwnMmsi = 257999990;

// The UDP/TCP ports of one HIL run, distinct per DDS domain so concurrent runs do not meet.
struct HilPorts {
  int gpsd, gnss, ais, gyro, feedback, orders;
  explicit HilPorts(int domain) {
    const int b = 20000 + 10 * domain;
    gpsd = b, gnss = b + 1, ais = b + 2, gyro = b + 3, feedback = b + 4, orders = b + 5;
  }
};

struct RunOptions {
  double realtime_factor = 0.0;  // 0: lockstep as fast as possible
  std::string out = "out";
  double record_period = 1.0;    // [s] simulated
  bool quiet = false;
  bool hil = false;              // hardware in the loop: simulator -> NMEA -> gpsd -> ship_bridge
  // Across a ship's network: the components on the hosts of a deployment, as network namespaces.
  std::optional<deploy::Deployment> hosts;
  std::map<std::string, deploy::LinkSpec> links;  // each host's egress
  uint64_t link_seed = 1;
  std::vector<deploy::LinkCut> cuts;
  bool capture = false;          // tcpdump of every host to <run>/network/<host>.pcap
  std::string secure;            // DDS Security: the folder made by deploy/security/make-pki.sh
  int domain = -1;               // -1: a free one in 201..230
  bool containers = false;       // with hosts: each host a podman container (deploy/container)
  std::string image = "localhost/mpgc:bookworm";
  double plan_latency = 0.0;     // [s] per planner iteration: plans take effect late (opp plan.latency_per_iteration)
  bool record = true;            // mpgc_record writes the bus to <run>/run.mcap
  int view_port = 0;             // the recorder serves the live view on 127.0.0.1:<port>; 0: no live view
  std::string planner;           // opp's plan.planner over the scenario's (--planner); empty: the scenario's or the default
};

// What the command line gives beside RunOptions' own fields.
struct RunCommandLine {
  bool late_plans = false;  // --late-plans: the paper's 0.5 s per 20000 iterations
  std::string hosts_file;   // --hosts
  std::vector<std::string> links;  // --link
  std::vector<std::string> cuts;   // --cut HOST@T+D
  bool view = false;               // --view: the live view on kViewPort
};

// Completes `o` from the command line: HIL's real-time factor, late plans' latency, the deployment
// with its links and cuts. Throws std::invalid_argument naming the option at fault. What needs the
// machine (podman's image, network namespaces, the security folder) the caller checks.
void resolve_options(RunOptions& o, const RunCommandLine& cl);

// The scenario files to run: `files`, then a suite's (scenarios/<suite>/*.yaml; dnv: the 55 DNV
// situations of <data_dir>/encounters/dnv/baseline_situations_generated/*.json; all: paper, chart
// and dnv), each folder sorted; none at all: the paper's s1_colreg. Throws std::invalid_argument
// "no suite folder <dir>" for a missing folder.
std::vector<std::string> scenario_files(std::vector<std::string> files, const std::string& suite,
                                        const std::string& scen_dir, const std::string& data_dir);

// The simulator's world file of a run (the own ship gets an MMSI under HIL when it has none).
std::string world_file(const Scenario& s, bool hil);

// dijkstra-sv plans on turning-circle tables of the own ship (seed 002 §2). When the run's planner
// (--planner, else the scenario's plan.planner) is dijkstra-sv and the scenario names no
// plan.dsv.tables: the command that makes them for the world's own ship at the cruise speed
// (`<bin_dir>/mpgc_trial ... table --out out_csv`, half a second). Empty when none is needed.
std::vector<std::string> turning_tables_command(const Scenario& s, const std::string& planner,
                                                const std::string& bin_dir, const std::string& out_csv);

// Where a component runs when the run is spread over a deployment's hosts.
struct Placement {
  bool on_hosts = false;
  std::map<std::string, std::string> ns;  // host -> its network namespace
  std::string network_dir;                // <run>/network: <host>/cyclonedds.xml
};
// What the launch file takes from the machine.
struct LaunchContext {
  std::string bin_dir;      // mpgc_run's own folder (mpgc_launch and the components)
  std::string source_dir;   // $MPGC_SOURCE_DIR
  std::string shared_dir;   // the shared data folder ("" when there is none)
  std::string cwd;          // relative paths in parameters resolve from here
  bool root = false;        // gpsd is then run as nobody
  std::vector<std::pair<std::string, std::string>> env;  // passed into containers (MPGC_SHARED_DATA, ...)
};
// The launch file for one run: the simulator plus the four autonomy components on simulated time
// (under HIL with gpsd and ship_bridge; with containers one podman container per host, each host's
// own launch file written to <network_dir>/<host>/launch.yaml).
std::string launch_file(const Scenario& s, const std::string& world_path, const RunOptions& o, int domain,
                        const Placement& where, const LaunchContext& ctx);

// Records a run from what the runner hears: ground truth at the record period, plans, guidance and
// every fixed obstacle published (obstacle_manager sends the region around the own ship, so the
// union of all versions, not the last one, is what the ship sailed past).
class RunRecorder {
 public:
  // `obstacles`: the scenario's own (scenario_obstacles), which the run is judged against.
  RunRecorder(const Scenario& s, FixedObstacles obstacles);

  struct Ship {
    uint32_t id = 0;
    double length = 0;  // [m] <= 0: unknown
    ShipState state;
  };
  // A fresh sample at t [s]: later than the last recorded one.
  bool fresh(double t) const { return run_.t.empty() || t > run_.t.back(); }
  // Records the truth at t (the first sample fixes the scene; a sample with another number of
  // targets is dropped: nullopt). Returns the own ship's distance to the goal [m].
  std::optional<double> record(double t, const Ship& own, const std::vector<Ship>& targets);
  // Why the run ends after a recorded sample ("goal reached", "time limit"), "" when it goes on.
  std::string end_reason(double t, double to_goal) const;

  // A plan: NO_PATH when it has fewer than two waypoints; dropped when older than the last.
  void plan(PlanRecord r);
  void guidance(const GuidanceRecord& r);  // dropped unless later than the last

  RunRecord& run() { return run_; }
  const RunRecord& run() const { return run_; }
  // The run is over: its metrics.
  Metrics evaluate(double wall_s);

 private:
  const Scenario& s_;
  RunRecord run_;
  std::size_t targets_ = 0;
};

// The health news of a run (the view is rt::HealthBoard's, on the run's simulated clock in ns): a component's
// change to down, stale, degraded or back; a new incarnation (its health seq starts again) marks
// the recovery of a killed or stopped one. "up" is news only after something else was said.
class HealthNews {
 public:
  HealthNews(const std::vector<std::string>& expected, int64_t now_ns);
  // A health sample; returns the lines to print; `restarted` receives whether it is a new process.
  std::vector<std::string> sample(const std::string& component, uint32_t seq, rt::Reported state,
                                  const std::string& detail, int64_t now_ns, bool* restarted);
  std::vector<std::string> changes(int64_t now_ns);  // stale ones, which no sample announces
  void killed(const std::string& component, int64_t now_ns);

 private:
  rt::HealthBoard board_;
  std::map<std::string, uint32_t> seq_;
  std::map<std::string, rt::Status> said_;
};

// Link cuts: each begins when the simulated clock reaches it and lasts its wall-clock time.
struct CutState {
  deploy::LinkCut cut;
  bool begun = false, ended = false;
  double wall_begin = 0;  // [s] run's wall clock
  double sim_begin = 0, sim_end = 0;
};
class CutSchedule {
 public:
  explicit CutSchedule(const std::vector<deploy::LinkCut>& cuts);
  std::vector<const CutState*> begin(double sim, double wall);  // the cuts that begin now
  std::vector<const CutState*> end(double wall, double sim);    // the cuts whose time is over
  std::vector<const CutState*> end_all(double sim);             // the run is over
  const std::vector<CutState>& cuts() const { return cuts_; }

 private:
  std::vector<CutState> cuts_;
};

// Plans that arrived strictly between t0 and t1 [s].
int plans_between(const RunRecord& run, double t0, double t1);
// printf of v with `f`, "-" when not finite.
std::string num_text(double v, const char* f = "%.0f");

// What the network did, beside metrics.json (network.json): the hosts, the links, every cut and
// netem's counts; and the same as the summary's notes.
std::string network_json(const RunOptions& o, const std::vector<CutState>& cuts, const RunRecord& run,
                         const std::map<std::string, std::string>& netem);
std::vector<std::string> network_notes(const std::vector<CutState>& cuts, const RunRecord& run,
                                       const std::map<std::string, std::string>& netem);

// Progress lines.
std::string say_line(const std::string& scenario, double sim, const std::string& what);
std::string progress_line(const std::string& scenario, double sim, double to_goal, std::size_t plans, double wall);
std::string cut_line(const std::string& scenario, double sim, const deploy::LinkCut& cut);

struct Outcome {
  bool ran = false;
  Metrics metrics;
  std::string error;
  std::vector<std::string> notes;  // what the network did (cuts, netem)
  bool passed() const { return ran && metrics.passed; }
};
// The summary table of a suite, its failures and notes, and the count line.
std::string summary(const std::vector<std::pair<std::string, Outcome>>& results, const std::string& out);

}  // namespace mpgc::scenario_runner
