// control/actuators, both of its readers, after the validator they share (mpgc/ship/check_command.hpp):
// the simulator (the own-ship model steps with the order, which saturates it: MMG and Nomoto) and
// the ship bridge (encode_orders saturates it onto the actuator wire, whose ROR/PRC lines the
// simulator's devices read back in HIL). No exception is expected: every one is a finding.
#include <memory>

#include "env.hpp"
#include "msg.hpp"
#include "mpgc/ship/check_command.hpp"
#include "mpgc/ship_bridge/bridge.hpp"
#include "mpgc/ship_simulator/devices.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"

namespace sim = mpgc::ship_simulator;
namespace sb = mpgc::ship_bridge;
namespace msg = mpgc::msg;
namespace fz = mpgc::fuzz;

namespace {
struct Models {
  std::unique_ptr<sim::ShipModel> mmg, nomoto;
  sim::ShipState start;
};
Models& models() {
  static Models m = [] {
    Models x;
    sim::ModelChoice c;
    x.mmg = sim::make_model(c);
    c.kind = "nomoto";
    x.nomoto = sim::make_model(c);
    x.start = x.mmg->state();
    x.start.u = 7.0;
    x.start.rpm = 60.0;
    return x;
  }();
  return m;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fz::default_env();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fz::Reader r(data, size);
  Models& m = models();
  m.mmg->set_state(m.start);
  m.nomoto->set_state(m.start);
  sim::Devices dev(mpgc::geo::LocalNed({1.04, 0.19}), 1'700'000'000'000'000'000LL);
  sim::DeviceOrders orders;
  int64_t t = 0;
  for (int i = 0; i < 8 && !r.empty(); ++i) {
    const msg::ActuatorCommand a = fz::actuators(r);
    if (mpgc::ship::check_command(a).empty()) {
      const sim::ShipCommand cmd{a.rudder, a.propeller_rpm};
      m.mmg->step(0.1, cmd);
      m.nomoto->step(0.1, cmd);
      bool sat = false;
      const std::string wire = sb::encode_orders(a.rudder, a.propeller_rpm, sb::ActuatorLimits{}, &sat);
      std::vector<std::string> lines;
      for (size_t s = 0, e; s < wire.size(); s = e + 1) {
        e = wire.find('\n', s);
        if (e == std::string::npos) e = wire.size();
        lines.push_back(wire.substr(s, e - s));
      }
      t += 100'000'000;
      dev.on_order_lines(lines, t, m.mmg->max_rudder(), m.mmg->max_rpm(), &orders);
    }
  }
  return 0;
}
