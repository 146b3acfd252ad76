// mpgc_ship_bridge: stands where ship_simulator stands, on a real vessel. GNSS and AIS from gpsd
// (libgps), heading and rate of turn from the gyro compass's NMEA on UDP (gpsd 3.22 drops the $HE
// talker and decodes neither THS nor ROT), rudder/engine orders out and their feedback in on the
// actuator wire (README "Putting mpgc on a boat"). Publishes nav/own_state (validity explicit:
// an invalid field is NaN and its NAV_*_VALID bit is clear) and sensors/ais per target.
// Its logic is mpgc/ship_bridge/bridge.hpp and node.hpp; this is its wiring.
#include <map>
#include <memory>
#include <optional>

#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/net/udp.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_bridge/gpsd_client.hpp"
#include "mpgc/ship_bridge/node.hpp"
#include "mpgc/ship/check_command.hpp"
#include "mpgc/topics.hpp"

namespace sb = mpgc::ship_bridge;
namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;
namespace geo = mpgc::geo;

namespace {

// The names of the NavFusion / AisAssembler counters that were new since the last call.
void publish_counters(rt::Component& c, const std::map<std::string, uint64_t>& now, std::map<std::string, uint64_t>& seen) {
  for (const auto& [k, v] : now) {
    auto& s = seen[k];
    if (v > s) c.count("rejected." + k, v - s), s = v;
  }
}

}  // namespace

