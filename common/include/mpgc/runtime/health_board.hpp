// One view of the system's health: which component is up, starting, degraded, stale or down,
// from the ComponentHealth samples on `health` and what the caller knows about the processes.
// No DDS, no clock, no threads: the caller passes every time (any monotonic clock in ns, the same
// for every call) and feeds the samples it took. Used by mpgc_launch and the scenario runner.
//
//   mpgc::rt::HealthBoard board;                       // HealthBoardParams: period, stale periods
//   board.expect("opp", now_ns);                       // a component that should be there
//   board.sample(health_msg, now_ns);                  // every msg::ComponentHealth taken
//   board.process_gone("opp", "killed by signal 9, restarting 1/10", now_ns);   // optional
//   board.process_started("opp", now_ns);              // optional: forgets the old incarnation
//   for (const auto& v : board.changes(now_ns)) ...    // what changed since the last call
//   std::cout << board.line(now_ns);   // "opp down (killed by signal 9, restarting 1/10); 4 up"
//   std::cout << board.table(now_ns);  // one line per component
//
// Status, first rule that holds:
//   down      the caller said the process is gone, or the component's last word was STOPPING,
//             or it never published and the caller knows nothing of its process after `stale` s;
//   stale     no sample for stale_periods x health_period (a hung process, a cut network, or a
//             running process that never published);
//   starting  it said STARTING, or its process runs and nothing was heard yet (within `stale`);
//   degraded  it said DEGRADED or ERROR ("error: " prefixed to the detail);
//   up        it said OK.
// A component never expected but heard on the bus (another host's) is shown too; its process is
// unknown to the caller.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace mpgc::rt {

// What a component reports: the values and order of msg::HealthState (idl/core.idl).
enum class Reported { kStarting, kOk, kDegraded, kError, kStopping };

enum class Status { kUp, kStarting, kDegraded, kStale, kDown };
const char* to_string(Status s);  // "up", "starting", "degraded", "stale", "down"

struct HealthBoardParams {
  double health_period = 1.0;  // [s] the components' health.period (samples are periodic)
  int stale_periods = 3;       // [-] no sample for this many periods: stale
  void validate() const;       // throws std::invalid_argument
};

struct ComponentView {
  std::string name;
  Status status = Status::kDown;
  std::string detail;         // why, for every status but up ("" when up)
  double last_heard = -1.0;   // [s] since its last sample; < 0 when never heard
  bool expected = false;      // declared by expect() (else only heard on the bus)
};

class HealthBoard {
 public:
  explicit HealthBoard(HealthBoardParams p = {});

  // A component that should be there, from `now_ns` on. `publishes_health` = false for processes
  // that are not mpgc components (gpsd): their status is their process's (up while it runs).
  void expect(const std::string& name, int64_t now_ns, bool publishes_health = true);

  // A health sample that arrived at `arrival_ns`. Any component name is accepted.
  void sample(const std::string& name, Reported state, const std::string& detail, int64_t arrival_ns);
  // The same from a msg::ComponentHealth (or anything with .component, .state, .detail).
  template <class HealthMsg>
  void sample(const HealthMsg& h, int64_t arrival_ns) {
    sample(h.component, static_cast<Reported>(static_cast<int>(h.state)), h.detail, arrival_ns);
  }

  // What the caller knows of the process (mpgc_launch started it): optional. process_started
  // forgets the samples of the previous incarnation; process_gone makes it down with `detail`.
  void process_started(const std::string& name, int64_t now_ns);
  void process_gone(const std::string& name, const std::string& detail, int64_t now_ns);

  // Every component, expected ones first in the order of expect(), then the others by name.
  std::vector<ComponentView> view(int64_t now_ns) const;
  // The components whose status (or, not up, whose detail) changed since the previous call; the
  // first call returns every component.
  std::vector<ComponentView> changes(int64_t now_ns);
  // One line: the components not up as "name status (detail)" joined by "; ", then "N up";
  // "all N up" when nothing is wrong, "no components" when there are none.
  std::string line(int64_t now_ns) const;
  // One line per component: name, status, seconds since its last sample, detail.
  std::string table(int64_t now_ns) const;

 private:
  enum class Process { kUnknown, kRunning, kGone };
  struct Entry {
    bool expected = false;
    bool publishes_health = true;
    int order = 0;
    int64_t since_ns = 0;  // expected, or process (re)started, at
    Process process = Process::kUnknown;
    std::string gone_detail;
    std::optional<int64_t> heard_ns;
    Reported state = Reported::kStarting;
    std::string detail;
  };
  ComponentView judge(const std::string& name, const Entry& e, int64_t now_ns) const;
  Entry& entry(const std::string& name, int64_t now_ns);

  HealthBoardParams p_;
  std::map<std::string, Entry> entries_;
  std::map<std::string, std::pair<Status, std::string>> last_reported_;
  int next_order_ = 0;
};

}  // namespace mpgc::rt
