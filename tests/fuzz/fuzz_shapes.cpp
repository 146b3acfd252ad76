// Inline chart shapes (obstacle_manager's chart.shapes parameter, a scenario's chart.shapes:
// "circle N E R; polygon N E N E ...; line N E ...; point N E") through add_shapes and
// scale_shapes (the runner's *_lpp scaling), then the planner's query map of the result.
// Expected rejections: ChartError (std::runtime_error) and std::invalid_argument.
#include "fuzz.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/scenario_runner/scenario.hpp"

namespace om = mpgc::obstacle_manager;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string spec = mpgc::fuzz::text(data, size);
  for (const std::string& s : {spec, std::string()}) {
    mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
      const std::string use = s.empty() ? mpgc::scenario_runner::scale_shapes(spec, 320.0) : s;
      om::ChartParams p;
      p.spacing = 50.0;
      p.max_points = 2'000'000;
      om::ChartBuilder b(mpgc::geo::LocalNed({0.6771, -1.3317}), p);
      om::add_shapes(b, use);
      const om::ObstacleSet set = b.take();
      const om::FixedObstacleMap map(set.points, set.polygons);
      (void)map.clearance({0.0, 0.0});
      (void)map.inside_land({100.0, 100.0});
    });
  }
  return 0;
}
