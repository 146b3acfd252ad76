#include "mpgc/obstacle_manager/node.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "mpgc/geo/angles.hpp"
#include "mpgc/runtime/params.hpp"
#include "mpgc/text/list.hpp"

namespace mpgc::obstacle_manager {

void NodeParams::validate() const {
  region.validate();
  domain.validate();
  aging.validate();
}

geo::LocalNed NodeParams::frame() const { return geo::LocalNed({geo::deg2rad(origin_lat), geo::deg2rad(origin_lon)}); }

std::string NodeParams::chart_name() const { return files + (shapes.empty() ? "" : " + inline shapes"); }

void declare(rt::ParamSet& ps, NodeParams& p) {
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
  ps.add("moving.stopped_speed", &p.domain.stopped_speed, 0.5, "m/s", 0.0, 5.0,
         "a track slower than this whose speed is within moving.stopped_sigmas velocity sigmas of 0 is published "
         "stopped (a ship at rest: its velocity is noise, which eq. 3 would carry over the plan's horizon)");
  ps.add("moving.stopped_sigmas", &p.domain.stopped_sigmas, 2.0, "-", 0.0, 10.0,
         "see moving.stopped_speed; the sigma is sqrt(var_vx + var_vy) of the track's covariance");
  ps.add("moving.tentative", &p.domain.tentative, false, "also pass on tentative tracks");
  ps.add("tracks.max_age", &p.aging.max_age, 60.0, "s", 0.1, 3600.0,
         "drop the last list's obstacles when situational_awareness has been silent this long (while it "
         "speaks, its tracker decides a track's life)");
  ps.add("tracks.timeout", &p.aging.timeout, 5.0, "s", 0.1, 3600.0,
         "no sa/tracks for this long: health degraded, the last obstacles are predicted on until tracks.max_age");
  ps.add("tracks.speed_std", &p.aging.speed_std, 1.0, "m/s", 0.0, 50.0,
         "velocity uncertainty of an unobserved target: position_std^2 grows by (speed_std * time since the list)^2");
  ps.add("tracks.radius_sigmas", &p.aging.radius_sigmas, 2.0, "-", 0.0, 10.0,
         "the domain radius grows by this many times the growth of position_std");
  ps.add("nav.origin_tolerance", &p.origin_tolerance, 100.0, "m", 0.0, 1e6,
         "warn when NavState x,y and lat/lon disagree by more than this through chart.origin");
}

std::vector<std::string> chart_files(const std::string& list, const std::string& shared_dir) {
  std::vector<std::string> out;
  for (std::string f : text::split_list(list)) {
    struct stat st {};
    if (f[0] != '/' && ::stat(f.c_str(), &st) != 0 && !shared_dir.empty()) {
      const std::string alt = shared_dir + "/" + f;
      if (::stat(alt.c_str(), &st) == 0) f = alt;
    }
    out.push_back(f);
  }
  return out;
}

std::string chart_stamp(const std::vector<std::string>& files) {
  std::string s;
  auto stamp = [&s](const struct stat& st) {
    s += std::to_string(st.st_mtim.tv_sec) + "." + std::to_string(st.st_mtim.tv_nsec) + ";";
  };
  for (const auto& f : files) {
    struct stat st {};
    if (::stat(f.c_str(), &st) == 0) stamp(st);
    if (f.size() > 4 && f.compare(f.size() - 4, 4, ".000") == 0)
      for (int k = 1; k < 1000; ++k) {
        char ext[8];
        std::snprintf(ext, sizeof ext, ".%03d", k);
        const std::string u = f.substr(0, f.size() - 4) + ext;
        if (::stat(u.c_str(), &st) != 0) break;
        stamp(st);
      }
  }
  return s;
}

ObstacleSet load_chart(const NodeParams& p, const geo::LocalNed& frame, const std::vector<std::string>& files) {
  ChartBuilder b(frame, p.chart);
  for (const auto& f : files) b.load_file(f);
  add_shapes(b, p.shapes);
  return b.take();
}

BoxNE chart_bounds(const ObstacleSet& s) {
  BoxNE b = FixedObstacleMap({}, s.polygons).bounds();
  for (const auto& q : s.points)
    b = {std::min(b.min_x, q.x), std::min(b.min_y, q.y), std::max(b.max_x, q.x), std::max(b.max_y, q.y)};
  return b;
}

FixedFeed::FixedFeed(const NodeParams& p, const geo::LocalNed& frame, std::vector<std::string> files)
    : p_(p), frame_(frame), files_(std::move(files)), stamp_(chart_stamp(files_)), region_(p.region) {
  set_chart(load_chart(p_, frame_, files_));
}

void FixedFeed::set_chart(ObstacleSet s) {
  chart_ = std::move(s);
  region_.chart_changed();
}

FixedFeed::Part FixedFeed::publish(geom::Vec2 centre) {
  Part part;
  part.box = region_.publish(centre);
  part.obstacles = region_.whole_chart() ? chart_ : crop(chart_, part.box);
  part.version = ++version_;
  return part;
}

std::optional<FixedFeed::Part> FixedFeed::own_at(geom::Vec2 own) {
  own_ = own;
  if (!region_.needs_update(own)) return std::nullopt;
  return publish(own);
}

std::optional<FixedFeed::Part> FixedFeed::goal_at(std::optional<geom::Vec2> goal) {
  region_.set_goal(goal);
  if (!own_ || !region_.needs_update(*own_)) return std::nullopt;
  return publish(*own_);
}

std::optional<FixedFeed::Part> FixedFeed::at_start() {
  if (!region_.whole_chart()) return std::nullopt;
  return publish({0, 0});
}

std::optional<FixedFeed::Part> FixedFeed::reload_if_changed(bool* changed) {
  const std::string now = chart_stamp(files_);
  *changed = now != stamp_;
  if (!*changed) return std::nullopt;
  stamp_ = now;
  set_chart(load_chart(p_, frame_, files_));
  if (own_) return publish(*own_);
  return at_start();
}

std::optional<double> OriginCheck::check(double x, double y, double lat, double lon) {
  if (warned_ || !std::isfinite(lat) || !std::isfinite(lon) || (lat == 0.0 && lon == 0.0)) return std::nullopt;
  const auto q = frame_.to_ned({lat, lon});
  const double off = std::hypot(q.x - x, q.y - y);
  if (off <= tolerance_) return std::nullopt;
  warned_ = true;
  return off;
}

std::vector<TracksHealth::Note> TracksHealth::update(const MovingObstacleFeed::Output& out, bool has_list) {
  using Feed = MovingObstacleFeed::Feed;
  std::vector<Note> notes;
  if (!out.aged_out.empty()) {
    notes.push_back({false, "", "tracks_aged_out", out.aged_out.size(), std::nullopt});
    for (const uint32_t id : out.aged_out)
      notes.push_back({false, fmt::format("track {} dropped: no track list for more than tracks.max_age = {} s", id, a_.max_age),
                       "", 1, std::nullopt});
  }
  // Silence: explicit, once per change. The last obstacles go on (their uncertainty growing)
  // until each is tracks.max_age old; then the list is empty and only health says why.
  if (out.feed == Feed::kSilent && last_ != Feed::kSilent) {
    const std::string d = fmt::format("no tracks from situational_awareness for {:.0f} s", out.silence);
    if (has_list)
      notes.push_back({true,
                       fmt::format("{} (tracks.timeout = {} s): predicting the last {} obstacles forward until "
                                   "tracks.max_age = {} s",
                                   d, a_.timeout, out.obstacles.size(), a_.max_age),
                       "tracks_timeout", 1, d + ", predicting the last obstacles forward"});
    else
      notes.push_back({true, fmt::format("{} since start (tracks.timeout = {} s): publishing no moving obstacles", d, a_.timeout),
                       "tracks_timeout", 1, d + " since start"});
  }
  if (out.feed == Feed::kSilent && out.obstacles.empty() && has_list && !emptied_) {
    emptied_ = true;
    const std::string d = fmt::format(
        "no tracks from situational_awareness for {:.0f} s: every track aged out, publishing none", out.silence);
    notes.push_back({true, d, "moving_emptied", 1, d});
  }
  if (out.feed != Feed::kSilent && last_ == Feed::kSilent) {
    emptied_ = false;
    notes.push_back({false, "tracks from situational_awareness again", "", 1, ""});
  }
  last_ = out.feed;
  return notes;
}

}  // namespace mpgc::obstacle_manager
