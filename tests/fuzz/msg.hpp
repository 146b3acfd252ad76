// IDL messages built from fuzz bytes (mpgc::fuzz::Reader): every double may be NaN, +-inf, huge
// or a denormal, every sequence empty, one element or huge, every id and enum any value (unknown
// enum values included), stamps near a base time or at the extremes.
#pragma once

#include "fuzz.hpp"
#include "mpgc/msg/control.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/sensors.hpp"
#include "mpgc/msg/tracks.hpp"

namespace mpgc::fuzz {

constexpr int64_t kBaseNs = 1'000'000'000'000LL;  // 1000 s

inline msg::Header header(Reader& r, int64_t base = kBaseNs) { return {r.stamp(base), r.str(8), r.u32()}; }

template <class E>
E any_enum(Reader& r, int known) {
  const uint8_t k = r.byte();
  return static_cast<E>(k < 224 ? k % known : static_cast<int32_t>(r.u32()));
}

inline uint32_t valid_mask(Reader& r) {
  const uint8_t k = r.byte();
  return k < 160 ? 31u : (k < 224 ? (k & 31u) : r.u32());
}

inline msg::NavState nav_state(Reader& r) {
  msg::NavState s;
  s.header = header(r);
  s.x = r.real(-1e5, 1e5);
  s.y = r.real(-1e5, 1e5);
  s.lat = r.real(-1.6, 1.6);
  s.lon = r.real(-3.2, 3.2);
  s.heading = r.real(-7, 7);
  s.cog = r.real(-7, 7);
  s.sog = r.real(-1, 30);
  s.u = r.real(-1, 30);
  s.v = r.real(-5, 5);
  s.r = r.real(-0.1, 0.1);
  s.rudder = r.real(-0.7, 0.7);
  s.propeller_rpm = r.real(-10, 200);
  s.valid_mask = valid_mask(r);
  return s;
}

inline msg::MissionGoal goal(Reader& r) {
  msg::MissionGoal g;
  g.header = header(r);
  g.goal_id = r.id();
  g.x = r.real(-2e4, 2e4);
  g.y = r.real(-2e4, 2e4);
  g.heading = r.real(-7, 7);
  g.heading_tolerance = r.real(-1, 4);
  g.cruise_speed = r.real(-1, 30);
  g.safety_distance = r.real(-10, 3000);
  g.colreg = r.flag();
  return g;
}

inline msg::MovingObstacles moving(Reader& r, size_t typical, size_t huge) {
  msg::MovingObstacles m;
  m.header = header(r);
  m.t_valid_ns = r.stamp(kBaseNs);
  m.obstacles.resize(r.count(typical, huge));
  for (auto& o : m.obstacles) {
    o.id = r.id();
    o.mmsi = r.id();
    o.x = r.real(-2e4, 2e4);
    o.y = r.real(-2e4, 2e4);
    o.vx = r.real(-15, 15);
    o.vy = r.real(-15, 15);
    o.radius = r.real(-10, 1000);
    o.domain_fore = r.real(0, 1000);
    o.domain_aft = r.real(0, 1000);
    o.domain_side = r.real(0, 1000);
    o.position_std = r.real(-1, 100);
  }
  return m;
}

inline msg::PointNE point(Reader& r, double span) { return {r.real(-span, span), r.real(-span, span)}; }

inline msg::FixedObstacles fixed(Reader& r, size_t typical, size_t huge) {
  msg::FixedObstacles m;
  m.header = header(r);
  m.version = r.id();
  m.chart = r.str(16);
  m.origin_lat = r.real(-1.6, 1.6);
  m.origin_lon = r.real(-3.2, 3.2);
  m.region_min_x = r.real(-2e4, 0);
  m.region_min_y = r.real(-2e4, 0);
  m.region_max_x = r.real(0, 2e4);
  m.region_max_y = r.real(0, 2e4);
  m.point_spacing = r.real(0, 100);
  m.points.resize(r.count(typical, huge));
  for (auto& p : m.points) p = point(r, 2e4);
  m.polygons.resize(r.count(4, huge / 4));
  for (auto& g : m.polygons) {
    g.feature_id = r.id();
    const msg::PointNE c = point(r, 2e4);
    g.ring.resize(r.count(typical, huge));
    for (auto& p : g.ring) {  // mostly near a centre, so that rings are rings
      const msg::PointNE d = point(r, 2000);
      p = {c.x + d.x, c.y + d.y};
    }
  }
  return m;
}

inline msg::Track track(Reader& r) {
  msg::Track t;
  t.id = r.id();
  t.mmsi = r.id();
  t.sources = r.byte();
  t.x = r.real(-2e4, 2e4);
  t.y = r.real(-2e4, 2e4);
  t.vx = r.real(-15, 15);
  t.vy = r.real(-15, 15);
  for (auto& c : t.cov) c = r.real(-10, 1000);
  t.age = r.real(0, 1000);
  t.since_update = r.real(0, 100);
  t.length = r.real(-10, 400);
  t.status = any_enum<msg::TrackStatus>(r, 4);
  return t;
}

inline msg::TrackList tracks(Reader& r, size_t typical, size_t huge) {
  msg::TrackList l;
  l.header = header(r);
  l.tracks.resize(r.count(typical, huge));
  for (auto& t : l.tracks) t = track(r);
  return l;
}

inline msg::AisReport ais(Reader& r) {
  msg::AisReport a;
  a.header = header(r);
  a.mmsi = r.id();
  a.ais_class = any_enum<msg::AisClass>(r, 2);
  a.lat = r.real(1.03, 1.05);
  a.lon = r.real(0.18, 0.20);
  a.cog = r.real(-7, 7);
  a.sog = r.real(-1, 60);
  a.heading = r.real(-7, 7);
  a.rot = r.real(-1, 1);
  a.nav_status = r.byte();
  a.report_time_ns = r.stamp(kBaseNs);
  a.length = r.real(-10, 400);
  a.beam = r.real(-10, 60);
  a.name = r.str(20);
  a.ship_type = static_cast<int16_t>(r.u32());
  return a;
}

inline msg::RadarScan radar(Reader& r, size_t typical, size_t huge) {
  msg::RadarScan s;
  s.header = header(r);
  s.antenna_x = r.real(-2e4, 2e4);
  s.antenna_y = r.real(-2e4, 2e4);
  s.max_range = r.real(-1, 5e4);
  s.contacts.resize(r.count(typical, huge));
  for (auto& c : s.contacts) c = {r.real(-10, 5e4), r.real(-7, 7), r.real(-1, 50), r.real(-0.1, 0.1)};
  return s;
}

inline msg::Path path(Reader& r, size_t typical, size_t huge) {
  msg::Path p;
  p.header = header(r);
  p.plan_id = r.id();
  p.goal_id = r.id();
  p.t0_ns = r.stamp(kBaseNs);
  p.status = any_enum<msg::PlanStatus>(r, 4);
  p.reason = r.str(16);
  p.colreg_compliant = r.flag();
  p.relaxed = r.flag();
  p.waypoints.resize(r.count(typical, huge));
  for (auto& w : p.waypoints) w = {r.real(-2e4, 2e4), r.real(-2e4, 2e4), r.real(0, 5000), r.real(-1, 30)};
  p.cost_total = r.real();
  p.iterations = r.u32();
  p.planning_time = r.real(0, 1);
  p.planner = r.str(8);
  p.effective_ns = r.stamp(kBaseNs);
  return p;
}

inline msg::ActuatorCommand actuators(Reader& r) { return {header(r), r.real(-1, 1), r.real(-50, 250)}; }

}  // namespace mpgc::fuzz
