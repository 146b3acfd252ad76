// opp's input topics: nav/own_state, plan/goal, obstacles/moving and obstacles/fixed, built from
// the fuzz bytes (msg.hpp), through opp's validators (mpgc/opp/validate.hpp) and, for what they
// accept, the library code opp's main then runs: the fixed obstacles' query map (map_from_msg,
// ChartObstacles), the targets' extrapolation, the encounter memory, a short plan (300 RRT*
// iterations, at most 32 targets, no clock: deterministic) and the COLREG assessment of every target.
// Expected rejections: std::invalid_argument (map_from_msg, EncounterMemory::update, colreg).
#include <memory>
#include <optional>

#include "msg.hpp"
#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geo/angles.hpp"
#include "mpgc/obstacle_manager/msg_convert.hpp"
#include "mpgc/opp/chart_obstacles.hpp"
#include "mpgc/opp/encounters.hpp"
#include "mpgc/opp/rrtstar.hpp"
#include "mpgc/opp/validate.hpp"

namespace opp = mpgc::opp;
namespace om = mpgc::obstacle_manager;
namespace msg = mpgc::msg;
namespace fz = mpgc::fuzz;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fz::Reader r(data, size);
  const msg::NavState own = fz::nav_state(r);
  const msg::MissionGoal goal = fz::goal(r);
  const msg::MovingObstacles moving = fz::moving(r, 6, 20000);
  const bool with_fixed = r.flag();

  std::shared_ptr<opp::ChartObstacles> fixed;
  if (with_fixed) {
    const msg::FixedObstacles f = fz::fixed(r, 12, 5000);
    fz::expect<std::invalid_argument>([&] {
      fixed = std::make_shared<opp::ChartObstacles>(std::make_shared<const om::FixedObstacleMap>(om::map_from_msg(f)));
    });
  }
  const bool own_ok = opp::check_nav(own).empty();
  const bool goal_ok = opp::check_goal(goal).empty();
  const bool moving_ok = opp::check_moving(moving).empty();
  if (!own_ok || !goal_ok) return 0;

  const int64_t now_ns = own.header.stamp_ns;
  std::vector<opp::Target> targets;
  if (moving_ok) {
    // The main computes (now - t_valid) in int64: signed overflow for extreme stamps (a finding,
    // README.md); here in double.
    const double dt = (static_cast<double>(now_ns) - static_cast<double>(moving.t_valid_ns)) * 1e-9;
    for (const auto& o : moving.obstacles) targets.push_back({o.id, {o.x + o.vx * dt, o.y + o.vy * dt}, {o.vx, o.vy}});
  }
  const double sog = std::isfinite(own.sog) ? own.sog : 0.0;
  const double cog = std::isfinite(own.cog) ? own.cog : own.heading;
  opp::Problem pb;
  pb.start = {own.x, own.y};
  pb.heading = own.heading;
  pb.speed = goal.cruise_speed > 0 ? goal.cruise_speed : (sog > 0.5 ? sog : 5.0);
  pb.goal.p = {goal.x, goal.y};
  pb.goal.heading = goal.heading;
  pb.goal.heading_tolerance = std::isfinite(goal.heading) ? goal.heading_tolerance : mpgc::geo::kPi;
  const double m = 3000.0;
  pb.bounds = {std::min(pb.start.x, pb.goal.p.x) - m, std::min(pb.start.y, pb.goal.p.y) - m,
               std::max(pb.start.x, pb.goal.p.x) + m, std::max(pb.start.y, pb.goal.p.y) + m};
  pb.fixed = fixed.get();
  // The validator and the encounter memory see every target; the plan (whose cost grows with
  // iterations x targets, bounded by its wall-clock budget in opp) at most 32 of them.
  pb.targets.assign(targets.begin(), targets.begin() + static_cast<std::ptrdiff_t>(std::min<size_t>(targets.size(), 32)));
  pb.colreg = goal.colreg;
  opp::Params prm;
  prm.max_iterations = 300;
  prm.restart_after = 100;
  prm.gamma_s = 500.0;
  prm.gamma_f = 1e5;
  prm.gamma_m = 1e5;
  if (goal.safety_distance > 0) prm.safety_distance = goal.safety_distance;
  prm.colreg_distance = std::max(prm.colreg_distance, prm.safety_distance);
  prm.seed = r.u32();
  const auto own_kin = mpgc::colreg::ShipKinematics::from_course(pb.start.x, pb.start.y, cog, sog, own.heading);
  return fz::expect<std::invalid_argument>([&] {
    if (pb.colreg) {
      opp::EncounterMemory mem;
      opp::EncounterMemoryParams ep;
      ep.cpa_risk = 2.0 * prm.safety_distance;
      ep.tcpa_max = opp::norm(pb.goal.p - pb.start) / pb.speed;
      ep.release_range = prm.colreg_distance;
      fz::expect<std::invalid_argument>([&] { mem.update(ep, own_kin, targets); });
      fz::expect<std::invalid_argument>([&] { mem.update(ep, own_kin, pb.targets); });
    }
    fz::expect<std::invalid_argument>([&] {
      if (opp::norm(pb.goal.p - pb.start) < 100.0) return;
      // Any problem the validators let through is planned: check_problem bounds its extent
      // (README.md findings: a goal 1.1e16 m away once ground one plan for minutes).
      prm.validate();
      const opp::Result res = opp::plan(pb, prm);
      if (!res.path.empty()) {
        std::vector<opp::Vec2> pts;
        for (const auto& w : res.path) pts.push_back(w.p);
        (void)opp::check_path(pb, prm, pts, pb.colreg);
        (void)opp::plan(pb, prm, {}, pts);  // warm start from it, as the next plan of the same goal
      }
    });
    mpgc::colreg::ColregParams cp;
    cp.d_colreg = prm.colreg_distance;
    for (const auto& t : targets) {
      const mpgc::colreg::ShipKinematics tk{t.p.x, t.p.y, t.v.x, t.v.y};
      fz::expect<std::invalid_argument>([&] {
        (void)mpgc::colreg::assess(own_kin, tk, cp);
        (void)mpgc::colreg::bearing(own_kin, tk);
      });
    }
  });
}
