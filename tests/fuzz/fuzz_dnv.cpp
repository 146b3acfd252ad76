// DNV ship-traffic-generator situations (../shared/data/encounters/dnv/, generated and input
// files) through read_dnv_situation and read_dnv_desired, then what an accepted situation feeds:
// its COLREG assessment (assess_dnv, as ./mpgc classify) and its conversion to a scenario
// (dnv_scenario, as ./mpgc run FILE.json). Expected rejections: std::runtime_error ("<file>:
// <field>: <problem>") and std::invalid_argument (geometry and parameter checks).
#include "env.hpp"
#include "fuzz.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/situational_awareness/dnv_situation.hpp"

namespace sa = mpgc::sa;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  mpgc::fuzz::default_env();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = mpgc::fuzz::scratch_file("traffic_situation_01.json", data, size);
  mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    for (const auto& d : sa::read_dnv_desired(path)) (void)sa::from_dnv_name(d);
  });
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    const sa::DnvSituation s = sa::read_dnv_situation(path);
    (void)sa::assess_dnv(s, mpgc::colreg::ColregParams{});
    std::vector<std::string> desired(s.targets.size(), "crossing-give-way");
    (void)mpgc::scenario_runner::dnv_scenario(s, desired);
  });
}
