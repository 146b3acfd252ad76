// obstacle_manager's input topics: nav/own_state through its validator into the region policy
// (needs_update, publish, crop of a small chart: what obstacles/fixed carries), and sa/tracks
// (any size, any status and id, NaN covariances) through target_state, check_target and
// to_moving_obstacle (what obstacles/moving carries). Validators in
// mpgc/obstacle_manager/validate.hpp. check_target returns reasons, so every exception is a finding.
#include "msg.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/obstacle_manager/fixed_obstacle_map.hpp"
#include "mpgc/obstacle_manager/manager.hpp"
#include "mpgc/obstacle_manager/validate.hpp"

namespace om = mpgc::obstacle_manager;
namespace msg = mpgc::msg;
namespace fz = mpgc::fuzz;

namespace {
const om::ObstacleSet& chart() {
  static const om::ObstacleSet set = [] {
    om::ChartBuilder b(mpgc::geo::LocalNed({0.6771, -1.3317}), om::ChartParams{});
    om::add_shapes(b, "circle 1000 500 200; polygon 3000 0 3000 800 3600 400; line 0 -150 20000 -150; point 5 5");
    return b.take();
  }();
  return set;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fz::Reader r(data, size);
  om::RegionParams rp;
  rp.half_size = r.flag() ? 0.0 : 10000.0;
  om::RegionPolicy region(rp);
  om::DomainParams dp;
  dp.tentative = r.flag();
  const om::ObstacleSet& set = chart();
  for (int i = 0; i < 16 && !r.empty(); ++i) {
    if (r.flag()) {
      const msg::NavState s = fz::nav_state(r);
      if (!om::check_nav(s).empty()) continue;
      const mpgc::geom::Vec2 own{s.x, s.y};
      if (r.flag()) {
        const msg::MissionGoal g = fz::goal(r);
        if (om::check_goal(g, dp.max_range).empty()) region.set_goal(mpgc::geom::Vec2{g.x, g.y});
      }
      if (region.needs_update(own)) {
        const om::BoxNE box = region.publish(own);
        if (!region.whole_chart()) (void)om::crop(set, box);
      }
    } else {
      const msg::TrackList l = fz::tracks(r, 6, 20000);
      for (const auto& t : l.tracks) {
        const om::TargetState ts = om::target_state(t);
        if (!om::check_target(ts, dp).empty()) continue;
        (void)om::to_moving_obstacle(ts, dp);
      }
    }
  }
  return 0;
}
