// Charts through ChartBuilder::load_file, as obstacle_manager loads them: GeoJSON (GDAL's GeoJSON
// driver, then our feature conversion, ring checks and densification) when the input starts with
// '{' or '[' after blanks, else an S-57 ENC cell (*.000, ISO 8211, GDAL's S57 driver). An accepted
// chart is cropped and turned into the planner's query map as obstacles/fixed would carry it.
// Expected rejections: ChartError (std::runtime_error) and std::invalid_argument (the query map).
#include "fuzz.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"

namespace om = mpgc::obstacle_manager;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  size_t i = 0;
  while (i < size && (data[i] == ' ' || data[i] == '\n' || data[i] == '\r' || data[i] == '\t')) ++i;
  const bool json = i < size && (data[i] == '{' || data[i] == '[');
  const std::string path = mpgc::fuzz::scratch_file(json ? "chart.geojson" : "CHART.000", data, size);
  return mpgc::fuzz::expect<std::runtime_error, std::invalid_argument>([&] {
    om::ChartParams p;
    p.spacing = 200.0;           // coarse: the densification is exercised, not timed
    p.max_points = 2'000'000;
    om::ChartBuilder b(mpgc::geo::LocalNed({0.6771, -1.3317}), p);  // 38.8 N, 76.3 W (the cells' area)
    b.load_file(path);
    const om::ObstacleSet set = b.take();
    const om::ObstacleSet part = om::crop(set, {-20000, -20000, 20000, 20000});
    const om::FixedObstacleMap map(part.points, part.polygons);
    (void)map.bounds();
  });
}
