// Scenario files (scenarios/*.yaml) through parse_scenario, then what mpgc_run does with an
// accepted one: the world it writes for the simulator parsed back (WorldConfig::from_yaml), the
// inline chart shapes (obstacle_manager's add_shapes) and the evaluation's parameters.
// Expected rejections: std::runtime_error (the documented "<file>:<line>: <key>: <problem>",
// ChartError and WorldError included) and std::invalid_argument (parameter validation).
#include <yaml-cpp/yaml.h>

#include "env.hpp"
#include "fuzz.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/scenario_runner/scenario.hpp"
#include "mpgc/ship_simulator/world.hpp"

namespace sr = mpgc::scenario_runner;
namespace om = mpgc::obstacle_manager;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  mpgc::fuzz::default_env();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    const sr::Scenario s = sr::parse_scenario(mpgc::fuzz::text(data, size), "fuzz.yaml");
    (void)sr::evaluation_params(s, s.lpp);
    YAML::Emitter e;
    e << s.world;
    (void)mpgc::ship_simulator::WorldConfig::from_yaml(e.c_str(), "world.yaml");
    om::ChartParams cp;
    om::ChartBuilder b(mpgc::geo::LocalNed({s.origin_lat_deg * 0.017453292519943295, s.origin_lon_deg * 0.017453292519943295}), cp);
    om::add_shapes(b, s.chart_shapes);
  });
}
