#include "mpgc/obstacle_manager/manager.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <sstream>
#include <vector>

#include "mpgc/runtime/clock.hpp"

namespace mpgc::obstacle_manager {

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}
}  // namespace

void add_shapes(ChartBuilder& b, const std::string& spec) {
  std::stringstream all(spec);
  std::string item;
  int k = 0;
  while (std::getline(all, item, ';')) {
    item = trim(item);
    if (item.empty()) continue;
    std::stringstream ss(item);
    std::string kind;
    ss >> kind;
    const std::string name = "shape " + std::to_string(k++) + " (" + kind + ")";
    std::vector<double> v;
    std::string tok;
    while (ss >> tok) {
      try {
        size_t used = 0;
        v.push_back(std::stod(tok, &used));
        if (used != tok.size()) throw std::invalid_argument(tok);
      } catch (const std::exception&) {
        throw ChartError(name + ": '" + tok + "' is not a number");
      }
    }
    std::vector<geom::Vec2> pts;
    for (size_t i = 0; i + 1 < v.size(); i += 2) pts.push_back({v[i], v[i + 1]});
    if (kind == "circle") {
      if (v.size() != 3) throw ChartError(name + ": needs 'circle N E R', got " + std::to_string(v.size()) + " numbers");
      b.add_circle({v[0], v[1]}, v[2], name);
    } else if (kind == "polygon" || kind == "line" || kind == "point") {
      if (v.size() % 2 != 0) throw ChartError(name + ": needs pairs N E, got " + std::to_string(v.size()) + " numbers");
      if (kind == "polygon") b.add_polygon(pts, name);
      if (kind == "line") b.add_line(pts, name);
      if (kind == "point") {
        if (pts.size() != 1) throw ChartError(name + ": needs 'point N E'");
        b.add_point(pts[0], name);
      }
    } else {
      throw ChartError(name + ": unknown shape '" + kind + "' (circle, polygon, line, point)");
    }
  }
}

void RegionParams::validate() const {
  if (!std::isfinite(half_size) || half_size < 0.0)
    throw std::invalid_argument("RegionParams.half_size = " + std::to_string(half_size) + " m must be >= 0");
  if (!std::isfinite(republish_distance) || republish_distance <= 0.0 ||
      (half_size > 0.0 && republish_distance >= half_size))
    throw std::invalid_argument("RegionParams.republish_distance = " + std::to_string(republish_distance) +
                                " m must be > 0 and below half_size");
}

RegionPolicy::RegionPolicy(RegionParams p) : p_(p) { p_.validate(); }

bool RegionPolicy::needs_update(geom::Vec2 own) const {
  if (dirty_ || !centre_) return true;
  if (whole_chart()) return false;
  return std::hypot(own.x - centre_->x, own.y - centre_->y) > p_.republish_distance;
}

void RegionPolicy::set_goal(std::optional<geom::Vec2> goal) {
  const bool same = goal.has_value() == goal_.has_value() && (!goal || (goal->x == goal_->x && goal->y == goal_->y));
  if (same) return;
  goal_ = goal;
  if (!whole_chart()) dirty_ = true;
}

BoxNE RegionPolicy::publish(geom::Vec2 own) {
  centre_ = own;
  dirty_ = false;
  if (whole_chart()) {
    const double inf = std::numeric_limits<double>::infinity();
    return {-inf, -inf, inf, inf};
  }
  const geom::Vec2 g = goal_.value_or(own);
  return {std::min(own.x, g.x) - p_.half_size, std::min(own.y, g.y) - p_.half_size,
          std::max(own.x, g.x) + p_.half_size, std::max(own.y, g.y) + p_.half_size};
}

void DomainParams::validate() const {
  if (!std::isfinite(min_radius) || min_radius < 0.0) throw std::invalid_argument("DomainParams.min_radius must be >= 0");
  if (!std::isfinite(lengths) || lengths < 0.0) throw std::invalid_argument("DomainParams.lengths must be >= 0");
  if (!(max_speed > 0.0)) throw std::invalid_argument("DomainParams.max_speed must be > 0");
  if (!(max_range > 0.0)) throw std::invalid_argument("DomainParams.max_range must be > 0");
  if (!std::isfinite(stopped_speed) || stopped_speed < 0.0)
    throw std::invalid_argument("DomainParams.stopped_speed must be >= 0 m/s");
  if (!std::isfinite(stopped_sigmas) || stopped_sigmas < 0.0)
    throw std::invalid_argument("DomainParams.stopped_sigmas must be >= 0");
}

std::string check_target(const TargetState& t, const DomainParams& p) {
  if (t.deleted) return "deleted";
  if (t.tentative && !p.tentative) return "tentative";
  for (double v : {t.x, t.y, t.vx, t.vy, t.var_x, t.var_y, t.var_vx, t.var_vy, t.since_update})
    if (!std::isfinite(v)) return "track " + std::to_string(t.id) + ": state is not finite";
  if (t.var_x < 0.0 || t.var_y < 0.0) return "track " + std::to_string(t.id) + ": negative position variance";
  if (t.var_vx < 0.0 || t.var_vy < 0.0) return "track " + std::to_string(t.id) + ": negative velocity variance";
  if (t.since_update < 0.0) return "track " + std::to_string(t.id) + ": negative since_update";
  const double speed = std::hypot(t.vx, t.vy);
  if (speed > p.max_speed)
    return "track " + std::to_string(t.id) + ": speed " + std::to_string(speed) + " m/s > max " + std::to_string(p.max_speed);
  if (std::hypot(t.x, t.y) > p.max_range) return "track " + std::to_string(t.id) + ": position beyond max_range";
  if (!std::isnan(t.length) && !(t.length > 0.0 && t.length < 1000.0))
    return "track " + std::to_string(t.id) + ": length " + std::to_string(t.length) + " m out of range";
  return "";
}

