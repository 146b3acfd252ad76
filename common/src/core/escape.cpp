// colreg::best_escape: the widest single manoeuvre from a start (colreg.hpp).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/geom/vec2.hpp"

namespace mpgc::colreg {

void EscapeParams::validate() const {
  auto need = [](bool ok, const std::string& field, const std::string& what) {
    if (!ok) throw std::invalid_argument("escape." + field + ": " + what);
  };
  need(!speed_fractions.empty(), "speed_fractions", "is empty");
  for (double f : speed_fractions) need(std::isfinite(f) && f > 0.0 && f <= 1.0, "speed_fractions", "each must be in (0, 1]");
  need(std::isfinite(course_step) && course_step >= geo::deg2rad(0.01) && course_step <= geo::kPi, "course_step",
       "must be in [0.01 deg, 180 deg]");
  need(std::isfinite(turn_radius) && turn_radius >= 0.0, "turn_radius", "must be >= 0 m");
  need(std::isfinite(dt) && dt > 0.0 && dt <= 60.0, "dt", "must be in (0, 60] s");
  need(std::isfinite(max_alteration) && max_alteration >= 0.0 && max_alteration <= geo::kPi, "max_alteration",
       "must be in [0, 180] deg");
}

namespace {

struct Least {
  double d2 = INFINITY;
  int target = -1;
  void see(double v, int i) {
    if (v < d2) d2 = v, target = i;
  }
};

}  // namespace

Escape best_escape(const ShipKinematics& own, const std::vector<ShipKinematics>& targets, const EscapeParams& p) {
  p.validate();
  if (!own.finite()) throw std::invalid_argument("escape: the own ship's state is not finite");
  for (size_t i = 0; i < targets.size(); ++i)
    if (!targets[i].finite()) throw std::invalid_argument("escape: target " + std::to_string(i) + "'s state is not finite");
  const geom::Vec2 p0{own.x, own.y};
  const double u0 = own.speed(), psi0 = own.course();
  Escape best;
  best.min_distance = -1.0;  // the first candidate (no alteration) always replaces it
  const int n = static_cast<int>(std::floor(geo::kPi / p.course_step + 1e-9));
  for (double f : p.speed_fractions) {
    const double u = f * u0;
    // Alterations in the order a tie keeps: none, then starboard before port, the smaller first.
    for (int k = 0; k <= 2 * n; ++k) {
      const int side = k == 0 ? 0 : (k % 2 == 1 ? 1 : -1);
      const double delta = side * ((k + 1) / 2) * p.course_step;
      if ((p.starboard_only && side < 0) || std::fabs(delta) > p.max_alteration + 1e-12) continue;
      Least least;
      // The turn: a circle of turn_radius from the present course (x = x0 + s R (sin psi - sin psi0),
      // y = y0 - s R (cos psi - cos psi0) for heading psi = psi0 + s omega t), sampled every dt.
      double t_turn = 0.0;
      geom::Vec2 pe = p0;
      if (p.turn_radius > 0.0 && delta != 0.0 && u > 0.0) {
        const double s = side, omega = u / p.turn_radius;
        t_turn = std::fabs(delta) / omega;
        auto at = [&](double t) {
          const double psi = psi0 + s * omega * t;
          return p0 + geom::Vec2{s * p.turn_radius * (std::sin(psi) - std::sin(psi0)),
                                 -s * p.turn_radius * (std::cos(psi) - std::cos(psi0))};
        };
        for (double t = 0.0; t < t_turn; t += p.dt) {
          const geom::Vec2 q = at(t);
          for (size_t i = 0; i < targets.size(); ++i) {
            const geom::Vec2 y{targets[i].x + t * targets[i].vx, targets[i].y + t * targets[i].vy};
            least.see(geom::norm2(y - q), static_cast<int>(i));
          }
        }
        pe = at(t_turn);
      }
      // Then the course held: the closest approach from the end of the turn on.
      const double course = geo::wrap_pi(psi0 + delta);
      const geom::Vec2 v{u * std::cos(course), u * std::sin(course)};
      for (size_t i = 0; i < targets.size(); ++i) {
        const geom::Vec2 y{targets[i].x + t_turn * targets[i].vx, targets[i].y + t_turn * targets[i].vy};
        const geom::Vec2 w{targets[i].vx, targets[i].vy};
        least.see(geom::closest_approach(y - pe, w - v, INFINITY).dist2, static_cast<int>(i));
      }
      const double d = std::sqrt(least.d2);
      if (d > best.min_distance) best = {delta, course, u, d, least.target};
    }
  }
  return best;
}

}  // namespace mpgc::colreg
