// Test component: counts msg::Counter samples on `topic` and logs "received N" for each.
#include "mpgc/runtime/component.hpp"

int main(int argc, char** argv) {
  std::string topic;
  mpgc::rt::ParamSet ps;
  ps.add("topic", &topic, "test/chatter", "topic to read msg::Counter from");
  return mpgc::rt::run_component("listener", argc, argv, ps, [&](mpgc::rt::Component& c) {
    auto received = std::make_shared<uint64_t>(0);
    c.subscribe<mpgc::msg::Counter>(topic, mpgc::dds::QosProfile::command(16),
                                    [&c, received](const mpgc::msg::Counter& s) {
                                      ++*received;
                                      c.log().info("received {} (value {} from {})", *received, s.value, s.name);
                                    });
  });
}
