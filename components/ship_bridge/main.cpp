// mpgc_ship_bridge: stands where ship_simulator stands, on a real vessel. GNSS and AIS from gpsd
// (libgps), heading and rate of turn from the gyro compass's NMEA on UDP (gpsd 3.22 drops the $HE
// talker and decodes neither THS nor ROT), rudder/engine orders out and their feedback in on the
// actuator wire (README "Putting mpgc on a boat"). Publishes nav/own_state (validity explicit:
// an invalid field is NaN and its NAV_*_VALID bit is clear) and sensors/ais per target.
#include <algorithm>
#include <cmath>
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
#include "mpgc/ship/check_command.hpp"
#include "mpgc/topics.hpp"

namespace sb = mpgc::ship_bridge;
namespace msg = mpgc::msg;
namespace dds = mpgc::dds;
namespace rt = mpgc::rt;
namespace topics = mpgc::topics;
namespace geo = mpgc::geo;

namespace {

struct Params {
  std::string gpsd_host;
  int gpsd_port = 2947;
  bool gpsd_nmea = true;
  double gpsd_reconnect = 2.0;  // [s]
  std::string listen_host;
  int gyro_port = 0;            // 0: no direct gyro input
  std::string origin_source;    // param | first_fix
  double origin_lat = 0, origin_lon = 0;  // [deg]
  int own_mmsi = 0;
  double period = 0.1;          // [s] nav/own_state period and input polling
  sb::NavParams nav;
  std::string orders_host;
  int orders_port = 0;          // 0: no actuator wire (monitoring only)
  int feedback_port = 0;
  double order_period = 0.2;    // [s] orders are repeated: the steering gear's watchdog wants them
  double command_timeout = 1.0; // [s] no control/actuators this long: stop sending orders
  double max_rudder_deg = 35.0, min_rpm = 0.0, max_rpm = 150.0;

