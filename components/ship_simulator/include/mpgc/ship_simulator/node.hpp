// The simulator component's logic without DDS or a clock (mpgc_ship_simulator's main.cpp is wiring
// around it): its named parameters, the actuator watchdog as the component runs it (what it says
// when it trips and ends), the schedule of ground truth and the HIL devices' outputs, and when the
// lockstep timer starts, drops a missing participant or resends the Clock (wall times in ns come
// from the caller).
//
//   sim::NodeParams p;  sim::declare(ps, p);  ps.validate_and_apply();  sim::validate(p);
//   sim::ActuatorWatchdog wd(sim::watchdog_params(p, world.own()));
//   if (auto news = wd.update(orders, t, &cmd)) log(news->text);
//   sim::LockstepPacer pacer(p);  switch (pacer.tick(wall_ns, started, alive, barrier)) ...
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/ship_simulator/lockstep.hpp"
#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::rt {
class ParamSet;
}

namespace mpgc::ship_simulator {

struct NodeParams {
  std::string world_file;
  std::string mode;          // realtime | factor | lockstep
  double factor = 1.0;       // [-] real-time factor in factor mode
  double step = 0.1;         // [s] simulation step
  double duration = 0.0;     // [s] simulated time after which the simulator exits; 0 = never
  std::string participants;  // comma-separated component names for the lockstep barrier
  double start_settle = 0.5;  // [s] wall time between all participants alive and step 0
  double ack_timeout = 1.0;  // [s] wall time before the current Clock is sent again
  double absent_after = 0.5; // [s] wall: a step this long short of acks, with a participant's
                             //     liveliness lost, goes on without the missing ones
  double hang_timeout = 0.0; // [s] wall: drop a missing participant even while alive (0 = never)
  double truth_period = 0.1; // [s] simulated time between sim/truth samples
  // Hardware in the loop (README "The simulator as hardware"): NMEA/AIS out on UDP, orders in.
  bool hil = false;
  std::string hil_host;
  int gnss_port = 0, ais_port = 0, gyro_port = 0, feedback_port = 0, orders_port = 0;
  double gnss_period = 0.2;     // [s] simulated
  double order_timeout = 2.0;   // [s] simulated: the actuator watchdog in HIL
  // Actuator watchdog on control/actuators (README "Actuator watchdog").
  double watchdog_timeout = 2.0;   // [s] simulated time without an order before it trips
  std::string watchdog_engine;     // reduce | hold
  double steerage_speed = 3.0;     // [m/s] "reduce": engine to the rpm of this straight speed
  bool hil_radar = false;       // keep publishing sensors/radar in HIL (a radar with its own DDS link)
  std::string journal;          // step journal: resume where a killed simulator left off ("" = none)

  bool lockstep() const { return mode == "lockstep"; }
  double wall_per_sim() const { return mode == "factor" ? 1.0 / factor : 1.0; }  // [s/s]
  int64_t step_ns() const;
  // The simulated time time.duration is over (never when it is 0).
  bool finished(int64_t t_ns) const;
};

// Declares every parameter of the component.
void declare(rt::ParamSet& ps, NodeParams& p);
// What the ranges cannot check: throws std::invalid_argument ("world.file is required").
void validate(const NodeParams& p);

// The actuator watchdog of the component: HIL's order timeout or watchdog.timeout; the engine
// reduced to the rpm of watchdog.steerage_speed (clamped to the engine's range) or held.
WatchdogParams watchdog_params(const NodeParams& p, const ShipModel& own);

class ActuatorWatchdog {
 public:
  explicit ActuatorWatchdog(const WatchdogParams& wd);  // validated
  const WatchdogParams& params() const { return wd_; }
  // "engine to at most 12.3 rpm" or "engine order held".
  const std::string& engine_safe() const { return engine_safe_; }
  struct News {
    bool tripped;      // true: it tripped; false: orders again
    std::string text;  // the log line (and, tripped, the health problem)
  };
  // The actuators follow the latest orders at t (follow_orders); news when the watchdog trips or ends.
  std::optional<News> update(const DeviceOrders& o, int64_t t_ns, ShipCommand* cmd);

 private:
  WatchdogParams wd_;
  std::string engine_safe_;
  bool tripped_ = false;
};

// When the periodic outputs are due, on simulated time [ns]: ground truth every truth.period on
// a fixed grid (a resumed simulator keeps the same one); in HIL the GNSS every hil.gnss_period and
// the own ship's AIS (class A underway) every 10 s, after the last sent.
class OutputSchedule {
 public:
  explicit OutputSchedule(const NodeParams& p);
  void resume(int64_t t_ns);  // the first truth at the first grid time at or after t
  bool truth_due(int64_t t_ns);
  bool gnss_due(int64_t t_ns);
  bool own_ais_due(int64_t t_ns);

 private:
  int64_t truth_period_, gnss_period_;
  int64_t next_truth_ = 0, next_gnss_ = 0, next_own_ais_ = 0;
};

// What the lockstep timer does (every timer_period() s of wall time).
class LockstepPacer {
 public:
  explicit LockstepPacer(const NodeParams& p);
  double timer_period() const;  // [s] min(0.05, ack_timeout / 2)
  enum class Action { kWait, kStart, kDrop, kResend };
  // Before step 0 (`started` false): start once `alive` ack writers cover every participant and
  // discovery has settled (lockstep.start_settle). Then drop the missing ones when the step waited
  // past absent_after with fewer alive than present, or past hang_timeout (`why` receives the
  // reason); else resend the Clock after ack_timeout without progress.
  Action tick(int64_t wall_ns, bool started, uint32_t alive, const LockstepBarrier& b, std::string* why);
  void stepped(int64_t wall_ns);  // a step's Clock was written
  void resent(int64_t wall_ns);   // the Clock was written again

 private:
  int64_t settle_ns_, absent_ns_, hang_ns_, ack_ns_;
  double ack_timeout_;
  int64_t ready_wall_ = 0, step_wall_ = 0, last_progress_wall_ = 0;
};

// The health problem of a barrier with absent participants: "lockstep without [a, b] (why)".
std::string lockstep_problem(const LockstepBarrier& b, const std::string& why);

}  // namespace mpgc::ship_simulator
