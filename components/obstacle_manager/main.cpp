// mpgc_obstacle_manager: chart(s) -> obstacles/fixed (latched, the region around the own ship),
// sa/tracks -> obstacles/moving (every cycle). Seed 000 §2 "obstacle management", §4.2.
#include <sys/stat.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/obstacle_manager/msg_convert.hpp"
#include "mpgc/obstacle_manager/validate.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace om = mpgc::obstacle_manager;
namespace msg = mpgc::msg;
using mpgc::geo::deg2rad;

namespace {

struct Params {
  std::string files;         // chart files, comma separated (.000 S-57 cells, .geojson)
  std::string shapes;        // inline NED shapes (see om::add_shapes)
  double origin_lat = 0;     // [deg] NED origin, must be the run's origin
  double origin_lon = 0;     // [deg]
  double watch_period = 5;   // [s] chart file change check; 0 = never
  double moving_period = 0.5;  // [s] obstacles/moving period
  double origin_tolerance = 100;  // [m] NavState x,y vs lat/lon through our origin
  om::ChartParams chart;
  om::RegionParams region;
  om::DomainParams domain;
  om::AgingParams aging;
};

void declare(mpgc::rt::ParamSet& ps, Params& p) {
  ps.add("chart.files", &p.files, "", "chart files, comma separated: S-57 cells (*.000, updates applied) and GeoJSON; "
                                      "relative paths are tried against $MPGC_SHARED_DATA too");
  ps.add("chart.shapes", &p.shapes, "", "inline NED shapes: 'circle N E R; polygon N E N E ...; line N E ...; point N E'");
  ps.add("chart.origin_lat", &p.origin_lat, 0.0, "deg", -90.0, 90.0, "latitude of the NED origin (the run's origin)");
  ps.add("chart.origin_lon", &p.origin_lon, 0.0, "deg", -180.0, 180.0, "longitude of the NED origin");
  ps.add("chart.spacing", &p.chart.spacing, 20.0, "m", 0.5, 10000.0, "densification spacing of boundary points");
  ps.add("chart.draught", &p.chart.draught, 5.0, "m", 0.0, 50.0, "depth areas shallower than this are obstacles");
  ps.add("chart.depth_areas", &p.chart.depth_areas, true, "treat shallow depth areas (DEPARE) as obstacles");
  ps.add("chart.watch_period", &p.watch_period, 5.0, "s", 0.0, 3600.0, "check chart files for changes; 0 = never");
  ps.add("region.half_size", &p.region.half_size, 10000.0, "m", 0.0, 1e6,
         "half side of the published square around the own ship; 0 = whole chart at once");
  ps.add("region.republish_distance", &p.region.republish_distance, 2000.0, "m", 1.0, 1e6,
         "republish when the own ship moved this far from the last centre");
  ps.add("moving.period", &p.moving_period, 0.5, "s", 0.01, 60.0, "obstacles/moving publication period");
  ps.add("moving.min_radius", &p.domain.min_radius, 50.0, "m", 0.0, 1e4, "ship-domain radius when the length is unknown");
  ps.add("moving.lengths", &p.domain.lengths, 2.0, "-", 0.0, 100.0, "ship-domain radius in target lengths");
  ps.add("moving.max_speed", &p.domain.max_speed, 40.0, "m/s", 1.0, 200.0, "faster tracks are rejected");
  ps.add("moving.tentative", &p.domain.tentative, false, "also pass on tentative tracks");
  ps.add("tracks.max_age", &p.aging.max_age, 60.0, "s", 0.1, 3600.0,
         "drop a track whose last measurement is older (situational_awareness deletes at tracker.delete_after, "
         "also 60 s by default)");
  ps.add("tracks.timeout", &p.aging.timeout, 5.0, "s", 0.1, 3600.0,
         "no sa/tracks for this long: health degraded, the last obstacles are predicted on until tracks.max_age");
  ps.add("tracks.speed_std", &p.aging.speed_std, 1.0, "m/s", 0.0, 50.0,
         "velocity uncertainty of an unobserved target: position_std^2 grows by (speed_std * time since the list)^2");
  ps.add("tracks.radius_sigmas", &p.aging.radius_sigmas, 2.0, "-", 0.0, 10.0,
         "the domain radius grows by this many times the growth of position_std");
  ps.add("nav.origin_tolerance", &p.origin_tolerance, 100.0, "m", 0.0, 1e6,
         "warn when NavState x,y and lat/lon disagree by more than this through chart.origin");
}

std::vector<std::string> split_files(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string f;
  while (std::getline(ss, f, ',')) {
    const auto a = f.find_first_not_of(" \t"), b = f.find_last_not_of(" \t");
    if (a == std::string::npos) continue;
    f = f.substr(a, b - a + 1);
    struct stat st {};
    if (f[0] != '/' && ::stat(f.c_str(), &st) != 0)
      if (const char* d = std::getenv("MPGC_SHARED_DATA")) {
        const std::string alt = std::string(d) + "/" + f;
        if (::stat(alt.c_str(), &st) == 0) f = alt;
      }
    out.push_back(f);
  }
  return out;
}

// Modification times of the chart files and their S-57 updates (.001 ... beside a .000).
std::string chart_stamp(const std::vector<std::string>& files) {
  std::string s;
  for (const auto& f : files) {
    struct stat st {};
    if (::stat(f.c_str(), &st) == 0) s += std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ";";
    if (f.size() > 4 && f.compare(f.size() - 4, 4, ".000") == 0)
      for (int k = 1; k < 1000; ++k) {
        char ext[8];
        std::snprintf(ext, sizeof ext, ".%03d", k);
        const std::string u = f.substr(0, f.size() - 4) + ext;
        if (::stat(u.c_str(), &st) != 0) break;
        s += std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ";";
      }
  }
  return s;
}

om::ObstacleSet load_chart(const Params& p, const mpgc::geo::LocalNed& frame, const std::vector<std::string>& files) {
  om::ChartBuilder b(frame, p.chart);
  for (const auto& f : files) b.load_file(f);
  om::add_shapes(b, p.shapes);
  return b.take();
}

}  // namespace