  void declare(rt::ParamSet& ps) {
    ps.add("gpsd.host", &gpsd_host, "127.0.0.1", "gpsd host");
    ps.add("gpsd.port", &gpsd_port, 2947, "-", 1, 65535, "gpsd TCP port");
    ps.add("gpsd.nmea", &gpsd_nmea, true, "also watch gpsd's raw NMEA (HDT/THS/ROT from talkers gpsd passes through)");
    ps.add("gpsd.reconnect", &gpsd_reconnect, 2.0, "s", 0.1, 600.0, "retry period while gpsd cannot be reached");
    ps.add("listen.host", &listen_host, "127.0.0.1", "IPv4 address the UDP inputs bind to");
    ps.add("gyro.port", &gyro_port, 0, "-", 0, 65535, "UDP port of the gyro compass NMEA (HDT/THS/ROT); 0 = none");
    ps.add("origin.source", &origin_source, "first_fix", "local NED origin: origin.lat/lon, or the first good fix",
           {"param", "first_fix"});
    ps.add("origin.lat", &origin_lat, 0.0, "deg", -90.0, 90.0, "NED origin latitude (origin.source = param)");
    ps.add("origin.lon", &origin_lon, 0.0, "deg", -180.0, 180.0, "NED origin longitude (origin.source = param)");
    ps.add("own.mmsi", &own_mmsi, 0, "-", 0, 999999999, "own ship's MMSI: its AIS messages are never a target");
    ps.add("period", &period, 0.1, "s", 0.01, 10.0, "nav/own_state period (inputs are polled at the same rate)");
    ps.add("nav.fix_timeout", &nav.fix_timeout, 3.0, "s", 0.1, 600.0, "a position older than this is invalid");
    ps.add("nav.heading_timeout", &nav.heading_timeout, 1.0, "s", 0.05, 600.0, "a heading / rate of turn older than this is invalid");
    ps.add("nav.feedback_timeout", &nav.feedback_timeout, 2.0, "s", 0.05, 600.0, "rudder/rpm feedback older than this is invalid");
    ps.add("nav.require_3d", &nav.require_3d, false, "a 2-D fix is invalid");
    ps.add("nav.max_speed", &nav.max_speed, 25.0, "m/s", 0.1, 200.0, "a position jump faster than this is rejected");
    ps.add("nav.jump_margin", &nav.jump_margin, 30.0, "m", 0.0, 10000.0, "GNSS noise allowance of the jump check");
    ps.add("nav.max_sog", &nav.max_sog, 40.0, "m/s", 0.1, 200.0, "a reported SOG above this is rejected");
    ps.add("actuators.host", &orders_host, "127.0.0.1", "IPv4 address of the steering gear / engine control (orders)");
    ps.add("actuators.port", &orders_port, 0, "-", 0, 65535, "UDP port orders (ROR, PRC) are sent to; 0 = no orders");
    ps.add("actuators.feedback_port", &feedback_port, 0, "-", 0, 65535, "UDP port for RSA/RPM feedback; 0 = none");
    ps.add("actuators.period", &order_period, 0.2, "s", 0.01, 10.0, "orders are repeated at this period");
    ps.add("actuators.command_timeout", &command_timeout, 1.0, "s", 0.05, 60.0,
           "no control/actuators this long: stop sending orders, the steering gear's own watchdog takes over");
    ps.add("actuators.max_rudder", &max_rudder_deg, 35.0, "deg", 1.0, 90.0, "rudder limit (orders beyond are saturated)");
    ps.add("actuators.min_rpm", &min_rpm, 0.0, "1/min", -10000.0, 10000.0, "lowest shaft speed order");
    ps.add("actuators.max_rpm", &max_rpm, 150.0, "1/min", 0.0, 10000.0, "highest shaft speed order");
  }
};

// The names of the NavFusion / AisAssembler counters that were new since the last call.
void publish_counters(rt::Component& c, const std::map<std::string, uint64_t>& now, std::map<std::string, uint64_t>& seen) {
  for (const auto& [k, v] : now) {
    auto& s = seen[k];
    if (v > s) c.count("rejected." + k, v - s), s = v;
  }
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  rt::ParamSet ps;
  p.declare(ps);
  return rt::run_component("ship_bridge", argc, argv, ps, [&](rt::Component& c) {
    if (p.min_rpm > p.max_rpm) throw std::invalid_argument("actuators.min_rpm is above actuators.max_rpm");
    std::optional<geo::LatLon> origin;
    if (p.origin_source == "param") origin = geo::LatLon{geo::deg2rad(p.origin_lat), geo::deg2rad(p.origin_lon)};
    auto nav = std::make_shared<sb::NavFusion>(p.nav, origin);
    auto ais = std::make_shared<sb::AisAssembler>(static_cast<uint32_t>(p.own_mmsi));
    const sb::ActuatorLimits lim{geo::deg2rad(p.max_rudder_deg), p.min_rpm, p.max_rpm};

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
      int64_t cmd_ns = -1, next_order_ns = 0;
      bool ordering = false;
      std::map<std::string, uint64_t> seen_nav, seen_ais;
      std::string last_health;
    };
    auto st = std::make_shared<State>();

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
            // What gpsd does not decode ($TIROT, THS) and the receiver's own verdict on its fix
            // (GGA quality, RMC status: gpsd reports an RMC "V" cycle with a position as a 3-D fix).
            // gpsd sends a cycle's raw sentences before its TPV, so the verdict applies to that TPV.
            static const char* kUsed[] = {"ROT", "THS", "GGA", "RMC"};
            if (raw->line.size() > 6 &&
                std::any_of(std::begin(kUsed), std::end(kUsed), [&](const char* t) { return raw->line.compare(3, 3, t) == 0; }))
              apply_lines({raw->line}, "gpsd_nmea");
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
      // No speed log: through-water velocity from SOG/COG and heading (exact without current).
      double u = std::nan(""), v = std::nan("");
      if (o.velocity_valid && o.heading_valid) {
        const double beta = geo::angle_diff(o.cog, o.heading);
        u = o.sog * std::cos(beta), v = o.sog * std::sin(beta);
      }
      nav_w.write(msg::NavState{c.header(), o.x, o.y, o.lat, o.lon, o.heading, o.cog, o.sog, u, v, o.r, o.rudder, o.rpm, mask});

      // Orders: repeated while commands are fresh; when they stop, so do the orders (and the ship's
      // own actuator watchdog puts the rudder amidships), said on health.
      std::string health;
      if (orders) {
        const bool fresh = st->cmd && now - st->cmd_ns <= static_cast<int64_t>(p.command_timeout * 1e9);
        if (fresh && now >= st->next_order_ns) {
          bool sat = false;
          const std::string wire = sb::encode_orders(st->cmd->rudder, st->cmd->propeller_rpm, lim, &sat);
          if (sat) c.count("orders.saturated");
          if (!orders->send(wire)) c.count("orders.send_failures");
          c.count("orders.sent");
          st->next_order_ns = now + static_cast<int64_t>(p.order_period * 1e9);
        }
        if (st->ordering && !fresh) c.log().warn("no control/actuators for {} s: orders stopped", p.command_timeout);
        st->ordering = fresh;
        if (!fresh && st->cmd) health = "no fresh control/actuators: no orders sent";
      }
      const uint32_t need = msg::NAV_POSITION_VALID | msg::NAV_HEADING_VALID | msg::NAV_VELOCITY_VALID;
      if ((mask & need) != need) health = "navigation invalid: " + o.why_invalid + (health.empty() ? "" : "; " + health);
      if (!st->gpsd) health = "gpsd " + p.gpsd_host + ":" + std::to_string(p.gpsd_port) + " not connected" +
                              (health.empty() ? "" : "; " + health);
      if (health != st->last_health) {
        if (!health.empty()) c.log().warn("{}", health);
        else c.log().info("navigation valid");
        c.set_health(health.empty() ? msg::HealthState::HEALTH_OK : msg::HealthState::HEALTH_DEGRADED, health);
        st->last_health = health;
      }
    });
  });
}
