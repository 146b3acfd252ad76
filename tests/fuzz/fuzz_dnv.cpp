// DNV ship-traffic-generator situations (../shared/data/encounters/dnv/, generated and input
// files) through dnv::read_situation and dnv::read_desired (common), then what an accepted
// situation feeds: its COLREG assessment (dnv::assess, as ./mpgc classify) and its conversion to a scenario
// (dnv_scenario, as ./mpgc run FILE.json). Expected rejections: std::runtime_error ("<file>:
// <field>: <problem>") and std::invalid_argument (geometry and parameter checks).
#include "env.hpp"
#include "fuzz.hpp"
#include "mpgc/dnv/situation.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace dnv = mpgc::dnv;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  mpgc::fuzz::default_env();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = mpgc::fuzz::scratch_file("traffic_situation_01.json", data, size);
  mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    for (const auto& d : dnv::read_desired(path)) (void)dnv::encounter_type(d);
  });
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    const dnv::Situation s = dnv::read_situation(path);
    (void)dnv::assess(s, mpgc::colreg::ColregParams{});
    std::vector<std::string> desired(s.targets.size(), "crossing-give-way");
    (void)mpgc::scenario_runner::dnv_scenario(s, desired);
  });
}
