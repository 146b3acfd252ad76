// Simulator worlds (components/ship_simulator/config/*.yaml, a scenario's world:) through
// WorldConfig::from_yaml; an accepted world is built and stepped as the simulator would (own-ship
// model, targets, sensors) for a few steps. Expected rejections: std::runtime_error (WorldError,
// malformed YAML) and std::invalid_argument (model and world construction).
#include "env.hpp"
#include "fuzz.hpp"
#include "mpgc/ship_simulator/world.hpp"

namespace sim = mpgc::ship_simulator;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  mpgc::fuzz::default_env();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    sim::WorldConfig cfg = sim::WorldConfig::from_yaml(mpgc::fuzz::text(data, size), "fuzz.yaml");
    if (cfg.targets.size() > 200) return;  // a world that size is legal, just slow to step
    sim::World w(std::move(cfg), 100'000'000);
    (void)w.sense();
    for (int i = 0; i < 5; ++i) {
      w.step(w.initial_command());
      (void)w.sense();
    }
    (void)w.own_truth();
    (void)w.target_truth();
  });
}
