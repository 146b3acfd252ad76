// mpgc_obstacle_manager: chart(s) -> obstacles/fixed (latched, the region around the own ship and goal),
// sa/tracks -> obstacles/moving (every cycle). Seed 000 §2 "obstacle management", §4.2.
// Its logic is mpgc/obstacle_manager/node.hpp and manager.hpp; this is its wiring.
#include <cstdlib>
#include <memory>

#include "mpgc/geo/angles.hpp"
#include "mpgc/msg/nav.hpp"
#include "mpgc/msg/obstacles.hpp"
#include "mpgc/msg/plan.hpp"
#include "mpgc/msg/tracks.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/obstacle_manager/msg_convert.hpp"
#include "mpgc/obstacle_manager/node.hpp"
#include "mpgc/obstacle_manager/validate.hpp"
#include "mpgc/runtime/component.hpp"
#include "mpgc/topics.hpp"

namespace om = mpgc::obstacle_manager;
namespace msg = mpgc::msg;

int main(int argc, char** argv) {
  om::NodeParams p;
  mpgc::rt::ParamSet ps;
  om::declare(ps, p);
  return mpgc::rt::run_component("obstacle_manager", argc, argv, ps, [&p](mpgc::rt::Component& comp) {
    // Callbacks outlive this function: they capture the component by pointer, the rest by value
    // or through the shared state.
    mpgc::rt::Component* c = &comp;
    p.validate();
    const mpgc::geo::LocalNed frame = p.frame();
    const char* shared = std::getenv("MPGC_SHARED_DATA");

    struct State {
      om::FixedFeed fixed;
      om::OriginCheck origin;
      om::MovingObstacleFeed feed;
      om::TracksHealth health;
    };
    auto st = std::make_shared<State>(State{om::FixedFeed(p, frame, om::chart_files(p.files, shared ? shared : "")),
                                            om::OriginCheck(frame, p.origin_tolerance),
                                            om::MovingObstacleFeed(p.domain, p.aging), om::TracksHealth(p.aging)});
    c->log().info("chart '{}': {} points, {} rings, {} features", p.files, st->fixed.chart().points.size(),
                 st->fixed.chart().polygons.size(), st->fixed.chart().features.size());

    auto* fixed_out = &c->publisher<msg::FixedObstacles>(mpgc::topics::kFixedObstacles, mpgc::dds::QosProfile::latched());
    auto* moving_out = &c->publisher<msg::MovingObstacles>(mpgc::topics::kMovingObstacles, mpgc::dds::QosProfile::state());

    auto publish_fixed = [c, &p, fixed_out](const om::FixedFeed::Part& part) {
      const om::BoxNE& box = part.box;
      msg::FixedObstacles m;
      m.header = c->header();
      m.version = part.version;
      m.chart = p.chart_name();
      m.origin_lat = mpgc::geo::deg2rad(p.origin_lat);
      m.origin_lon = mpgc::geo::deg2rad(p.origin_lon);
      m.region_min_x = box.min_x;
      m.region_min_y = box.min_y;
      m.region_max_x = box.max_x;
      m.region_max_y = box.max_y;
      m.point_spacing = p.chart.spacing;
      m.points = om::points_to_msg(part.obstacles.points);
      m.polygons.reserve(part.obstacles.polygons.size());
      for (const auto& g : part.obstacles.polygons) m.polygons.push_back({g.feature_id, om::points_to_msg(g.ring)});
      fixed_out->write(m);
      c->count("fixed_published");
      c->log().info("obstacles/fixed v{}: {} points, {} polygons in [{:.0f}, {:.0f}] x [{:.0f}, {:.0f}] m", m.version,
                   m.points.size(), m.polygons.size(), box.min_x, box.max_x, box.min_y, box.max_y);
    };

    c->subscribe<msg::NavState>(
        mpgc::topics::kOwnState, mpgc::dds::QosProfile::state(),
        [c, st, publish_fixed](const msg::NavState& s) {
          if (const auto off = st->origin.check(s.x, s.y, s.lat, s.lon)) {
            c->count("origin_mismatch");
            c->log().warn("nav/own_state x,y differs by {:.0f} m from its lat/lon through chart.origin: is "
                         "chart.origin_lat/lon the run's origin?", *off);
          }
          if (const auto part = st->fixed.own_at({s.x, s.y})) publish_fixed(*part);
        },
        om::check_nav);

    // The region covers the goal too: the planner counts water beyond it as unknown.
    c->subscribe<msg::MissionGoal>(
        mpgc::topics::kGoal, mpgc::dds::QosProfile::latched(),
        [st, publish_fixed](const msg::MissionGoal& g) {
          if (const auto part = st->fixed.goal_at(mpgc::geom::Vec2{g.x, g.y})) publish_fixed(*part);
        },
        [&p](const msg::MissionGoal& g) { return om::check_goal(g, p.domain.max_range); });

    c->subscribe<msg::TrackList>(mpgc::topics::kTracks, mpgc::dds::QosProfile::state(), [c, st](const msg::TrackList& l) {
      std::vector<om::TargetState> targets;
      targets.reserve(l.tracks.size());
      for (const auto& t : l.tracks) targets.push_back(om::target_state(t));
      const auto r = st->feed.receive(l.header.stamp_ns, targets, c->now_ns());
      if (r.deleted > 0) c->count("tracks_skipped_deleted", r.deleted);
      if (r.tentative > 0) c->count("tracks_skipped_tentative", r.tentative);
      for (const auto& why : r.rejected) c->reject(mpgc::topics::kTracks, why);
    });

    if (const auto part = st->fixed.at_start()) publish_fixed(*part);

    c->every(p.moving_period, [c, st, moving_out] {
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
      for (const auto& n : st->health.update(out, st->feed.has_list())) {
        if (!n.counter.empty()) c->count(n.counter, n.count);
        if (!n.log.empty()) {
          if (n.warn) c->log().warn("{}", n.log);
          else c->log().info("{}", n.log);
        }
        if (n.problem) c->set_problem("tracks", *n.problem);
      }
      moving_out->write(m);
    });

    if (p.watch_period > 0.0)
      c->every(p.watch_period, [c, st, publish_fixed] {
        try {
          bool changed = false;
          const auto part = st->fixed.reload_if_changed(&changed);
          if (!changed) return;
          c->count("chart_reloaded");
          c->set_problem("chart", "");
          c->log().info("chart changed on disk: reloaded, {} points", st->fixed.chart().points.size());
          if (part) publish_fixed(*part);
        } catch (const std::exception& e) {
          c->reject("chart", std::string("reload failed, keeping the previous chart: ") + e.what());
          c->set_problem("chart", std::string("chart reload failed: ") + e.what());
        }
      });
  });
}