int main(int argc, char** argv) {
  sb::NodeParams p;
  rt::ParamSet ps;
  p.declare(ps);
  return rt::run_component("ship_bridge", argc, argv, ps, [&](rt::Component& c) {
    p.validate();
    auto nav = std::make_shared<sb::NavFusion>(p.nav, p.origin());
    auto ais = std::make_shared<sb::AisAssembler>(static_cast<uint32_t>(p.own_mmsi));
    const sb::ActuatorLimits lim = p.limits();

    std::shared_ptr<mpgc::net::UdpReceiver> gyro, feedback;
    std::shared_ptr<mpgc::net::UdpSender> orders;
    if (p.gyro_port > 0) gyro = std::make_shared<mpgc::net::UdpReceiver>(p.listen_host, p.gyro_port);
    if (p.feedback_port > 0) feedback = std::make_shared<mpgc::net::UdpReceiver>(p.listen_host, p.feedback_port);
    if (p.orders_port > 0) orders = std::make_shared<mpgc::net::UdpSender>(p.orders_host, p.orders_port);
    c.log().info("gpsd {}:{}, gyro UDP {}, orders -> {}:{}, feedback UDP {}, own MMSI {}", p.gpsd_host, p.gpsd_port,
                 p.gyro_port, p.orders_host, p.orders_port, p.feedback_port, p.own_mmsi);

    auto& nav_w = c.publisher<msg::NavState>(topics::kOwnState, dds::QosProfile::state(3 * p.period));
    auto& ais_w = c.publisher<msg::AisReport>(topics::kAis, dds::QosProfile::command(64));

    struct State {
      std::unique_ptr<sb::GpsdClient> gpsd;
      int64_t next_connect_ns = 0;
      std::optional<msg::ActuatorCommand> cmd;
      int64_t cmd_ns = -1;
      sb::OrderPacer orders;
      std::map<std::string, uint64_t> seen_nav, seen_ais;
      std::string last_health;
    };
    auto st = std::make_shared<State>(State{nullptr, 0, std::nullopt, -1, sb::OrderPacer(p), {}, {}, {}});

    c.subscribe<msg::ActuatorCommand>(
        topics::kActuators, dds::QosProfile::command(16),
        [&c, st](const msg::ActuatorCommand& a) {
          st->cmd = a;
          st->cmd_ns = c.now_ns();
        },
        mpgc::ship::check_command);

    const auto apply_lines = [&c, nav](const std::vector<std::string>& lines, const char* input) {
      for (const auto& l : lines) {
        std::string kind;
        const std::string why = sb::apply_nmea_line(l, *nav, c.now_ns(), &kind);
        if (why.empty()) continue;
        if (kind.empty()) c.reject(std::string(input) + ".bad_sentence", why + ": " + l.substr(0, 90));
        else c.count(std::string(input) + ".ignored." + kind);  // other sentences on a shared wire are normal
      }
    };

    c.every(p.period, [&, st, nav, ais, gyro, feedback, orders, apply_lines, lim] {
      const int64_t now = c.now_ns();
      // gpsd: (re)connect, then take everything it has sent.
      if (!st->gpsd && now >= st->next_connect_ns) {
        try {
          st->gpsd = std::make_unique<sb::GpsdClient>(p.gpsd_host, p.gpsd_port, p.gpsd_nmea);
          c.log().info("connected to gpsd {}:{}", p.gpsd_host, p.gpsd_port);
        } catch (const std::exception& e) {
          c.count("gpsd.connect_failures");
          c.log().warn("{}", e.what());
          st->next_connect_ns = now + static_cast<int64_t>(p.gpsd_reconnect * 1e9);
        }
      }
      if (st->gpsd) {
        std::vector<sb::GpsdEvent> events;
        const bool open = st->gpsd->poll(0, &events);
        for (const auto& ev : events) {
          if (const auto* f = std::get_if<sb::GnssFix>(&ev)) {
            const std::string why = nav->on_fix(*f, now);
            if (!why.empty()) c.log().debug("fix not used: {}", why);
          } else if (const auto* h = std::get_if<sb::AttitudeHeading>(&ev)) {
            nav->on_heading(h->heading_deg, now);
          } else if (const auto* m = std::get_if<sb::AisMessage>(&ev)) {
            std::string why;
            const auto r = ais->on_message(*m, &why);
            if (!r) continue;
            msg::AisReport a{c.header(), r->mmsi, r->class_b ? msg::AisClass::AIS_CLASS_B : msg::AisClass::AIS_CLASS_A,
                             r->lat, r->lon, r->cog, r->sog, r->heading, r->rot, static_cast<uint8_t>(r->nav_status),
                             now, r->length, r->beam, r->name, static_cast<int16_t>(r->ship_type)};
            ais_w.write(a);
            c.count("ais.reports");
          } else if (const auto* raw = std::get_if<sb::RawNmea>(&ev)) {
            if (sb::gpsd_nmea_used(raw->line)) apply_lines({raw->line}, "gpsd_nmea");
          } else if (std::holds_alternative<sb::DeviceEnd>(ev)) {
            c.log().warn("gpsd reports a device gone");
          }
        }
        if (!open) {
          c.log().warn("gpsd closed the connection; reconnecting every {} s", p.gpsd_reconnect);
          c.count("gpsd.disconnects");
          st->gpsd.reset();
          st->next_connect_ns = now + static_cast<int64_t>(p.gpsd_reconnect * 1e9);
        }
      }
      if (gyro) apply_lines(gyro->receive_lines(), "gyro");
      if (feedback) apply_lines(feedback->receive_lines(), "feedback");
      publish_counters(c, nav->rejected(), st->seen_nav);
      publish_counters(c, ais->rejected(), st->seen_ais);

      // Own-ship state: invalid fields NaN with their bit clear, never the last value as if fresh.
      const sb::NavOutput o = nav->state(now);
      uint32_t mask = 0;
      if (o.position_valid) mask |= msg::NAV_POSITION_VALID;
      if (o.heading_valid) mask |= msg::NAV_HEADING_VALID;
      if (o.velocity_valid) mask |= msg::NAV_VELOCITY_VALID;
      if (o.rate_valid) mask |= msg::NAV_RATE_VALID;
      if (o.actuators_valid) mask |= msg::NAV_ACTUATORS_VALID;
      const sb::WaterVelocity w = sb::water_velocity(o);  // no speed log
      nav_w.write(msg::NavState{c.header(), o.x, o.y, o.lat, o.lon, o.heading, o.cog, o.sog, w.u, w.v, o.r, o.rudder, o.rpm, mask});

      // Orders: repeated while commands are fresh; when they stop, so do the orders (and the ship's
      // own actuator watchdog puts the rudder amidships), said on health.
      bool orders_stale = false;
      if (orders) {
        const auto step = st->orders.at(now, st->cmd.has_value(), st->cmd_ns);
        if (step.send) {
          bool sat = false;
          const std::string wire = sb::encode_orders(st->cmd->rudder, st->cmd->propeller_rpm, lim, &sat);
          if (sat) c.count("orders.saturated");
          if (!orders->send(wire)) c.count("orders.send_failures");
          c.count("orders.sent");
        }
        if (step.stopped) c.log().warn("no control/actuators for {} s: orders stopped", p.command_timeout);
        orders_stale = !step.fresh && st->cmd;
      }
      const std::string health = sb::health_text(p, o, orders_stale, st->gpsd != nullptr);
      if (health != st->last_health) {
        if (!health.empty()) c.log().warn("{}", health);
        else c.log().info("navigation valid");
        c.set_health(health.empty() ? msg::HealthState::HEALTH_OK : msg::HealthState::HEALTH_DEGRADED, health);
        st->last_health = health;
      }
    });
  });
}
