#include "mpgc/opp/problem.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mpgc::opp {

namespace {
constexpr double kPi = 3.14159265358979323846;
bool fin(double v) { return std::isfinite(v); }
void require(bool ok, const char* field, const std::string& why) {
  if (!ok) throw std::invalid_argument(std::string("opp::Params.") + field + " " + why);
}
}  // namespace

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(6);
  os << v;
  return os.str();
}

void ConstraintParams::validate() const {
  require(fin(safety_distance) && safety_distance >= 0, "safety_distance", "must be finite and >= 0");
  require(fin(colreg_distance) && colreg_distance >= safety_distance, "colreg_distance",
          "must be finite and >= safety_distance");
  require(fin(max_turn) && max_turn > 0, "max_turn", "must be finite and > 0");
  require(fin(colreg.overtaking_course_angle) && colreg.overtaking_course_angle > 0 && colreg.overtaking_course_angle < kPi / 2,
          "colreg.overtaking_course_angle", "must be in (0, pi/2)");
  require(fin(colreg.head_on_course_angle) && colreg.head_on_course_angle > 0 && colreg.head_on_course_angle < kPi / 2,
          "colreg.head_on_course_angle", "must be in (0, pi/2)");
  require(fin(colreg.epsilon) && colreg.epsilon > 0 && colreg.epsilon < 1, "colreg.epsilon", "must be in (0, 1)");
  require(fin(colreg.min_speed) && colreg.min_speed >= 0, "colreg.min_speed", "must be finite and >= 0");
  require(fin(colreg.port_tolerance) && colreg.port_tolerance >= 0 && colreg.port_tolerance < kPi, "colreg.port_tolerance",
          "must be in [0, pi)");
  require(fin(colreg.apparent_turn) && colreg.apparent_turn >= 0 && colreg.apparent_turn < kPi, "colreg.apparent_turn",
          "must be in [0, pi)");
  require(colreg.port_turn_range > 0, "colreg.port_turn_range", "must be > 0");
  require(colreg.risk_cpa > 0, "colreg.risk_cpa", "must be > 0");
  require(colreg.port_turn_lead >= 0 && std::isfinite(colreg.port_turn_lead), "colreg.port_turn_lead", "must be finite and >= 0");
  require(colreg.act_range >= 0, "colreg.act_range", "must be >= 0");
  require(fin(colreg.head_on_turn) && colreg.head_on_turn >= 0 && colreg.head_on_turn < kPi / 2, "colreg.head_on_turn",
          "must be in [0, pi/2)");
  require(fin(colreg.apparent_slowdown) && colreg.apparent_slowdown >= 0 && colreg.apparent_slowdown < 1,
          "colreg.apparent_slowdown", "must be in [0, 1)");
  require(fin(colreg.apparent_turn_margin) && colreg.apparent_turn_margin >= 0 && colreg.apparent_turn_margin < kPi / 2,
          "colreg.apparent_turn_margin", "must be in [0, pi/2)");
  require(fin(colreg.apparent_slowdown_margin) && colreg.apparent_slowdown_margin >= 0 &&
              colreg.apparent_slowdown + colreg.apparent_slowdown_margin < 1,
          "colreg.apparent_slowdown_margin", "must be >= 0 with apparent_slowdown + it < 1");
  require(fin(colreg_spacing) && colreg_spacing > 0, "colreg_spacing", "must be finite and > 0");
}

void ObjectiveParams::validate() const {
  require(fin(gamma_s) && gamma_s >= 0, "gamma_s", "must be finite and >= 0");
  require(fin(gamma_f) && gamma_f >= 0, "gamma_f", "must be finite and >= 0");
  require(fin(gamma_m) && gamma_m >= 0, "gamma_m", "must be finite and >= 0");
  require(fin(gamma_l) && gamma_l >= 0, "gamma_l", "must be finite and >= 0");
  require(gamma_s + gamma_f + gamma_m + gamma_l > 0, "gamma_l", "all cost weights are zero");
  require(fin(min_margin) && min_margin > 0, "min_margin", "must be finite and > 0");
}

