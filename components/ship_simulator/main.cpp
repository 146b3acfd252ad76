// mpgc_ship_simulator: the world as the autonomy sees it. Integrates the own ship from
// control/actuators, moves the targets, publishes sensors, ground truth and the clock.
// Time modes (README.md): realtime, factor (fixed real-time factor), lockstep (barrier on
// clock/ack, as fast as the slowest participant). The simulator runs on the wall clock.
#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <memory>

#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/net/udp.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/ship_simulator/lockstep.hpp"
#include "mpgc/ship_simulator/sensor_faults.hpp"
#include "mpgc/ship_simulator/step_log.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/ship/check_command.hpp"
#include "mpgc/topics.hpp"

namespace sim = mpgc::ship_simulator;
namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;

namespace {

using mpgc::ship::check_command;

struct Params {
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

  void declare(rt::ParamSet& ps) {
    ps.add("world.file", &world_file, "", "world YAML file (own ship, targets, sensors; README.md)");
    ps.add("time.mode", &mode, "realtime", "realtime | factor | lockstep", {"realtime", "factor", "lockstep"});
    ps.add("time.factor", &factor, 1.0, "-", 0.01, 1000.0, "real-time factor in factor mode");
    ps.add("time.step", &step, 0.1, "s", 0.001, 1.0, "simulation step (RK4 step of the ship model)");
    ps.add("time.duration", &duration, 0.0, "s", 0.0, 1e7, "simulated time after which to exit (0 = run forever)");
    ps.add("lockstep.participants", &participants, "", "comma-separated components that must ack every step");
    ps.add("lockstep.start_settle", &start_settle, 0.5, "s", 0.0, 60.0,
           "wall time to let discovery settle after every participant is alive, before step 0");
    ps.add("lockstep.ack_timeout", &ack_timeout, 1.0, "s", 0.01, 60.0, "resend the Clock after this wall time without progress");
    ps.add("lockstep.absent_after", &absent_after, 0.5, "s", 0.0, 600.0,
           "a step this long without all acks while a participant's liveliness is lost goes on without the "
           "missing ones (a dead component must not stop the ship); its next ack re-admits it");
    ps.add("lockstep.hang_timeout", &hang_timeout, 0.0, "s", 0.0, 3600.0,
           "drop a participant that is alive but has not acked for this long (0 = wait for ever; set it above "
           "the planner's time budget)");
    ps.add("truth.period", &truth_period, 0.1, "s", 0.001, 60.0, "sim/truth publication period (simulated time)");
    ps.add("hil.enabled", &hil, false, "be the ship's devices: NMEA/AIS on UDP instead of nav/own_state, sensors/*; "
           "orders from the actuator wire instead of control/actuators");
    ps.add("hil.host", &hil_host, "127.0.0.1", "IPv4 address of gpsd and the bridge (the devices' wires)");
    ps.add("hil.gnss_port", &gnss_port, 10110, "-", 1, 65535, "UDP port (gpsd) for the GNSS receiver's RMC/GGA/VTG");
    ps.add("hil.ais_port", &ais_port, 10111, "-", 1, 65535, "UDP port (gpsd) for the AIS transponder's !AIVDM/!AIVDO");
    ps.add("hil.gyro_port", &gyro_port, 10112, "-", 1, 65535, "UDP port (bridge) for the gyro compass's $HEHDT/$HEROT");
    ps.add("hil.feedback_port", &feedback_port, 10113, "-", 1, 65535, "UDP port (bridge) for RSA/RPM feedback");
    ps.add("hil.orders_port", &orders_port, 10114, "-", 1, 65535, "UDP port this simulator takes ROR/PRC orders on");
    ps.add("hil.radar", &hil_radar, false, "in HIL, still publish sensors/radar (a radar with its own DDS link)");
    ps.add("resume.journal", &journal, "",
           "step journal file: every step's command is appended, and a restarted simulator replays it to resume "
           "the world where it was, bit for bit (a simulator killed mid-run; \"\" = start afresh)");
    ps.add("hil.gnss_period", &gnss_period, 0.2, "s", 0.05, 10.0, "GNSS output interval (simulated time)");
    ps.add("hil.order_timeout", &order_timeout, 2.0, "s", 0.1, 60.0,
           "actuator watchdog in HIL: no rudder order this long puts the rudder amidships, the engine to watchdog.engine");
    ps.add("watchdog.timeout", &watchdog_timeout, 2.0, "s", 0.1, 60.0,
           "actuator watchdog: no valid control/actuators sample for this long (simulated) puts the rudder "
           "amidships and the engine to watchdog.engine; the next order ends it (4 control periods at 2 Hz)");
    ps.add("watchdog.engine", &watchdog_engine, "reduce",
           "engine order while the watchdog has tripped: reduce (to the rpm of watchdog.steerage_speed, never "
           "above the last order) | hold (the last order, as class rules want for a manned ship)", {"reduce", "hold"});
    ps.add("watchdog.steerage_speed", &steerage_speed, 3.0, "m/s", 0.0, 30.0,
           "watchdog.engine=reduce: straight speed whose rpm the engine is reduced to (KVLCC2: steerage at ~6 kn)");
  }
};

msg::ShipTruth to_msg(const sim::TruthShip& t) {
  return {t.id, t.mmsi, t.x, t.y, t.heading, t.cog, t.sog, t.u, t.v, t.r, t.length, t.beam};
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  rt::ParamSet ps;
  p.declare(ps);
  return rt::run_component("ship_simulator", argc, argv, ps, [&](rt::Component& c) {
    if (p.world_file.empty()) throw std::invalid_argument("world.file is required");
    const auto step_ns = static_cast<int64_t>(std::llround(p.step * 1e9));
    auto world = std::make_shared<sim::World>(sim::WorldConfig::from_file(p.world_file), step_ns);
    const auto& cfg = world->config();
    const bool lockstep = p.mode == "lockstep";
    const double wall_per_sim = p.mode == "factor" ? 1.0 / p.factor : 1.0;
    auto barrier = std::make_shared<sim::LockstepBarrier>(sim::split_names(p.participants));
    c.log().info("world {}: model {}, {} targets, mode {}, step {} s, participants [{}]", p.world_file,
                 world->own().name(), cfg.targets.size(), p.mode, p.step, p.participants);

    auto& clock_w = c.publisher<msg::Clock>(topics::kClock, dds::QosProfile::command(16));
    // Reliable state writers (deterministic()): the components on simulated time read them reliably.
    const auto state = [](double deadline_s) { return dds::QosProfile::state(deadline_s).deterministic(); };
    // In HIL mode the autonomy's inputs come from the devices' wires: no writers for them at all.
    auto* nav_w = p.hil ? nullptr : &c.publisher<msg::NavState>(topics::kOwnState, state(3 * cfg.nav.period * wall_per_sim));
    auto* ais_w = p.hil ? nullptr : &c.publisher<msg::AisReport>(topics::kAis, dds::QosProfile::command(64));
    auto* radar_w = p.hil && !p.hil_radar ? nullptr : &c.publisher<msg::RadarScan>(topics::kRadar, state(3 * cfg.radar.period * wall_per_sim));
    auto& truth_w = c.publisher<msg::GroundTruth>(topics::kTruth, state(3 * p.truth_period * wall_per_sim));

    struct State {
      sim::ShipCommand cmd;
      uint32_t seq = 0;
      bool started = false;
      bool stopped = false;
      int64_t last_progress_wall = 0;
      int64_t step_wall = 0;   // [ns] wall time the current step's Clock was first written
      int64_t ready_wall = 0;  // [ns] wall time all participants were first seen alive
      int64_t start_wall = 0;
      int64_t next_truth_ns = 0;
      msg::Clock last_clock{};
    };
    auto st = std::make_shared<State>();
    st->cmd = world->initial_command();
    std::shared_ptr<sim::StepLog> journal;
    if (!p.journal.empty()) {
      journal = std::make_shared<sim::StepLog>(p.journal);
      if (journal->steps() > 0) {
        st->cmd = sim::replay(*world, journal->take_commands(), st->cmd);
        const auto period = static_cast<int64_t>(std::llround(p.truth_period * 1e9));
        st->next_truth_ns = (world->time_ns() + period - 1) / period * period;  // the same schedule
        c.log().warn("resumed from {}: {} steps replayed, simulated time {:.1f} s", p.journal, journal->steps(),
                     world->time_ns() * 1e-9);
        c.count("resumed");
      }
    }
    auto header = [st, world] { return msg::Header{world->time_ns(), "ship_simulator", st->seq++}; };

    // Sensor samples of the current step, then its Clock (a participant's tick sees its data).
    // Hardware in the loop: the devices' wires instead of the sensor topics.
    struct Hil {
      std::unique_ptr<sim::Devices> dev;
      std::unique_ptr<mpgc::net::UdpSender> gnss, ais, gyro, feedback;
      std::unique_ptr<mpgc::net::UdpReceiver> orders;
      sim::DeviceOrders last;  // the latest orders, from the wire (HIL) or control/actuators
      int64_t next_gnss_ns = 0, next_own_ais_ns = 0;
      bool watchdog = false;   // the actuator watchdog has tripped
      std::map<std::string, uint64_t> seen;
    };
    auto hil = std::make_shared<Hil>();
    if (p.hil) {
      const auto utc0 = std::chrono::duration_cast<std::chrono::seconds>(std::chrono::system_clock::now().time_since_epoch());
      hil->dev = std::make_unique<sim::Devices>(world->frame(), static_cast<int64_t>(utc0.count()) * 1'000'000'000);
      hil->gnss = std::make_unique<mpgc::net::UdpSender>(p.hil_host, p.gnss_port);
      hil->ais = std::make_unique<mpgc::net::UdpSender>(p.hil_host, p.ais_port);
      hil->gyro = std::make_unique<mpgc::net::UdpSender>(p.hil_host, p.gyro_port);
      hil->feedback = std::make_unique<mpgc::net::UdpSender>(p.hil_host, p.feedback_port);
      hil->orders = std::make_unique<mpgc::net::UdpReceiver>(p.hil_host, p.orders_port);
      c.log().info("hardware in the loop: GNSS -> {}:{}, AIS -> :{}, gyro -> :{}, feedback -> :{}, orders <- :{}",
                   p.hil_host, p.gnss_port, p.ais_port, p.gyro_port, p.feedback_port, p.orders_port);
    }
    // The actuator watchdog of the steering gear and engine control (README "Actuator watchdog"):
    // without orders the rudder goes amidships and the engine to the safe order; the next order
    // ends it. Orders come from the wire (HIL) or control/actuators (the subscription below).
    sim::WatchdogParams wd;
    wd.timeout_s = p.hil ? p.order_timeout : p.watchdog_timeout;
    if (p.watchdog_engine == "reduce")
      wd.safe_rpm = p.steerage_speed > 0.0
                        ? std::clamp(sim::straight_rpm(world->own(), p.steerage_speed), 0.0, world->own().max_rpm())
                        : 0.0;
    wd.validate();
    const std::string engine_safe = std::isnan(wd.safe_rpm) ? std::string("engine order held")
                                                            : fmt::format("engine to at most {:.1f} rpm", wd.safe_rpm);
    c.log().info("actuator watchdog: after {} s without an order, rudder amidships, {}", wd.timeout_s, engine_safe);
    // Health is the sum of what is wrong: the watchdog and the lockstep barrier each report theirs.
    auto report = [&c](const std::string& source, const std::string& detail) { c.set_problem(source, detail); };
    auto take_orders = [&, st, world, hil, wd, engine_safe, report] {
      const int64_t t = world->time_ns();
      if (p.hil) {
        hil->dev->on_order_lines(hil->orders->receive_lines(), t, world->own().max_rudder(), world->own().max_rpm(), &hil->last);
        for (const auto& [k, v] : hil->dev->counters())
          if (v > hil->seen[k]) c.count("hil." + k, v - hil->seen[k]), hil->seen[k] = v;
      }
      const bool tripped = sim::follow_orders(hil->last, t, wd, &st->cmd);
      if (tripped == hil->watchdog) return;
      hil->watchdog = tripped;
      const double silent = static_cast<double>(t - hil->last.rudder_ns) * 1e-9;
      if (tripped) {
        const std::string what = fmt::format("actuator watchdog: no order for {:.1f} s, rudder amidships, {}", silent, engine_safe);
        c.log().warn("{}", what);
        c.count("watchdog_trips");
        report("watchdog", what);
      } else {
        c.log().info("actuator watchdog: orders again, the actuators follow them");
        report("watchdog", "");
      }
    };
    auto hil_outputs = [&, world, hil](const sim::SensorOutputs& out) {
      const int64_t t = world->time_ns();
      const sim::ShipState& s = world->own().state();
      if (out.nav) {
        hil->gyro->send(hil->dev->gyro(*out.nav));
        hil->feedback->send(hil->dev->feedback(s.rudder, s.rpm));
        if (t >= hil->next_gnss_ns) {
          hil->gnss->send(hil->dev->gnss(*out.nav, t));
          hil->next_gnss_ns = t + static_cast<int64_t>(std::llround(p.gnss_period * 1e9));
        }
        if (t >= hil->next_own_ais_ns) {  // the own ship's transponder: class A underway, 10 s
          for (const auto& l : hil->dev->ais_own(cfg.own_mmsi, *out.nav, t)) hil->ais->send(l);
          hil->next_own_ais_ns = t + 10'000'000'000;
        }
      }
      for (const auto& a : out.ais) {
        const auto& tc = *std::find_if(cfg.targets.begin(), cfg.targets.end(), [&](const auto& x) { return x.mmsi == a.mmsi; });
        for (const auto& l : hil->dev->ais_target(a, tc, t)) hil->ais->send(l);
      }
    };

    // Sensor faults of a scenario (faults.accept): applied to what the sensors produced.
    auto faults = std::make_shared<sim::SensorFaults>();
    if (c.accepts_faults())
      c.subscribe<msg::FaultCommand>(topics::kFaults, dds::QosProfile::command(16), [&, faults](const msg::FaultCommand& f) {
        using K = sim::SensorFaults::Kind;
        if (f.kind == msg::FaultKind::FAULT_SILENCE_TOPIC) return;  // the runtime's
        const K kind = f.kind == msg::FaultKind::FAULT_AIS_OUTAGE     ? K::kAisOutage
                       : f.kind == msg::FaultKind::FAULT_GNSS_DROPOUT ? K::kGnssDropout
                                                                      : K::kPositionJump;
        try {
          faults->add({kind, f.header.stamp_ns, f.header.stamp_ns + static_cast<int64_t>(std::llround(f.duration * 1e9)),
                       f.mmsi, f.dx, f.dy});
          c.log().warn("fault injected at {:.1f} s: kind {} for {:.1f} s", f.header.stamp_ns * 1e-9, static_cast<int>(f.kind), f.duration);
        } catch (const std::exception& e) {
          c.reject(topics::kFaults, e.what());
        }
      }, rt::check_fault);

    auto publish_step = [&, st, world, barrier, header, lockstep, hil_outputs, nav_w, ais_w, radar_w, faults] {
      sim::SensorOutputs out = world->sense();
      const int64_t t = world->time_ns();
      if (!faults->empty() && faults->apply(t, &out) > 0) c.count("faults.sensor_outputs_changed");
      const sim::ShipState& s = world->own().state();
      if (p.hil) {
        hil_outputs(out);
      } else if (out.nav) {
        const auto& n = *out.nav;
        const auto ll = world->frame().to_latlon({n.x, n.y});
        msg::NavState m{header(), n.x, n.y, ll.lat, ll.lon, n.heading, n.cog, n.sog, s.u, s.v, n.rot, s.rudder, s.rpm,
                        msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID |
                            msg::NAV_RATE_VALID | msg::NAV_ACTUATORS_VALID};
        nav_w->write(m);
      }
      if (!p.hil) for (const auto& a : out.ais) {
        const auto ll = world->frame().to_latlon({a.x, a.y});
        const auto& tc = *std::find_if(cfg.targets.begin(), cfg.targets.end(), [&](const auto& x) { return x.mmsi == a.mmsi; });
        ais_w->write(msg::AisReport{header(), a.mmsi, msg::AisClass::AIS_CLASS_A, ll.lat, ll.lon, a.cog, a.sog, a.heading,
                                   a.rot, a.nav_status, a.report_time_ns, tc.length, tc.beam, tc.name, 70});
      }
      if (out.radar && radar_w != nullptr) {
        msg::RadarScan r{header(), out.radar->antenna_x, out.radar->antenna_y, out.radar->max_range, {}};
        for (const auto& k : out.radar->contacts)
          r.contacts.push_back({k.range, k.bearing, cfg.radar.sigma_range, cfg.radar.sigma_bearing});
        radar_w->write(r);
      }
      if (t >= st->next_truth_ns) {
        msg::GroundTruth g{header(), to_msg(world->own_truth()), {}};
        for (const auto& tt : world->target_truth()) g.targets.push_back(to_msg(tt));
        truth_w.write(g);
        st->next_truth_ns += static_cast<int64_t>(std::llround(p.truth_period * 1e9));
      }
      st->last_clock = msg::Clock{t, world->step_index(), world->step_ns(), lockstep && !barrier->empty()};
      barrier->begin(world->step_index());
      clock_w.write(st->last_clock);
      st->last_progress_wall = st->step_wall = c.now_ns();
    };

    auto finished = [&, world] { return p.duration > 0.0 && world->time_ns() >= static_cast<int64_t>(std::llround(p.duration * 1e9)); };
    auto advance = [&, st, world, publish_step, finished, take_orders, journal] {
      if (!st->started) {
        st->started = true;
        st->start_wall = c.now_ns();
        publish_step();  // step 0: the initial state
        return;
      }
      if (finished()) {
        const double wall = (c.now_ns() - st->start_wall) * 1e-9, simt = world->time_ns() * 1e-9;
        c.log().info("done: {} steps, {:.1f} s simulated in {:.2f} s wall, real-time factor {:.1f}",
                     world->step_index(), simt, wall, wall > 0 ? simt / wall : 0.0);
        st->stopped = true;
        c.stop(0);
        return;
      }
      take_orders();  // the latest orders through the actuator watchdog
      if (journal) journal->append(st->cmd);
      world->step(st->cmd);
      c.count("steps");
      publish_step();
    };

    if (!p.hil) c.subscribe<msg::ActuatorCommand>(
        topics::kActuators, dds::QosProfile::command(16),
        [&c, world, hil](const msg::ActuatorCommand& a) {
          // Beyond a limit: saturated (the gear stops there) and counted, not refused.
          const auto o = mpgc::ship::saturate(world->own().actuator_limits(), a.rudder, a.propeller_rpm);
          if (o.rudder_saturated) c.count("saturated.rudder");
          if (o.rpm_saturated) c.count("saturated.rpm");
          hil->last = {o.rudder, o.rpm, true, true, world->time_ns()};  // applied at the next step
        },
        [](const msg::ActuatorCommand& a) { return check_command(a); });

    if (!lockstep) {
      c.every(p.step * wall_per_sim, advance);
    } else if (barrier->empty()) {
      // No participants: as fast as the model goes, in bursts of 5 ms wall so the executor
      // still serves actuator commands (and a tiny timer period would make its catch-up loop spin).
      c.every(1e-3, [&, st, advance] {
        const int64_t until = c.now_ns() + 5'000'000;
        do advance();
        while (!st->stopped && c.now_ns() < until);
      });
    } else {
      auto& acks = c.subscribe<msg::StepAck>(topics::kStepAck, dds::QosProfile::command(16), [&, st, barrier, advance, report](const msg::StepAck& a) {
        const auto r = barrier->ack(a.component, a.step);
        if (r == sim::LockstepBarrier::Ack::Unknown) c.count("lockstep.unknown_acks");
        if (r == sim::LockstepBarrier::Ack::Readmitted) {
          c.log().warn("lockstep: {} is back (ack of step {}), waiting for it again", a.component, a.step);
          c.count("lockstep.readmitted");
          if (barrier->absent().empty()) report("lockstep", "");
        }
        if ((r != sim::LockstepBarrier::Ack::Counted && r != sim::LockstepBarrier::Ack::Readmitted) || !barrier->complete()) return;
        // The participants wrote their commands before their acks: read them all before stepping.
        c.poll();
        advance();
      });
      // A participant that died (its ack writer's liveliness is lost) or hangs: go on without it,
      // so the ship keeps being simulated and its watchdogs see the silence; it rejoins on restart.
      auto drop_missing = [&, st, barrier, advance, report](const char* why) {
        std::string names;
        for (const auto& m : barrier->missing()) {
          barrier->drop(m);
          names += (names.empty() ? "" : ", ") + m;
          c.count("lockstep.dropped");
        }
        if (names.empty()) return;
        c.log().warn("lockstep: step {} goes on without [{}] ({})", st->last_clock.step, names, why);
        std::string all;
        for (const auto& m : barrier->absent()) all += (all.empty() ? "" : ", ") + m;
        report("lockstep", "lockstep without [" + all + "] (" + why + ")");
        if (barrier->complete()) {
          c.poll();
          advance();
        }
      };
      // Start once every participant is up (its ack writer is alive) and discovery has settled, so
      // all of them receive step 0's data: a run must not depend on who was discovered first.
      // Then resend the current Clock when an ack (or the Clock itself) was lost.
      c.every(std::min(0.05, p.ack_timeout / 2), [&, st, barrier, advance, drop_missing] {
        if (!st->started) {
          if (acks.liveliness().alive_count < static_cast<uint32_t>(barrier->size())) return;
          if (st->ready_wall == 0) st->ready_wall = c.now_ns();
          if (c.now_ns() - st->ready_wall < static_cast<int64_t>(p.start_settle * 1e9)) return;
          return advance();
        }
        const int64_t waited = c.now_ns() - st->step_wall;
        if (waited > static_cast<int64_t>(p.absent_after * 1e9) &&
            acks.liveliness().alive_count < static_cast<uint32_t>(barrier->present()))
          return drop_missing("liveliness lost");
        if (p.hang_timeout > 0 && waited > static_cast<int64_t>(p.hang_timeout * 1e9))
          return drop_missing("no ack within lockstep.hang_timeout");
        if (c.now_ns() - st->last_progress_wall < static_cast<int64_t>(p.ack_timeout * 1e9)) return;
        std::string missing;
        for (const auto& m : barrier->missing()) missing += (missing.empty() ? "" : ", ") + m;
        c.log().debug("step {}: no ack from [{}] within {} s, resending the clock", st->last_clock.step, missing, p.ack_timeout);
        c.count("lockstep.resends");
        clock_w.write(st->last_clock);
        st->last_progress_wall = c.now_ns();
      });
    }
  });
}