MovingObstacleOut to_moving_obstacle(const TargetState& t, const DomainParams& p) {
  MovingObstacleOut o;
  o.id = t.id;
  o.mmsi = t.mmsi;
  o.x = t.x;
  o.y = t.y;
  const double speed = std::hypot(t.vx, t.vy);
  const bool stopped = speed < p.stopped_speed && speed < p.stopped_sigmas * std::sqrt(t.var_vx + t.var_vy);
  o.vx = stopped ? 0.0 : t.vx;
  o.vy = stopped ? 0.0 : t.vy;
  o.radius = std::isnan(t.length) ? p.min_radius : std::max(p.min_radius, p.lengths * t.length);
  o.position_std = std::sqrt(std::max(t.var_x, t.var_y));
  return o;
}

void AgingParams::validate() const {
  if (!(max_age > 0.0) || !std::isfinite(max_age))
    throw std::invalid_argument("AgingParams.max_age = " + std::to_string(max_age) + " s must be > 0");
  if (!(timeout > 0.0) || !std::isfinite(timeout))
    throw std::invalid_argument("AgingParams.timeout = " + std::to_string(timeout) + " s must be > 0");
  if (!(speed_std >= 0.0) || !std::isfinite(speed_std))
    throw std::invalid_argument("AgingParams.speed_std = " + std::to_string(speed_std) + " m/s must be >= 0");
  if (!(radius_sigmas >= 0.0) || !std::isfinite(radius_sigmas))
    throw std::invalid_argument("AgingParams.radius_sigmas = " + std::to_string(radius_sigmas) + " must be >= 0");
}

MovingObstacleOut grow_uncertainty(MovingObstacleOut o, double dt, const AgingParams& a) {
  if (!(dt > 0.0)) return o;
  const double s0 = o.position_std, g = a.speed_std * dt;
  o.position_std = std::sqrt(s0 * s0 + g * g);
  o.radius += a.radius_sigmas * (o.position_std - s0);
  return o;
}

MovingObstacleFeed::MovingObstacleFeed(DomainParams d, AgingParams a) : d_(d), a_(a) {
  d_.validate();
  a_.validate();
}

MovingObstacleFeed::Received MovingObstacleFeed::receive(int64_t stamp_ns, const std::vector<TargetState>& targets,
                                                         int64_t now_ns) {
  Received r;
  held_.clear();
  std::set<uint32_t> ids;
  for (const auto& t : targets) {
    const std::string why = check_target(t, d_);
    if (why == "deleted") ++r.deleted;
    else if (why == "tentative") ++r.tentative;
    else if (!why.empty()) r.rejected.push_back(why);
    else {
      held_.push_back(to_moving_obstacle(t, d_));
      ids.insert(t.id);
    }
  }
  // Forget what was reported for tracks no longer listed (bounded memory, ids are never reused).
  for (auto it = reported_.begin(); it != reported_.end();) it = ids.count(*it) ? std::next(it) : reported_.erase(it);
  list_stamp_ns_ = stamp_ns;
  arrival_ns_ = now_ns;
  return r;
}

MovingObstacleFeed::Output MovingObstacleFeed::at(int64_t now_ns) {
  if (!first_call_ns_) first_call_ns_ = now_ns;
  Output out;
  const int64_t since = arrival_ns_ ? *arrival_ns_ : *first_call_ns_;
  out.silence = std::max(0.0, static_cast<double>(rt::ns_between(now_ns, since)) / 1e9);
  if (!list_stamp_ns_) {
    out.t_valid_ns = now_ns;  // no tracks yet: an empty, current list
    out.feed = out.silence > a_.timeout ? Feed::kSilent : Feed::kWaiting;
    return out;
  }
  out.feed = out.silence > a_.timeout ? Feed::kSilent : Feed::kFresh;
  // A stamp ahead of our clock (another host's clock) counts as age 0, never as negative age.
  const double dt = std::max(0.0, static_cast<double>(rt::ns_between(now_ns, *list_stamp_ns_)) / 1e9);
  out.t_valid_ns = *list_stamp_ns_;
  for (const auto& o : held_) {
    if (dt > a_.max_age) {
      if (reported_.insert(o.id).second) out.aged_out.push_back(o.id);
      continue;
    }
    reported_.erase(o.id);  // listed again: report its next ageing too
    out.obstacles.push_back(grow_uncertainty(o, dt, a_));
  }
  // Nothing left: an empty list valid now, not an old stamp nobody should extrapolate from.
  if (out.obstacles.empty()) out.t_valid_ns = now_ns;
  return out;
}

}  // namespace mpgc::obstacle_manager