std::string beyond_chart(const Problem& pb, double d) {
  if (!pb.charted) return "";
  const Bounds& r = *pb.charted;
  // Unknown water beyond the region counts as land: the start may be closer (it is where the
  // ship is; its first leg keeps what it has), the goal may not.
  if (r.contains(pb.start) && r.contains_by(pb.goal.p, d)) return "";
  return std::string(r.contains(pb.start) ? "goal" : "own ship") + " outside the charted region [" + fmt(r.min_x) +
         ", " + fmt(r.max_x) + "] x [" + fmt(r.min_y) + ", " + fmt(r.max_y) + "] m or within d_safety (" + fmt(d) +
         " m) of its edge: the water beyond it is unknown";
}

std::string check_problem(const Problem& pb, const ConstraintParams& c) {
  if (!finite(pb.start)) return "start position is not finite";
  if (!std::isfinite(pb.heading)) return "own heading is not finite";
  if (!std::isfinite(pb.speed) || pb.speed <= 0.0) return "own speed must be finite and > 0 (got " + fmt(pb.speed) + ")";
  if (!finite(pb.goal.p)) return "goal position is not finite";
  if (std::isinf(pb.goal.heading)) return "goal heading is infinite (NaN means any heading)";
  if (!std::isnan(pb.goal.heading) && !(pb.goal.heading_tolerance >= 0.0))
    return "goal heading tolerance must be >= 0 (got " + fmt(pb.goal.heading_tolerance) + ")";
  const Bounds& b = pb.bounds;
  if (!std::isfinite(b.min_x) || !std::isfinite(b.min_y) || !std::isfinite(b.max_x) || !std::isfinite(b.max_y) ||
      !(b.max_x > b.min_x) || !(b.max_y > b.min_y))
    return "sampling bounds are empty or not finite";
  // The local NED frame is flat, and a search box 1e16 m wide took minutes and gigabytes for one
  // plan (NodeGrid scans rings of empty cells, inside one iteration): the problem is bounded.
  if (b.max_x - b.min_x > kMaxBoundsSide || b.max_y - b.min_y > kMaxBoundsSide)
    return "sampling bounds wider than " + fmt(kMaxBoundsSide / 1000.0) + " km (start and goal too far apart)";
  if (!b.contains(pb.start)) return "start lies outside the sampling bounds";
  if (!b.contains(pb.goal.p)) return "goal lies outside the sampling bounds";
  if (pb.charted) {
    const Bounds& r = *pb.charted;
    if (std::isnan(r.min_x) || std::isnan(r.min_y) || std::isnan(r.max_x) || std::isnan(r.max_y) ||
        !(r.max_x > r.min_x) || !(r.max_y > r.min_y))
      return "charted region is empty or NaN";
    const std::string why = beyond_chart(pb, c.safety_distance);
    if (!why.empty()) return why;
  }
  if (pb.targets.size() > 10000) return "too many targets (" + std::to_string(pb.targets.size()) + " > 10000)";
  for (size_t i = 0; i < pb.targets.size(); ++i) {
    const Target& t = pb.targets[i];
    if (!finite(t.p) || !finite(t.v))
      return "target " + std::to_string(i) + " (id " + std::to_string(t.id) + ") has a non-finite position or velocity";
    if (!(t.margin >= 0.0) || !std::isfinite(t.margin))
      return "target " + std::to_string(i) + " (id " + std::to_string(t.id) + ") has a margin that is not finite and >= 0";
  }
  if (pb.fixed) {
    const double ds = pb.fixed->nearest(pb.start);
    if (ds <= 0.0 || (ds < c.safety_distance && !c.escape_start))
      return "start is within the safety distance of a fixed obstacle (" + fmt(ds) + " m < " + fmt(c.safety_distance) + " m)";
    const double dg = pb.fixed->nearest(pb.goal.p);
    if (dg < c.safety_distance || dg <= 0.0)
      return "goal is inside or within the safety distance of a fixed obstacle (" + fmt(dg) + " m < " +
             fmt(c.safety_distance) + " m)";
  }
  for (size_t i = 0; i < pb.targets.size() && !c.escape_start; ++i) {
    const double d = norm(pb.targets[i].p - pb.start), need = c.safety_distance + pb.targets[i].margin;
    if (d < need)
      return "start is within the safety distance of target " + std::to_string(i) + " (id " +
             std::to_string(pb.targets[i].id) + "): " + fmt(d) + " m < " + fmt(need) + " m";
  }
  return "";
}

}  // namespace mpgc::opp
