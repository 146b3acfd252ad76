// Chart input against the real NOAA cell US4MD81M and its GeoJSON extracts, inline shapes, and
// malformed input. The 12 labelled points of crop_annapolis_test_points.csv are the ground truth.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <random>
#include <sstream>

#include "mpgc/geo/angles.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/testing.hpp"

namespace om = mpgc::obstacle_manager;
namespace fs = std::filesystem;
using mpgc::geo::deg2rad;
using mpgc::geom::Vec2;

namespace {

// Origin in the middle of the Annapolis crop (lon -76.50..-76.40, lat 38.93..39.00).
const mpgc::geo::LatLon kOrigin{deg2rad(38.965), deg2rad(-76.45)};

struct Labelled {
  double lon, lat;
  bool land;
  double drval1;  // NaN for land points
};

std::vector<Labelled> labelled_points() {
  std::ifstream in(mpgc::testing::shared_data("chart/crop_annapolis_test_points.csv"));
  EXPECT_TRUE(in.good());
  std::vector<Labelled> out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF file
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string lon, lat, land, band;
    std::getline(ss, lon, ',');
    std::getline(ss, lat, ',');
    std::getline(ss, land, ',');
    std::getline(ss, band, ',');
    out.push_back({std::stod(lon), std::stod(lat), land == "True",
                   band.empty() ? std::nan("") : std::stod(band.substr(0, band.find("..")))});
  }
  return out;
}

mpgc::geom::Vec2 ned(const om::ChartBuilder& b, double lon, double lat) {
  const auto p = b.frame().to_ned({deg2rad(lat), deg2rad(lon)});
  return {p.x, p.y};
}

om::ChartParams land_only() {
  om::ChartParams p;
  p.spacing = 20.0;
  p.depth_areas = false;
  return p;
}

// A temp directory removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("mpgc_om_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    const auto f = path / name;
    std::ofstream(f) << text;
    return f.string();
  }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const om::ChartError& e) {
    return e.what();
  }
  return "(no ChartError)";
}

}  // namespace

TEST(Chart, LabelledPointsFromAnnapolisCropGeoJson) {
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), land_only());
  EXPECT_GT(b.load_file(mpgc::testing::shared_data("chart/crop_annapolis_LNDARE.geojson")), 0u);
  const auto set = b.take();
  om::FixedObstacleMap map(set.points, set.polygons);
  const auto pts = labelled_points();
  ASSERT_EQ(pts.size(), 12u);
  int land = 0;
  for (const auto& l : pts) {
    EXPECT_EQ(map.inside_land(ned(b, l.lon, l.lat)), l.land) << l.lon << ", " << l.lat;
    land += l.land;
  }
  EXPECT_EQ(land, 3);  // both outcomes are exercised
}

TEST(Chart, WholeS57CellWithUpdatesAndLabelledPoints) {
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), land_only());
  const auto n = b.load_file(mpgc::testing::shared_data("chart/US4MD81M/US4MD81M.000"));
  const auto set = b.take();
  // Layer sizes of the cell with updates .001-.003 applied (WRECKS is 110 without them).
  EXPECT_EQ(set.layer_counts.at("LNDARE"), 183u);
  EXPECT_EQ(set.layer_counts.at("COALNE"), 1826u);
  EXPECT_EQ(set.layer_counts.at("OBSTRN"), 219u);
  EXPECT_EQ(set.layer_counts.at("WRECKS"), 111u);
  EXPECT_EQ(set.layer_counts.count("DEPARE"), 0u);  // depth areas off here
  EXPECT_EQ(n, 183u + 1826u + 219u + 111u);
  EXPECT_GT(set.points.size(), 100000u);  // the whole cell densified at 20 m
  std::printf("US4MD81M: %zu points, %zu rings\n", set.points.size(), set.polygons.size());
  om::FixedObstacleMap map(set.points, set.polygons);
  for (const auto& l : labelled_points()) EXPECT_EQ(map.inside_land(ned(b, l.lon, l.lat)), l.land) << l.lon << ", " << l.lat;
}

