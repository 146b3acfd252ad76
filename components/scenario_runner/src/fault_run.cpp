#include "mpgc/scenario_runner/fault_run.hpp"

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mpgc::scenario_runner {

FaultRun::FaultRun(std::vector<Fault> faults, FaultEffects fx)
    : faults_(std::move(faults)), fx_(std::move(fx)), signal_wall_(faults_.size(), kNaN) {
  for (const auto& f : faults_) {
    FaultRecord r;
    r.what = f.describe();
    r.t_planned = f.at_s;
    r.needs_recovery = f.kind == Fault::Kind::kKill || f.kind == Fault::Kind::kStop;
    if (r.needs_recovery) r.component = f.component;
    records_.push_back(r);
  }
}

void FaultRun::resume(Stopped& k, double t, double wall) {
  fx_.signal(k.pid, SIGCONT);
  k.continued = true;
  signal_wall_[k.fault] = wall;
  records_[k.fault].t_end = t;
  fx_.say("fault: " + faults_[k.fault].component + " continued (SIGCONT)");
}

void FaultRun::at_sim(double t, double wall) {
  for (auto& k : stopped_)
    if (!k.continued && !k.wall && t >= k.until_sim) resume(k, t, wall);
  for (; next_ < faults_.size() && t >= faults_[next_].at_s; ++next_) {
    const Fault& f = faults_[next_];
    FaultRecord& r = records_[next_];
    if (f.kind == Fault::Kind::kKill || f.kind == Fault::Kind::kStop) {
      const int pid = fx_.pid_of(f.component);
      if (pid <= 0) {
        fx_.say("fault: " + f.describe() + " not possible: " + f.component + " is not running");
        continue;  // never happened: the record says so (t stays NaN)
      }
      fx_.signal(pid, f.kind == Fault::Kind::kKill ? SIGKILL : SIGSTOP);
      signal_wall_[next_] = wall;
      if (f.kind == Fault::Kind::kKill) fx_.killed(f.component);
      // The simulator's clock stops with it: its stop lasts in wall time.
      if (f.kind == Fault::Kind::kStop)
        stopped_.push_back({pid, next_, t + f.duration_s, wall + f.duration_s, f.component == "ship_simulator"});
    } else {
      fx_.command(f);
      r.t_end = t + f.duration_s;
    }
    r.t = t;
    fx_.say("fault: " + f.describe());
  }
}

bool FaultRun::at_wall(double wall, double t) {
  bool ended = false;
  for (auto& k : stopped_)
    if (!k.continued && k.wall && wall >= k.until_wall) resume(k, t, wall), ended = true;
  return ended;
}

void FaultRun::on_health(const std::string& component, bool restarted, double t, double wall) {
  for (std::size_t i = 0; i < records_.size(); ++i) {
    FaultRecord& f = records_[i];
    if (f.component != component || !std::isfinite(f.t) || std::isfinite(f.t_recovered)) continue;
    const bool continued = std::any_of(stopped_.begin(), stopped_.end(),
                                       [&](const Stopped& x) { return x.continued && x.fault == i; });
    if (restarted || continued) {
      f.t_recovered = t;
      f.wall_recovery = wall - signal_wall_[i];
    }
  }
}

void FaultRun::release() {
  for (auto& k : stopped_)
    if (!k.continued) fx_.signal(k.pid, SIGCONT), k.continued = true;
}

}  // namespace mpgc::scenario_runner
