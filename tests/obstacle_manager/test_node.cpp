// The obstacle manager component's logic without DDS or a clock (node.hpp): what main.cpp used to
// do inline, tested here directly.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "mpgc/obstacle_manager/node.hpp"
#include "mpgc/testing_params.hpp"

namespace om = mpgc::obstacle_manager;
namespace fs = std::filesystem;

namespace {

om::NodeParams declared(const std::vector<std::string>& overrides = {}) {
  om::NodeParams p = mpgc::testing::declared<om::NodeParams>(om::declare, overrides);
  p.validate();
  return p;
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("mpgc_om_node_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path / name) << text;
    return (path / name).string();
  }
};

const char* kSquare =
    R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":"land"},"geometry":)"
    R"({"type":"Polygon","coordinates":[[[0.001,0.001],[0.002,0.001],[0.002,0.002],[0.001,0.002],[0.001,0.001]]]}}]})";

TEST(ObstacleNode, ChartFilesAreTrimmedAndFoundUnderTheSharedFolder) {
  TempDir d;
  d.write("a.geojson", "{}");
  const auto f = om::chart_files(" a.geojson , /abs/b.000,, missing.geojson", d.path.string());
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0], (d.path / "a.geojson").string());
  EXPECT_EQ(f[1], "/abs/b.000");
  EXPECT_EQ(f[2], "missing.geojson");  // nowhere: left as given (loading names it)
  EXPECT_EQ(om::chart_files("a.geojson", "")[0], "a.geojson");
}

TEST(ObstacleNode, StampCoversTheS57Updates) {
  TempDir d;
  const std::string cell = d.write("c.000", "x");
  const std::string before = om::chart_stamp({cell});
  EXPECT_FALSE(before.empty());
  d.write("c.001", "u");
  EXPECT_NE(om::chart_stamp({cell}), before);
  EXPECT_EQ(om::chart_stamp({(d.path / "none.000").string()}), "");
}

TEST(ObstacleNode, RegionIsPublishedAroundTheOwnShipWithRisingVersions) {
  const om::NodeParams p = declared({"chart.shapes=point 0 0; point 5000 0; point 30000 0", "region.half_size=10000",
                                     "region.republish_distance=2000"});
  EXPECT_EQ(p.chart_name(), " + inline shapes");
  om::FixedFeed feed(p, p.frame(), {});
  EXPECT_FALSE(feed.at_start());  // a region needs the own position
  const auto first = feed.own_at({0, 0});
  ASSERT_TRUE(first);
  EXPECT_EQ(first->version, 1u);
  EXPECT_EQ(first->obstacles.points.size(), 2u);  // 30 km away: outside
  EXPECT_FALSE(feed.own_at({1000, 0}));           // within the republish circle
  const auto moved = feed.own_at({25000, 0});
  ASSERT_TRUE(moved);
  EXPECT_EQ(moved->version, 2u);
  bool changed = true;
  EXPECT_FALSE(feed.reload_if_changed(&changed));  // no files: never changes
  EXPECT_FALSE(changed);
  const om::BoxNE b = om::chart_bounds(feed.chart());
  EXPECT_DOUBLE_EQ(b.min_x, 0);
  EXPECT_DOUBLE_EQ(b.max_x, 30000);
}

TEST(ObstacleNode, AChangedFileIsReloadedAndABadOneKeepsThePreviousChart) {
  TempDir d;
  const std::string f = d.write("land.geojson", kSquare);
  const om::NodeParams p = declared({"region.half_size=0"});
  om::FixedFeed feed(p, p.frame(), {f});
  ASSERT_TRUE(feed.at_start());  // the whole chart at once
  const std::size_t polygons = feed.chart().polygons.size();
  EXPECT_GT(polygons, 0u);
  bool changed = true;
  EXPECT_FALSE(feed.reload_if_changed(&changed));
  EXPECT_FALSE(changed);
  std::ofstream(f) << "{";  // truncated
  fs::last_write_time(f, fs::last_write_time(f) + std::chrono::seconds(2));
  EXPECT_THROW(feed.reload_if_changed(&changed), std::exception);
  EXPECT_EQ(feed.chart().polygons.size(), polygons);
  EXPECT_FALSE(feed.reload_if_changed(&changed));  // the failed change is not tried again
  std::ofstream(f) << kSquare;
  fs::last_write_time(f, fs::last_write_time(f) + std::chrono::seconds(4));
  const auto part = feed.reload_if_changed(&changed);
  EXPECT_TRUE(changed);
  ASSERT_TRUE(part);
  EXPECT_EQ(part->version, 2u);
}

TEST(ObstacleNode, OriginMismatchIsToldOnce) {
  const om::NodeParams p = declared({"chart.origin_lat=38.95", "chart.origin_lon=-76.45", "nav.origin_tolerance=100"});
  om::OriginCheck check(p.frame(), p.origin_tolerance);
  const auto o = p.frame().origin();
  EXPECT_FALSE(check.check(0, 0, o.lat, o.lon));
  EXPECT_FALSE(check.check(0, 0, 0, 0));            // no lat/lon
  EXPECT_FALSE(check.check(0, 0, std::nan(""), o.lon));
  const auto off = check.check(500, 0, o.lat, o.lon);
  ASSERT_TRUE(off);
  EXPECT_NEAR(*off, 500, 1e-6);
  EXPECT_FALSE(check.check(500, 0, o.lat, o.lon));  // once
}

TEST(ObstacleNode, SilenceIsToldOncePerChangeAndTheEmptiedListOnce) {
  using Feed = om::MovingObstacleFeed::Feed;
  om::AgingParams a;
  om::TracksHealth h(a);
  om::MovingObstacleFeed::Output out;
  out.feed = Feed::kFresh;
  out.obstacles.resize(2);
  EXPECT_TRUE(h.update(out, true).empty());
  out.feed = Feed::kSilent;
  out.silence = 6.2;
  auto n = h.update(out, true);
  ASSERT_EQ(n.size(), 1u);
  EXPECT_EQ(n[0].counter, "tracks_timeout");
  EXPECT_EQ(n[0].log, "no tracks from situational_awareness for 6 s (tracks.timeout = 5 s): predicting the last 2 "
                      "obstacles forward until tracks.max_age = 60 s");
  EXPECT_EQ(*n[0].problem, "no tracks from situational_awareness for 6 s, predicting the last obstacles forward");
  EXPECT_TRUE(h.update(out, true).empty());
  out.obstacles.clear();
  out.aged_out = {3, 4};
  n = h.update(out, true);
  ASSERT_EQ(n.size(), 4u);
  EXPECT_EQ(n[0].counter, "tracks_aged_out");
  EXPECT_EQ(n[0].count, 2u);
  EXPECT_EQ(n[1].log, "track 3 dropped: no track list for more than tracks.max_age = 60 s");
  EXPECT_EQ(n[3].counter, "moving_emptied");
  out.aged_out.clear();
  EXPECT_TRUE(h.update(out, true).empty());
  out.feed = Feed::kFresh;
  n = h.update(out, true);
  ASSERT_EQ(n.size(), 1u);
  EXPECT_EQ(*n[0].problem, "");  // cleared
  om::TracksHealth never(a);
  out.feed = Feed::kSilent;
  EXPECT_EQ(*never.update(out, false)[0].problem, "no tracks from situational_awareness for 6 s since start");
}

}  // namespace