TEST(Chart, DepthAreasShallowerThanDraughtAreObstacles) {
  // Draught 3 m: depth bands starting at 0.0 or 1.8 m are obstacles, 5.4 m and 10.9 m are not.
  om::ChartParams p;
  p.draught = 3.0;
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), p);
  b.load_file(mpgc::testing::shared_data("chart/crop_annapolis_DEPARE.geojson"));
  b.load_file(mpgc::testing::shared_data("chart/crop_annapolis_LNDARE.geojson"));
  const auto set = b.take();
  EXPECT_GT(set.skipped.at("DEPARE deeper than draught"), 0u);
  om::FixedObstacleMap map(set.points, set.polygons);
  for (const auto& l : labelled_points()) {
    const bool expect = l.land || l.drval1 < 3.0;
    EXPECT_EQ(map.inside_land(ned(b, l.lon, l.lat)), expect) << l.lon << ", " << l.lat << " drval1 " << l.drval1;
  }
}

TEST(Chart, WholeCellGeoJsonExtractsLoad) {
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), land_only());
  EXPECT_EQ(b.load_file(mpgc::testing::shared_data("chart/LNDARE_polygons.geojson")), 162u);
  EXPECT_EQ(b.load_file(mpgc::testing::shared_data("chart/OBSTRN.geojson")), 219u);
  om::FixedObstacleMap map(b.result().points, b.result().polygons);
  for (const auto& l : labelled_points()) EXPECT_EQ(map.inside_land(ned(b, l.lon, l.lat)), l.land);
}

TEST(Chart, NedLatLonRoundTrips) {
  const mpgc::geo::LocalNed frame(kOrigin);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-50000.0, 50000.0);
  for (int i = 0; i < 1000; ++i) {
    const mpgc::geo::NorthEast p{u(rng), u(rng)};
    const auto ll = frame.to_latlon(p);
    const auto q = frame.to_ned(ll);
    ASSERT_NEAR(q.x, p.x, 1e-6);
    ASSERT_NEAR(q.y, p.y, 1e-6);
    const auto ll2 = frame.to_latlon(q);
    ASSERT_NEAR(ll2.lat, ll.lat, 1e-12);
    ASSERT_NEAR(ll2.lon, ll.lon, 1e-12);
  }
  // 1 minute of latitude north of the origin is about 1852 m (1 nautical mile).
  const auto p = frame.to_ned({kOrigin.lat + deg2rad(1.0 / 60.0), kOrigin.lon});
  EXPECT_NEAR(p.x, 1852.0, 5.0);
  EXPECT_NEAR(p.y, 0.0, 1e-6);
}

TEST(Chart, InlineShapes) {
  om::ChartParams p;
  p.spacing = 10.0;
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), p);
  b.add_circle({1000, 500}, 208, "Cir01");  // seed 003 Table 3 style
  // Canal walls (seed 000 scenario 3) as two lines 100 m apart.
  b.add_line({{0, -50}, {2000, -50}}, "canal west wall");
  b.add_line({{0, 50}, {1000, 50}, {2000, 50}}, "canal east wall");
  b.add_polygon({{3000, 0}, {3100, 0}, {3100, 100}, {3000, 100}}, "pier");
  b.add_point({-100, -100}, "buoy");
  const auto set = b.take();
  om::FixedObstacleMap map(set.points, set.polygons);
  // Every densified point is at most `spacing` from the next one on the circle.
  EXPECT_TRUE(map.inside_land({1000, 500}));
  EXPECT_TRUE(map.inside_land({1000 + 207.9, 500}));  // the circle is inside the polygon
  EXPECT_FALSE(map.inside_land({1000 + 215, 500}));
  EXPECT_FALSE(map.inside_land({1000, 0}));             // canal: the lines have no inside
  EXPECT_NEAR(map.clearance({1000, 0}), 50.0, 1e-9);
  EXPECT_EQ(map.segment_clearance({500, -100}, {500, 0}), 0.0);  // crossing a wall
  EXPECT_TRUE(map.inside_land({3050, 50}));
  EXPECT_NEAR(map.nearest_distance({-100, -97}), 3.0, 1e-9);
  EXPECT_NE(error_of([&] { b.add_circle({0, 0}, -1, "bad circle"); }).find("bad circle"), std::string::npos);
  EXPECT_NE(error_of([&] { b.add_polygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, "bow tie"); }).find("bow tie: polygon ring intersects"),
            std::string::npos);
  EXPECT_NE(error_of([&] { b.add_line({{0, 0}}, "stub"); }).find("stub"), std::string::npos);
}

