// The faults of a run as they happen: which is due, what became of each (FaultRecord), and when a
// killed or stopped component counts as back. No processes, no DDS, no clock: the runner's main
// gives the times and carries out the effects (Effects), so the bookkeeping is tested alone.
//
//   FaultRun run(scenario.faults, effects);
//   run.at_sim(t, wall);                     // every record step: SIGCONTs due, faults due
//   run.at_wall(wall, t);                    // the wall-clock watchdog: the simulator's SIGCONT
//   run.on_health(component, restarted, t, wall);   // a health sample: recovery
//   run.release(); run.records();            // the end
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "mpgc/scenario_runner/evaluation.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace mpgc::scenario_runner {

struct FaultEffects {
  std::function<int(const std::string& component)> pid_of;  // its process, <= 0 when not running
  std::function<void(int pid, int signal)> signal;
  std::function<void(const Fault& f)> command;               // silence / sensor faults: on sim/faults
  std::function<void(const std::string& component)> killed;  // a kill was sent (the health view)
  std::function<void(const std::string& what)> say;          // progress lines
};

class FaultRun {
 public:
  FaultRun(std::vector<Fault> faults, FaultEffects fx);  // faults in order of at_s

  // At simulated time t [s] (wall: the run's wall clock [s]): continues the stops whose simulated
  // window ended, then injects every fault whose time has come.
  void at_sim(double t, double wall);
  // The stops of the simulator last in wall time (its clock stops with it); true when one ended.
  bool at_wall(double wall, double t);
  // A health sample of `component` at t (restarted: a new incarnation): a killed component is
  // back with a new process, a stopped one with its first sample after SIGCONT.
  void on_health(const std::string& component, bool restarted, double t, double wall);
  // Continues whatever is still stopped (a stopped process cannot stop).
  void release();

  const std::vector<FaultRecord>& records() const { return records_; }

 private:
  struct Stopped {
    int pid;
    std::size_t fault;
    double until_sim;   // [s] SIGCONT at this simulated time...
    double until_wall;  // [s] ...or this wall time (the simulator)
    bool wall;
    bool continued = false;
  };
  void resume(Stopped& k, double t, double wall);

  std::vector<Fault> faults_;
  FaultEffects fx_;
  std::vector<FaultRecord> records_;
  std::vector<double> signal_wall_;  // [s] wall time of the kill or SIGCONT, per fault
  std::vector<Stopped> stopped_;
  std::size_t next_ = 0;
};

}  // namespace mpgc::scenario_runner
