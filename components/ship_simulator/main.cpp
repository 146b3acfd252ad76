// mpgc_ship_simulator: the world as the autonomy sees it. Integrates the own ship from
// control/actuators, moves the targets, publishes sensors, ground truth and the clock.
// Time modes (README.md): realtime, factor (fixed real-time factor), lockstep (barrier on
// clock/ack, as fast as the slowest participant). The simulator runs on the wall clock.
// Its logic is mpgc/ship_simulator/node.hpp (and the world's library); this is its wiring.
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
#include "mpgc/ship_simulator/node.hpp"
#include "mpgc/ship_simulator/sensor_faults.hpp"
#include "mpgc/ship_simulator/step_log.hpp"
#include "mpgc/ship_simulator/world.hpp"
#include "mpgc/ship/check_command.hpp"
#include "mpgc/text/list.hpp"
#include "mpgc/topics.hpp"

namespace sim = mpgc::ship_simulator;
namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;

namespace {

using mpgc::ship::check_command;

msg::ShipTruth to_msg(const sim::TruthShip& t) {
  return {t.id, t.mmsi, t.x, t.y, t.heading, t.cog, t.sog, t.u, t.v, t.r, t.length, t.beam};
}

}  // namespace

int main(int argc, char** argv) {
  sim::NodeParams p;
  rt::ParamSet ps;
  sim::declare(ps, p);
  return rt::run_component("ship_simulator", argc, argv, ps, [&](rt::Component& c) {
    sim::validate(p);
    auto world = std::make_shared<sim::World>(sim::WorldConfig::from_file(p.world_file), p.step_ns());
    const auto& cfg = world->config();
    const bool lockstep = p.lockstep();
    const double wall_per_sim = p.wall_per_sim();
    auto barrier = std::make_shared<sim::LockstepBarrier>(mpgc::text::split_list(p.participants));
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
      int64_t start_wall = 0;
      sim::OutputSchedule outputs;
      sim::LockstepPacer pacer;
      msg::Clock last_clock{};
      uint64_t steps_without_clock = 0;  // lockstep: steps since the last Clock
      bool clock_out = false;            // the last step's Clock was written
    };
    auto st = std::make_shared<State>(State{{}, 0, false, false, 0, sim::OutputSchedule(p), sim::LockstepPacer(p), {}, 0, false});
    st->cmd = world->initial_command();
    std::shared_ptr<sim::StepLog> journal;
    if (!p.journal.empty()) {
      journal = std::make_shared<sim::StepLog>(p.journal);
      if (journal->steps() > 0) {
        st->cmd = sim::replay(*world, journal->take_commands(), st->cmd);
        st->outputs.resume(world->time_ns());  // the same schedule
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
    auto wd = std::make_shared<sim::ActuatorWatchdog>(sim::watchdog_params(p, world->own()));
    c.log().info("actuator watchdog: after {} s without an order, rudder amidships, {}", wd->params().timeout_s,
                 wd->engine_safe());
    // Health is the sum of what is wrong: the watchdog and the lockstep barrier each set theirs.
    auto take_orders = [&, st, world, hil, wd] {
      const int64_t t = world->time_ns();
      if (p.hil) {
        hil->dev->on_order_lines(hil->orders->receive_lines(), t, world->own().max_rudder(), world->own().max_rpm(), &hil->last);
        for (const auto& [k, v] : hil->dev->counters())
          if (v > hil->seen[k]) c.count("hil." + k, v - hil->seen[k]), hil->seen[k] = v;
      }
      const auto news = wd->update(hil->last, t, &st->cmd);
      if (!news) return;
      if (news->tripped) {
        c.log().warn("{}", news->text);
        c.count("watchdog_trips");
        c.set_problem("watchdog", news->text);
      } else {
        c.log().info("{}", news->text);
        c.set_problem("watchdog", "");
      }
    };
    auto hil_outputs = [&, st, world, hil](const sim::SensorOutputs& out) {
      const int64_t t = world->time_ns();
      const sim::ShipState& s = world->own().state();
      if (out.nav) {
        hil->gyro->send(hil->dev->gyro(*out.nav));
        hil->feedback->send(hil->dev->feedback(s.rudder, s.rpm));
        if (st->outputs.gnss_due(t)) hil->gnss->send(hil->dev->gnss(*out.nav, t));
        if (st->outputs.own_ais_due(t))  // the own ship's transponder
          for (const auto& l : hil->dev->ais_own(cfg.own_mmsi, *out.nav, t)) hil->ais->send(l);
      }
      for (const auto& a : out.ais)
        for (const auto& l : hil->dev->ais_target(a, cfg.target(a.mmsi), t)) hil->ais->send(l);
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
        const auto& tc = cfg.target(a.mmsi);
        ais_w->write(msg::AisReport{header(), a.mmsi, msg::AisClass::AIS_CLASS_A, ll.lat, ll.lon, a.cog, a.sog, a.heading,
                                   a.rot, a.nav_status, a.report_time_ns, tc.length, tc.beam, tc.name, 70});
      }
      if (out.radar && radar_w != nullptr) {
        msg::RadarScan r{header(), out.radar->antenna_x, out.radar->antenna_y, out.radar->max_range, {}};
        for (const auto& k : out.radar->contacts)
          r.contacts.push_back({k.range, k.bearing, cfg.radar.sigma_range, cfg.radar.sigma_bearing});
        radar_w->write(r);
      }
      if (st->outputs.truth_due(t)) {
        msg::GroundTruth g{header(), to_msg(world->own_truth()), {}};
        for (const auto& tt : world->target_truth()) g.targets.push_back(to_msg(tt));
        truth_w.write(g);
      }
      // In lockstep a step at which no participant's timer is due goes without a Clock: the
      // participants deliver its samples at the next one (Component::on_clock). Not in HIL, where
      // the bridge, on this clock but no participant, turns the wires into topics at every step.
      const bool barrier_step = lockstep && !barrier->empty();
      st->clock_out = !barrier_step || p.hil || p.finished(t) ||
                      sim::clock_due(t, world->step_ns(), barrier->due_ns(), st->steps_without_clock);
      if (!st->clock_out) {
        ++st->steps_without_clock;
        return;
      }
      st->steps_without_clock = 0;
      st->last_clock = msg::Clock{t, world->step_index(), world->step_ns(), barrier_step};
      barrier->begin(world->step_index());
      clock_w.write(st->last_clock);
      st->pacer.stepped(c.now_ns());
    };

    auto advance = [&, st, world, publish_step, take_orders, journal] {
      if (!st->started) {
        st->started = true;
        st->start_wall = c.now_ns();
        publish_step();  // step 0: the initial state
        return;
      }
      if (p.finished(world->time_ns())) {
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
    // Lockstep, once the barrier is complete: the participants wrote their commands before their
    // acks, so read them all, then step up to the next step with a Clock.
    auto run_to_clock = [&, st, advance] {
      c.poll();
      do advance();
      while (!st->stopped && !st->clock_out);
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
      auto& acks = c.subscribe<msg::StepAck>(topics::kStepAck, dds::QosProfile::command(16), [&, st, barrier, run_to_clock](const msg::StepAck& a) {
        const auto r = barrier->ack(a.component, a.step, a.next_due_ns);
        if (r == sim::LockstepBarrier::Ack::Unknown) c.count("lockstep.unknown_acks");
        if (r == sim::LockstepBarrier::Ack::Readmitted) {
          c.log().warn("lockstep: {} is back (ack of step {}), waiting for it again", a.component, a.step);
          c.count("lockstep.readmitted");
          if (barrier->absent().empty()) c.set_problem("lockstep", "");
        }
        if ((r != sim::LockstepBarrier::Ack::Counted && r != sim::LockstepBarrier::Ack::Readmitted) || !barrier->complete()) return;
        run_to_clock();
      });
      // A participant that died (its ack writer's liveliness is lost) or hangs: go on without it,
      // so the ship keeps being simulated and its watchdogs see the silence; it rejoins on restart.
      auto drop_missing = [&, st, barrier, run_to_clock](const std::string& why) {
        const auto dropped = barrier->drop_missing();
        for (size_t i = 0; i < dropped.size(); ++i) c.count("lockstep.dropped");
        if (dropped.empty()) return;
        c.log().warn("lockstep: step {} goes on without [{}] ({})", st->last_clock.step, sim::join_names(dropped), why);
        c.set_problem("lockstep", sim::lockstep_problem(*barrier, why));
        if (barrier->complete()) run_to_clock();
      };
      // Start once every participant is up (its ack writer is alive) and discovery has settled, so
      // all of them receive step 0's data: a run must not depend on who was discovered first.
      // Then resend the current Clock when an ack (or the Clock itself) was lost.
      c.every(st->pacer.timer_period(), [&, st, barrier, advance, drop_missing] {
        std::string why;
        switch (st->pacer.tick(c.now_ns(), st->started, acks.liveliness().alive_count, *barrier, &why)) {
          case sim::LockstepPacer::Action::kWait: return;
          case sim::LockstepPacer::Action::kStart: return advance();
          case sim::LockstepPacer::Action::kDrop: return drop_missing(why);
          case sim::LockstepPacer::Action::kResend: break;
        }
        c.log().debug("step {}: no ack from [{}] within {} s, resending the clock", st->last_clock.step,
                      sim::join_names(barrier->missing()), p.ack_timeout);
        c.count("lockstep.resends");
        clock_w.write(st->last_clock);
        st->pacer.resent(c.now_ns());
      });
    }
  });
}