TEST(Chart, DensifyRespectsSpacing) {
  const std::vector<mpgc::geom::Vec2> ring{{0, 0}, {100, 0}, {100, 35}, {0, 35}};
  const auto pts = om::densify_ring(ring, 10.0);
  EXPECT_EQ(pts.size(), 10u + 4u + 10u + 4u);
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& a = pts[i];
    const auto& c = pts[(i + 1) % pts.size()];
    EXPECT_LE(std::hypot(c.x - a.x, c.y - a.y), 10.0 + 1e-9);
  }
  EXPECT_THROW((om::ChartParams{0.0}).validate(), std::invalid_argument);
}

TEST(Chart, CropKeepsRegion) {
  om::ObstacleSet s;
  s.points = {{0, 0}, {50, 50}, {500, 500}};
  s.polygons = {{0, {{90, 90}, {200, 90}, {200, 200}}}, {1, {{900, 900}, {950, 900}, {950, 950}}}};
  const auto c = om::crop(s, {-10, -10, 100, 100});
  EXPECT_EQ(c.points.size(), 2u);
  ASSERT_EQ(c.polygons.size(), 1u);
  EXPECT_EQ(c.polygons[0].feature_id, 0u);
}

TEST(Chart, MalformedGeoJsonGivesClearErrors) {
  TempDir dir;
  auto feature = [](const std::string& name, const std::string& geom) {
    return R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":")" + name +
           R"("},"geometry":)" + geom + "}]}";
  };
  om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), land_only());
  const auto trunc = dir.write("trunc.geojson", R"({"type":"FeatureCollection","features":[{"type":"Feature")");
  EXPECT_NE(error_of([&] { b.load_file(trunc); }).find("trunc.geojson: cannot open as GeoJSON"), std::string::npos)
      << error_of([&] { b.load_file(trunc); });
  const auto unclosed = dir.write("unclosed.geojson", feature("u", R"({"type":"Polygon","coordinates":[[[-76.45,38.96],[-76.44,38.96],[-76.44,38.97]]]})"));
  EXPECT_NE(error_of([&] { b.load_file(unclosed); }).find("unclosed.geojson:unclosed:0 outer ring"), std::string::npos)
      << error_of([&] { b.load_file(unclosed); });
  const auto bow = dir.write("bow.geojson", feature("b", R"({"type":"Polygon","coordinates":[[[-76.45,38.96],[-76.44,38.97],[-76.44,38.96],[-76.45,38.97],[-76.45,38.96]]]})"));
  const auto bow_err = error_of([&] { b.load_file(bow); });
  EXPECT_NE(bow_err.find("bow.geojson:bow:0: invalid polygon"), std::string::npos) << bow_err;
  EXPECT_NE(bow_err.find("Self-intersection"), std::string::npos) << bow_err;
  const auto far = dir.write("far.geojson", feature("f", R"({"type":"Point","coordinates":[200.0,38.9]})"));
  EXPECT_NE(error_of([&] { b.load_file(far); }).find("far.geojson:far:0: coordinate out of range"), std::string::npos)
      << error_of([&] { b.load_file(far); });
  const auto empty = dir.write("empty.geojson", feature("e", "null"));
  EXPECT_NE(error_of([&] { b.load_file(empty); }).find("empty.geojson:empty:0: empty geometry"), std::string::npos)
      << error_of([&] { b.load_file(empty); });
  EXPECT_NE(error_of([&] { b.load_file((dir.path / "missing.geojson").string()); }).find("missing.geojson: cannot open"),
            std::string::npos);
  EXPECT_NE(error_of([&] { b.load_file("chart.shp"); }).find("unknown chart format"), std::string::npos);
}

TEST(Chart, TruncatedS57CellGivesClearError) {
  TempDir dir;
  const auto src = mpgc::testing::shared_data("chart/US4MD81M/US4MD81M.000");
  for (const size_t keep : {size_t{100}, size_t{1000000}}) {
    std::ifstream in(src, std::ios::binary);
    std::string bytes(keep, '\0');
    in.read(&bytes[0], static_cast<std::streamsize>(keep));
    const auto cut = dir.write("US4MD81M.000", bytes);
    om::ChartBuilder b(mpgc::geo::LocalNed(kOrigin), land_only());
    const auto err = error_of([&] { b.load_file(cut); });
    EXPECT_NE(err.find("US4MD81M.000"), std::string::npos) << err;
    EXPECT_NE(err, "(no ChartError)") << "kept " << keep << " bytes";
    std::printf("truncated to %zu bytes: %s\n", keep, err.c_str());
  }
}
