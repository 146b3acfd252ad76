#include "mpgc/guidance_control/path_follower.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::guidance_control {

namespace {
void require(bool ok, const std::string& field, const std::string& why) {
  if (!ok) throw std::invalid_argument("PathFollowerParams." + field + " " + why);
}
}  // namespace

void PathFollowerParams::validate() const {
  require(std::isfinite(lookahead) && lookahead > 0.0, "lookahead", "must be finite and > 0 m");
  require(std::isfinite(acceptance_radius) && acceptance_radius > 0.0, "acceptance_radius", "must be finite and > 0 m");
  require(std::isfinite(integral_gain) && integral_gain > 0.0 && integral_gain < 1.0, "integral_gain",
          "must be in (0, 1)");
  require(std::isfinite(integral_limit) && integral_limit >= 0.0, "integral_limit", "must be finite and >= 0 m");
  require(std::isfinite(integral_zone) && integral_zone > 0.0, "integral_zone", "must be finite and > 0 m");
  require(std::isfinite(default_speed) && default_speed > 0.0, "default_speed", "must be finite and > 0 m/s");
  require(std::isfinite(max_speed) && max_speed >= default_speed, "max_speed", "must be finite and >= default_speed");
}

std::string check_path(const std::vector<PathPoint>& pts, std::size_t max_points) {
  if (pts.empty()) return "empty path";
  if (pts.size() > max_points)
    return "path has " + std::to_string(pts.size()) + " waypoints, more than " + std::to_string(max_points);
  constexpr double kMaxCoord = 1e7;  // [m] far beyond any local NED frame
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      return "waypoint " + std::to_string(i) + " has a non-finite coordinate";
    if (std::abs(p.x) > kMaxCoord || std::abs(p.y) > kMaxCoord)
      return "waypoint " + std::to_string(i) + " is more than 1e7 m from the origin";
    if (!std::isfinite(p.speed)) return "waypoint " + std::to_string(i) + " has a non-finite speed";
  }
  if (drop_duplicate_points(pts).size() < 2)
    return pts.size() == 1 ? "path has a single waypoint (no leg to follow)" : "path has no leg of non-zero length";
  return {};
}

std::vector<PathPoint> drop_duplicate_points(const std::vector<PathPoint>& pts, double min_spacing) {
  std::vector<PathPoint> out;
  out.reserve(pts.size());
  for (const auto& p : pts) {
    if (!out.empty() && std::hypot(p.x - out.back().x, p.y - out.back().y) < min_spacing) {
      out.back().speed = p.speed;  // the later point ends the (merged) leg
      continue;
    }
    out.push_back(p);
  }
  return out;
}

LegGeometry leg_geometry(const PathPoint& a, const PathPoint& b, double x, double y) {
  LegGeometry g;
  const double dx = b.x - a.x, dy = b.y - a.y;
  g.length = std::hypot(dx, dy);
  g.course = geo::course_of(dx, dy);
  const double tx = dx / g.length, ty = dy / g.length;  // unit tangent (north, east)
  const double px = x - a.x, py = y - a.y;
  g.along = px * tx + py * ty;
  g.cross = -px * ty + py * tx;  // positive to starboard of the direction of travel
  g.to_end = std::hypot(x - b.x, y - b.y);
  return g;
}

PathFollower::PathFollower(const PathFollowerParams& p) : p_(p) { p_.validate(); }

void PathFollower::clear() {
  pts_.clear();
  active_ = 1;
  arrived_ = false;
}

std::size_t PathFollower::join_leg(const std::vector<PathPoint>& pts, double x, double y) {
  // Nearest segment, not "nearest leg whose end is ahead": a leg far abeam can have its end ahead in
  // the along-track sense (e.g. the first leg of a plan re-sent after the ship has turned the corner).
  std::size_t best = 1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < pts.size(); ++k) {
    const LegGeometry g = leg_geometry(pts[k - 1], pts[k], x, y);
    const double d = g.along < 0.0 ? std::hypot(x - pts[k - 1].x, y - pts[k - 1].y)
                     : g.along > g.length ? g.to_end
                                          : std::abs(g.cross);
    if (d < best_d - 1.0) {  // 1 m hysteresis: on ties the earlier leg wins (the path is flown in order)
      best_d = d;
      best = k;
    }
  }
  return best;
}

void PathFollower::set_path(const std::vector<PathPoint>& pts, double x, double y) {
  const std::string why = check_path(pts);
  if (!why.empty()) throw std::invalid_argument("PathFollower::set_path: " + why);
  if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("PathFollower::set_path: non-finite ship position");
  pts_ = drop_duplicate_points(pts);
  active_ = join_leg(pts_, x, y);
  arrived_ = false;
}

double PathFollower::leg_speed(std::size_t k) const {
  const double s = pts_[k].speed;
  return s > 0.0 ? std::min(s, p_.max_speed) : p_.default_speed;
}

GuidanceOutput PathFollower::update(double x, double y, double speed, double dt) {
  if (pts_.empty()) throw std::logic_error("PathFollower::update without a path");
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(speed) || !std::isfinite(dt) || dt < 0.0)
    throw std::invalid_argument("PathFollower::update: non-finite position or speed, or negative time step");

  // Waypoint management: switch on the circle of acceptance or on passing the along-track point of
  // the waypoint (the normal to the leg through it), whichever comes first.
  LegGeometry g = leg_geometry(pts_[active_ - 1], pts_[active_], x, y);
  while (!arrived_ && (g.to_end <= p_.acceptance_radius || g.along >= g.length)) {
    if (active_ + 1 >= pts_.size()) {
      arrived_ = true;
      break;
    }
    ++active_;
    g = leg_geometry(pts_[active_ - 1], pts_[active_], x, y);
  }

  GuidanceOutput out;
  out.arrived = arrived_;
  out.active_waypoint = active_;
  out.cross_track_error = g.cross;
  out.along_track = g.along;
  out.leg_course = g.course;
  if (arrived_) {
    out.desired_heading = geo::wrap_pi(g.course);
    out.desired_speed = 0.0;
    return out;
  }

  const double delta = p_.lookahead;
  double chi_d = 0.0;
  if (p_.integral) {
    const double kappa = p_.integral_gain;
    const double ee = g.cross + kappa * y_int_;
    chi_d = g.course - std::atan(ee / delta);
    // Integrate only near the path: far off it (turns, joins) the error is geometry, not current.
    if (std::abs(g.cross) < p_.integral_zone) y_int_ += dt * std::abs(speed) * delta * g.cross / (ee * ee + delta * delta);
    const double lim = p_.integral_limit / kappa;
    y_int_ = std::clamp(y_int_, -lim, lim);
  } else {
    chi_d = g.course - std::atan(g.cross / delta);
  }
  out.desired_heading = geo::wrap_pi(chi_d);
  out.desired_speed = leg_speed(active_);
  return out;
}

}  // namespace mpgc::guidance_control
