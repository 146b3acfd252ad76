// Component parameter files and --set overrides through mpgc::rt::ParamSet, the one parser every
// component uses for its configuration (components/*/params/*.yaml, launch files' params:).
// The set declared here has one parameter of every kind (double with a range, int, bool, string,
// string with choices) under the names obstacle_manager's shipped files use, so those seeds are
// accepted and their mutants reach the value checks. The input is read as a YAML file, then each
// of its lines as a NAME=VALUE override. Expected rejection: ParamError (std::runtime_error).
#include "fuzz.hpp"
#include "mpgc/runtime/params.hpp"

namespace rt = mpgc::rt;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text = mpgc::fuzz::text(data, size);
  double spacing = 0, draught = 0, half = 0, rep = 0, lat = 0;
  int port = 0, count = 0;
  bool depth = false;
  std::string files, shapes, source;
  rt::ParamSet ps;
  ps.add("chart.files", &files, "", "chart files");
  ps.add("chart.shapes", &shapes, "", "inline shapes");
  ps.add("chart.spacing", &spacing, 20.0, "m", 0.5, 10000.0, "spacing");
  ps.add("chart.draught", &draught, 5.0, "m", 0.0, 50.0, "draught");
  ps.add("chart.depth_areas", &depth, true, "depth areas");
  ps.add("chart.origin_lat", &lat, 0.0, "deg", -90.0, 90.0, "origin");
  ps.add("region.half_size", &half, 10000.0, "m", 0.0, 1e6, "half size");
  ps.add("region.republish_distance", &rep, 2000.0, "m", 1.0, 1e6, "republish");
  ps.add("gpsd.port", &port, 2947, "-", 1, 65535, "port");
  ps.add("plan.max_iterations", &count, 20000, "-", 1, 2000000, "iterations");
  ps.add("origin.source", &source, "nav", "origin", {"nav", "param"});
  mpgc::fuzz::expect<rt::ParamError>([&] { ps.load_yaml_string(text, "fuzz.yaml"); });
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (line.find('=') != std::string::npos) mpgc::fuzz::expect<rt::ParamError>([&] { ps.set_override(line); });
    start = end + 1;
  }
  return mpgc::fuzz::expect<rt::ParamError>([&] {
    ps.validate_and_apply();
    (void)ps.effective();
    (void)ps.help();
  });
}
