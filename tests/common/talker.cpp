// Test component: publishes msg::Counter{name, n} on `topic` at `rate`; stops after `count`
// samples when count > 0 (exit code `exit_code`), else runs until SIGTERM.
#include "mpgc/runtime/component.hpp"

int main(int argc, char** argv) {
  std::string topic;
  double rate = 10;
  int count = 0, exit_code = 0;
  mpgc::rt::ParamSet ps;
  ps.add("topic", &topic, "test/chatter", "topic to publish msg::Counter on");
  ps.add("rate", &rate, 10.0, "Hz", 0.1, 1000.0, "publication rate");
  ps.add("count", &count, 0, "-", 0, 1000000, "samples before exiting; 0 = until SIGTERM");
  ps.add("exit_code", &exit_code, 0, "-", 0, 255, "exit code after `count` samples");
  return mpgc::rt::run_component("talker", argc, argv, ps, [&](mpgc::rt::Component& c) {
    auto& w = c.publisher<mpgc::msg::Counter>(topic, mpgc::dds::QosProfile::command(16));
    auto sent = std::make_shared<int>(0);
    c.every(1.0 / rate, [&c, &w, sent, count, exit_code] {
      w.write(mpgc::msg::Counter{"talker", static_cast<uint64_t>(++*sent)});
      if (count > 0 && *sent >= count) c.stop(exit_code);
    });
  });
}
