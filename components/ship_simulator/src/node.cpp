#include "mpgc/ship_simulator/node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "mpgc/runtime/params.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"

namespace mpgc::ship_simulator {

namespace {
int64_t to_ns(double s) { return static_cast<int64_t>(std::llround(s * 1e9)); }
}  // namespace

int64_t NodeParams::step_ns() const { return to_ns(step); }

bool NodeParams::finished(int64_t t_ns) const { return duration > 0.0 && t_ns >= to_ns(duration); }

void declare(rt::ParamSet& ps, NodeParams& p) {
  ps.add("world.file", &p.world_file, "", "world YAML file (own ship, targets, sensors; README.md)");
  ps.add("time.mode", &p.mode, "realtime", "realtime | factor | lockstep", {"realtime", "factor", "lockstep"});
  ps.add("time.factor", &p.factor, 1.0, "-", 0.01, 1000.0, "real-time factor in factor mode");
  ps.add("time.step", &p.step, 0.1, "s", 0.001, 1.0, "simulation step (RK4 step of the ship model)");
  ps.add("time.duration", &p.duration, 0.0, "s", 0.0, 1e7, "simulated time after which to exit (0 = run forever)");
  ps.add("lockstep.participants", &p.participants, "", "comma-separated components that must ack every step");
  ps.add("lockstep.start_settle", &p.start_settle, 0.5, "s", 0.0, 60.0,
         "wall time to let discovery settle after every participant is alive, before step 0");
  ps.add("lockstep.ack_timeout", &p.ack_timeout, 1.0, "s", 0.01, 60.0, "resend the Clock after this wall time without progress");
  ps.add("lockstep.absent_after", &p.absent_after, 0.5, "s", 0.0, 600.0,
         "a step this long without all acks while a participant's liveliness is lost goes on without the "
         "missing ones (a dead component must not stop the ship); its next ack re-admits it");
  ps.add("lockstep.hang_timeout", &p.hang_timeout, 0.0, "s", 0.0, 3600.0,
         "drop a participant that is alive but has not acked for this long (0 = wait for ever; set it above "
         "the planner's time budget)");
  ps.add("truth.period", &p.truth_period, 0.1, "s", 0.001, 60.0, "sim/truth publication period (simulated time)");
  ps.add("hil.enabled", &p.hil, false, "be the ship's devices: NMEA/AIS on UDP instead of nav/own_state, sensors/*; "
         "orders from the actuator wire instead of control/actuators");
  ps.add("hil.host", &p.hil_host, "127.0.0.1", "IPv4 address of gpsd and the bridge (the devices' wires)");
  ps.add("hil.gnss_port", &p.gnss_port, 10110, "-", 1, 65535, "UDP port (gpsd) for the GNSS receiver's RMC/GGA/VTG");
  ps.add("hil.ais_port", &p.ais_port, 10111, "-", 1, 65535, "UDP port (gpsd) for the AIS transponder's !AIVDM/!AIVDO");
  ps.add("hil.gyro_port", &p.gyro_port, 10112, "-", 1, 65535, "UDP port (bridge) for the gyro compass's $HEHDT/$HEROT");
  ps.add("hil.feedback_port", &p.feedback_port, 10113, "-", 1, 65535, "UDP port (bridge) for RSA/RPM feedback");
  ps.add("hil.orders_port", &p.orders_port, 10114, "-", 1, 65535, "UDP port this simulator takes ROR/PRC orders on");
  ps.add("hil.radar", &p.hil_radar, false, "in HIL, still publish sensors/radar (a radar with its own DDS link)");
  ps.add("resume.journal", &p.journal, "",
         "step journal file: every step's command is appended, and a restarted simulator replays it to resume "
         "the world where it was, bit for bit (a simulator killed mid-run; \"\" = start afresh)");
  ps.add("hil.gnss_period", &p.gnss_period, 0.2, "s", 0.05, 10.0, "GNSS output interval (simulated time)");
  ps.add("hil.order_timeout", &p.order_timeout, 2.0, "s", 0.1, 60.0,
         "actuator watchdog in HIL: no rudder order this long puts the rudder amidships, the engine to watchdog.engine");
  ps.add("watchdog.timeout", &p.watchdog_timeout, 2.0, "s", 0.1, 60.0,
         "actuator watchdog: no valid control/actuators sample for this long (simulated) puts the rudder "
         "amidships and the engine to watchdog.engine; the next order ends it (4 control periods at 2 Hz)");
  ps.add("watchdog.engine", &p.watchdog_engine, "reduce",
         "engine order while the watchdog has tripped: reduce (to the rpm of watchdog.steerage_speed, never "
         "above the last order) | hold (the last order, as class rules want for a manned ship)", {"reduce", "hold"});
  ps.add("watchdog.steerage_speed", &p.steerage_speed, 3.0, "m/s", 0.0, 30.0,
         "watchdog.engine=reduce: straight speed whose rpm the engine is reduced to (KVLCC2: steerage at ~6 kn)");
}

void validate(const NodeParams& p) {
  if (p.world_file.empty()) throw std::invalid_argument("world.file is required");
}

WatchdogParams watchdog_params(const NodeParams& p, const ShipModel& own) {
  WatchdogParams wd;
  wd.timeout_s = p.hil ? p.order_timeout : p.watchdog_timeout;
  if (p.watchdog_engine == "reduce")
    wd.safe_rpm = p.steerage_speed > 0.0 ? std::clamp(straight_rpm(own, p.steerage_speed), 0.0, own.max_rpm()) : 0.0;
  wd.validate();
  return wd;
}

ActuatorWatchdog::ActuatorWatchdog(const WatchdogParams& wd) : wd_(wd) {
  wd_.validate();
  char b[96];
  std::snprintf(b, sizeof b, "engine to at most %.1f rpm", wd_.safe_rpm);
  engine_safe_ = std::isnan(wd_.safe_rpm) ? "engine order held" : b;
}

std::optional<ActuatorWatchdog::News> ActuatorWatchdog::update(const DeviceOrders& o, int64_t t_ns, ShipCommand* cmd) {
  const bool tripped = follow_orders(o, t_ns, wd_, cmd);
  if (tripped == tripped_) return std::nullopt;
  tripped_ = tripped;
  if (!tripped) return News{false, "actuator watchdog: orders again, the actuators follow them"};
  char b[128];
  std::snprintf(b, sizeof b, "actuator watchdog: no order for %.1f s, rudder amidships, ",
                static_cast<double>(t_ns - o.rudder_ns) * 1e-9);
  return News{true, b + engine_safe_};
}

OutputSchedule::OutputSchedule(const NodeParams& p) : truth_period_(to_ns(p.truth_period)), gnss_period_(to_ns(p.gnss_period)) {}

void OutputSchedule::resume(int64_t t_ns) { next_truth_ = (t_ns + truth_period_ - 1) / truth_period_ * truth_period_; }

bool OutputSchedule::truth_due(int64_t t_ns) {
  if (t_ns < next_truth_) return false;
  next_truth_ += truth_period_;
  return true;
}

bool OutputSchedule::gnss_due(int64_t t_ns) {
  if (t_ns < next_gnss_) return false;
  next_gnss_ = t_ns + gnss_period_;
  return true;
}

bool OutputSchedule::own_ais_due(int64_t t_ns) {
  if (t_ns < next_own_ais_) return false;
  next_own_ais_ = t_ns + 10'000'000'000;
  return true;
}

LockstepPacer::LockstepPacer(const NodeParams& p)
    : settle_ns_(static_cast<int64_t>(p.start_settle * 1e9)),
      absent_ns_(static_cast<int64_t>(p.absent_after * 1e9)),
      hang_ns_(p.hang_timeout > 0 ? static_cast<int64_t>(p.hang_timeout * 1e9) : 0),
      ack_ns_(static_cast<int64_t>(p.ack_timeout * 1e9)),
      ack_timeout_(p.ack_timeout) {}

double LockstepPacer::timer_period() const { return std::min(0.05, ack_timeout_ / 2); }

LockstepPacer::Action LockstepPacer::tick(int64_t wall_ns, bool started, uint32_t alive, const LockstepBarrier& b,
                                          std::string* why) {
  if (!started) {
    if (alive < static_cast<uint32_t>(b.size())) return Action::kWait;
    if (ready_wall_ == 0) ready_wall_ = wall_ns;
    return wall_ns - ready_wall_ < settle_ns_ ? Action::kWait : Action::kStart;
  }
  const int64_t waited = wall_ns - step_wall_;
  if (waited > absent_ns_ && alive < static_cast<uint32_t>(b.present())) {
    if (why) *why = "liveliness lost";
    return Action::kDrop;
  }
  if (hang_ns_ > 0 && waited > hang_ns_) {
    if (why) *why = "no ack within lockstep.hang_timeout";
    return Action::kDrop;
  }
  return wall_ns - last_progress_wall_ < ack_ns_ ? Action::kWait : Action::kResend;
}

void LockstepPacer::stepped(int64_t wall_ns) { step_wall_ = last_progress_wall_ = wall_ns; }

void LockstepPacer::resent(int64_t wall_ns) { last_progress_wall_ = wall_ns; }

std::string lockstep_problem(const LockstepBarrier& b, const std::string& why) {
  return "lockstep without [" + join_names(b.absent()) + "] (" + why + ")";
}

}  // namespace mpgc::ship_simulator
