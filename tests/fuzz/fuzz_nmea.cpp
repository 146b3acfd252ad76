// NMEA 0183 lines (../shared/data/nmea/: real GNSS, gyro and AIS logs) through every reader of the
// project: mpgc::nmea::parse (with and without the checksum required) and each decoder (HDT, THS,
// ROT, RSA, ROR, RPM, PRC); the bridge's apply_nmea_line into NavFusion, as the gyro, feedback and
// gpsd raw-NMEA inputs do; and the simulator's order wire (Devices::on_order_lines), as in HIL.
// One line per input line; a malformed line is rejected by a return value, never an exception, so
// every exception here is a finding.
#include <vector>

#include "fuzz.hpp"
#include "mpgc/nmea/nmea0183.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_simulator/devices.hpp"

namespace nmea = mpgc::nmea;
namespace sb = mpgc::ship_bridge;
namespace sim = mpgc::ship_simulator;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> lines;
  std::string cur;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      lines.push_back(cur);
      cur.clear();
    } else {
      cur.push_back(static_cast<char>(data[i]));
    }
  }
  lines.push_back(cur);

  sb::NavFusion nav(sb::NavParams{}, mpgc::geo::LatLon{1.04, 0.19});
  int64_t now = 1'000'000'000;
  for (const auto& l : lines) {
    for (bool strict : {true, false}) {
      std::string why;
      const auto s = nmea::parse(l, &why, strict);
      if (!s) continue;
      (void)nmea::parse_hdt(*s, &why);
      (void)nmea::parse_ths(*s, &why);
      (void)nmea::parse_rot(*s, &why);
      (void)nmea::parse_rsa(*s, &why);
      (void)nmea::parse_ror(*s, &why);
      (void)nmea::parse_rpm(*s, &why);
      (void)nmea::parse_prc(*s, &why);
    }
    std::string kind;
    (void)sb::apply_nmea_line(l, nav, now, &kind);
    now += 100'000'000;
  }
  (void)nav.state(now);

  sim::Devices dev(mpgc::geo::LocalNed({1.04, 0.19}), 1'700'000'000'000'000'000LL);
  sim::DeviceOrders orders;
  dev.on_order_lines(lines, now, 0.6108652, 150.0, &orders);
  sim::ShipCommand cmd{0.0, 60.0};
  (void)sim::follow_orders(orders, now + 500'000'000, 2.0, &cmd);
  return 0;
}