int main(int argc, char** argv) {
  Params p;
  mpgc::rt::ParamSet ps;
  declare(ps, p);
  return mpgc::rt::run_component("obstacle_manager", argc, argv, ps, [&p](mpgc::rt::Component& comp) {
    // Callbacks outlive this function: they capture the component by pointer, the rest by value
    // or through the shared state.
    mpgc::rt::Component* c = &comp;
    p.region.validate();
    p.domain.validate();
    p.aging.validate();
    const mpgc::geo::LocalNed frame({deg2rad(p.origin_lat), deg2rad(p.origin_lon)});
    const auto files = split_files(p.files);

    struct State {
      om::ObstacleSet chart;
      om::BoxNE bounds{0, 0, 0, 0};
      std::string stamp;
      om::RegionPolicy region;
      std::optional<mpgc::geom::Vec2> own;
      om::MovingObstacleFeed feed;
      uint32_t version = 0;
      bool origin_warned = false;
      om::MovingObstacleFeed::Feed last_feed = om::MovingObstacleFeed::Feed::kWaiting;
      bool emptied = false;  // silent and every track aged out
    };
    auto st = std::make_shared<State>(State{{}, {}, chart_stamp(files), om::RegionPolicy(p.region), {},
                                            om::MovingObstacleFeed(p.domain, p.aging), 0, false, {}, false});
    // Health is the sum of independent problems ("chart", "tracks"); OK when there are none.
    auto set_problem = [c](const std::string& what, const std::string& detail) { c->set_problem(what, detail); };
    auto set_chart = [st](om::ObstacleSet s) {
      st->chart = std::move(s);
      st->bounds = om::FixedObstacleMap({}, st->chart.polygons).bounds();
      for (const auto& q : st->chart.points)
        st->bounds = {std::min(st->bounds.min_x, q.x), std::min(st->bounds.min_y, q.y), std::max(st->bounds.max_x, q.x),
                      std::max(st->bounds.max_y, q.y)};
      st->region.chart_changed();
    };
    set_chart(load_chart(p, frame, files));
    c->log().info("chart '{}': {} points, {} rings, {} features", p.files, st->chart.points.size(),
                 st->chart.polygons.size(), st->chart.features.size());

    auto* fixed_out = &c->publisher<msg::FixedObstacles>(mpgc::topics::kFixedObstacles, mpgc::dds::QosProfile::latched());
    auto* moving_out = &c->publisher<msg::MovingObstacles>(mpgc::topics::kMovingObstacles, mpgc::dds::QosProfile::state());

    auto publish_fixed = [c, &p, st, fixed_out](mpgc::geom::Vec2 centre) {
      const om::BoxNE box = st->region.publish(centre, st->bounds);
      const om::ObstacleSet part = st->region.whole_chart() ? st->chart : om::crop(st->chart, box);
      msg::FixedObstacles m;
      m.header = c->header();
      m.version = ++st->version;
      m.chart = p.files + (p.shapes.empty() ? "" : " + inline shapes");
      m.origin_lat = deg2rad(p.origin_lat);
      m.origin_lon = deg2rad(p.origin_lon);
      m.region_min_x = box.min_x;
      m.region_min_y = box.min_y;
      m.region_max_x = box.max_x;
      m.region_max_y = box.max_y;
      m.point_spacing = p.chart.spacing;
      m.points = om::points_to_msg(part.points);
      m.polygons.reserve(part.polygons.size());
      for (const auto& g : part.polygons) m.polygons.push_back({g.feature_id, om::points_to_msg(g.ring)});
      fixed_out->write(m);
      c->count("fixed_published");
      c->log().info("obstacles/fixed v{}: {} points, {} polygons in [{:.0f}, {:.0f}] x [{:.0f}, {:.0f}] m", m.version,
                   m.points.size(), m.polygons.size(), box.min_x, box.max_x, box.min_y, box.max_y);
    };

    c->subscribe<msg::NavState>(
        mpgc::topics::kOwnState, mpgc::dds::QosProfile::state(),
        [c, &p, st, frame, publish_fixed](const msg::NavState& s) {
          st->own = mpgc::geom::Vec2{s.x, s.y};
          if (!st->origin_warned && std::isfinite(s.lat) && std::isfinite(s.lon) && (s.lat != 0.0 || s.lon != 0.0)) {
            const auto q = frame.to_ned({s.lat, s.lon});
            const double off = std::hypot(q.x - s.x, q.y - s.y);
            if (off > p.origin_tolerance) {
              c->count("origin_mismatch");
              c->log().warn("nav/own_state x,y differs by {:.0f} m from its lat/lon through chart.origin: is "
                           "chart.origin_lat/lon the run's origin?", off);
              st->origin_warned = true;
            }
          }
          if (st->region.needs_update(*st->own)) publish_fixed(*st->own);
        },
        om::check_nav);

    c->subscribe<msg::TrackList>(mpgc::topics::kTracks, mpgc::dds::QosProfile::state(), [c, st](const msg::TrackList& l) {
      std::vector<om::TargetState> targets;
      targets.reserve(l.tracks.size());
      for (const auto& t : l.tracks) targets.push_back(om::target_state(t));
      const auto r = st->feed.receive(l.header.stamp_ns, targets, c->now_ns());
      if (r.deleted > 0) c->count("tracks_skipped_deleted", r.deleted);
      if (r.tentative > 0) c->count("tracks_skipped_tentative", r.tentative);
      for (const auto& why : r.rejected) c->reject(mpgc::topics::kTracks, why);
    });

    // The whole chart needs no own position: publish it at once for planners that start first.
    if (st->region.whole_chart()) publish_fixed({0, 0});

    c->every(p.moving_period, [c, &p, st, moving_out, set_problem] {
      using Feed = om::MovingObstacleFeed::Feed;
      msg::MovingObstacles m;
      m.header = c->header();
      const auto out = st->feed.at(m.header.stamp_ns);
      m.t_valid_ns = out.t_valid_ns;
      for (const auto& o : out.obstacles) {
        msg::MovingObstacle mo;
        mo.id = o.id;
        mo.mmsi = o.mmsi;
        mo.x = o.x;
        mo.y = o.y;
        mo.vx = o.vx;
        mo.vy = o.vy;
        mo.radius = o.radius;
        mo.position_std = o.position_std;
        m.obstacles.push_back(mo);
      }
      if (!out.aged_out.empty()) {
        c->count("tracks_aged_out", out.aged_out.size());
        for (const uint32_t id : out.aged_out)
          c->log().info("track {} dropped: last measured more than tracks.max_age = {} s ago", id, p.aging.max_age);
      }
      // Silence: explicit, once per change. The last obstacles go on (their uncertainty growing)
      // until each is tracks.max_age old; then the list is empty and only health says why.
      if (out.feed == Feed::kSilent && st->last_feed != Feed::kSilent) {
        c->count("tracks_timeout");
        const std::string d = fmt::format("no tracks from situational_awareness for {:.0f} s", out.silence);
        if (st->feed.has_list()) {
          c->log().warn("{} (tracks.timeout = {} s): predicting the last {} obstacles forward until tracks.max_age = {} s",
                        d, p.aging.timeout, m.obstacles.size(), p.aging.max_age);
          set_problem("tracks", d + ", predicting the last obstacles forward");
        } else {
          c->log().warn("{} since start (tracks.timeout = {} s): publishing no moving obstacles", d, p.aging.timeout);
          set_problem("tracks", d + " since start");
        }
      }
      if (out.feed == Feed::kSilent && m.obstacles.empty() && st->feed.has_list() && !st->emptied) {
        st->emptied = true;
        c->count("moving_emptied");
        const std::string d =
            fmt::format("no tracks from situational_awareness for {:.0f} s: every track aged out, publishing none",
                        out.silence);
        c->log().warn("{}", d);
        set_problem("tracks", d);
      }
      if (out.feed != Feed::kSilent && st->last_feed == Feed::kSilent) {
        c->log().info("tracks from situational_awareness again");
        st->emptied = false;
        set_problem("tracks", "");
      }
      st->last_feed = out.feed;
      moving_out->write(m);
    });

    if (p.watch_period > 0.0)
      c->every(p.watch_period, [c, &p, st, frame, files, set_chart, publish_fixed, set_problem] {
        const std::string now = chart_stamp(files);
        if (now == st->stamp) return;
        st->stamp = now;
        try {
          set_chart(load_chart(p, frame, files));
          c->count("chart_reloaded");
          set_problem("chart", "");
          c->log().info("chart changed on disk: reloaded, {} points", st->chart.points.size());
          if (st->own) publish_fixed(*st->own);
          else if (st->region.whole_chart()) publish_fixed({0, 0});
        } catch (const std::exception& e) {
          c->reject("chart", std::string("reload failed, keeping the previous chart: ") + e.what());
          set_problem("chart", std::string("chart reload failed: ") + e.what());
        }
      });
  });
}
