// Path following for a waypoint path: waypoint management (circle of acceptance or passing the
// along-track point of the waypoint, whichever comes first), line-of-sight guidance with a lookahead
// distance and optional integral action against current (ILOS), desired heading and speed, and a
// seamless join of a new path under way. No DDS, no clock: time steps are inputs.
//
// Guidance laws (Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control, 2011/2021):
//   path-tangential angle   pi_p = atan2(y_k - y_{k-1}, x_k - x_{k-1})
//   along / cross track     s = (p - p_{k-1}) . t_k,   e = (p - p_{k-1}) x t_k  (positive: starboard)
//   LOS                     chi_d = pi_p - atan(e / Delta)
//   ILOS                    chi_d = pi_p - atan((e + kappa y_int) / Delta),
//                           dy_int/dt = U Delta e / ((e + kappa y_int)^2 + Delta^2)   (U: ship speed)
// The ILOS integral builds the crab angle a steady current (or wind) needs, so the desired course
// is used directly as the desired heading.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mpgc::guidance_control {

// One waypoint of a plan in the local NED frame.
struct PathPoint {
  double x = 0.0;      // [m] north
  double y = 0.0;      // [m] east
  double speed = 0.0;  // [m/s] planned speed on the leg that ends here; <= 0: use the default speed
};

// Defaults are for KVLCC2 (Lpp = 320 m, tactical diameter ~3.2 Lpp at 35 deg rudder): see README.md.
struct PathFollowerParams {
  double lookahead = 800.0;          // [m] LOS lookahead distance Delta (2.5 Lpp)
  double acceptance_radius = 800.0;  // [m] radius of the circle of acceptance around a waypoint (2.5 Lpp)
  bool integral = true;              // ILOS: integral action against current and wind
  double integral_gain = 0.2;        // [-] ILOS kappa (0 < kappa < 1 keeps the integral well damped)
  double integral_limit = 400.0;     // [m] |kappa * y_int| bound (limits the crab angle it can build)
  double integral_zone = 200.0;      // [m] integrate only while |cross-track| < this: joining a path from
                                     // far off is geometry, not current, and would wind the integral up
  double default_speed = 7.0;        // [m/s] used where a waypoint carries no speed (<= 0)
  double max_speed = 12.0;           // [m/s] planned speeds above this are clamped
  void validate() const;  // throws std::invalid_argument naming the bad field
};

// Checks a waypoint list: at least two distinct points, every coordinate finite and within
// |x|,|y| <= 1e7 m, every speed finite, at most `max_points`. Returns an empty string when valid, else
// the reason (naming the waypoint index).
std::string check_path(const std::vector<PathPoint>& pts, std::size_t max_points = 10000);

// Removes consecutive points closer than `min_spacing` (zero-length legs carry no direction).
std::vector<PathPoint> drop_duplicate_points(const std::vector<PathPoint>& pts, double min_spacing = 1e-3);

// Geometry of the ship relative to one leg.
struct LegGeometry {
  double course = 0.0;       // [rad] path-tangential angle pi_p
  double length = 0.0;       // [m] leg length
  double along = 0.0;        // [m] along-track distance from the leg start
  double cross = 0.0;        // [m] cross-track error, positive when the ship is starboard of the leg
  double to_end = 0.0;       // [m] distance from the ship to the leg's end waypoint
};
LegGeometry leg_geometry(const PathPoint& a, const PathPoint& b, double x, double y);

// Output of one guidance step.
struct GuidanceOutput {
  bool arrived = false;            // the last waypoint has been reached
  std::size_t active_waypoint = 0; // [-] index of the waypoint being steered to (end of active leg)
  double desired_heading = 0.0;    // [rad] (-pi, pi]
  double desired_speed = 0.0;      // [m/s]
  double cross_track_error = 0.0;  // [m] positive: starboard of the path
  double along_track = 0.0;        // [m] progress along the active leg
  double leg_course = 0.0;         // [rad] pi_p of the active leg
};

class PathFollower {
 public:
  explicit PathFollower(const PathFollowerParams& p);

  // Starts following `pts` (validated with check_path; throws std::invalid_argument otherwise)
  // from the ship position (x, y): the active leg is the leg nearest to the ship (the first one on a
  // tie); the first update then moves on past legs whose end the ship has already reached or passed.
  // The ILOS integral is kept, since the current does not change with the plan.
  void set_path(const std::vector<PathPoint>& pts, double x, double y);
  bool has_path() const { return !pts_.empty(); }
  void clear();

  // One guidance step at ship position (x, y) [m], speed [m/s] (through the water or over ground;
  // scales the ILOS integral rate), over the time step dt [s].
  GuidanceOutput update(double x, double y, double speed, double dt);

  // The leg (index of its end waypoint) nearest to (x, y), as set_path chooses it.
  static std::size_t join_leg(const std::vector<PathPoint>& pts, double x, double y);

  const std::vector<PathPoint>& path() const { return pts_; }
  std::size_t active_waypoint() const { return active_; }
  bool arrived() const { return arrived_; }
  double integral_state() const { return y_int_; }  // [m]
  const PathFollowerParams& params() const { return p_; }

 private:
  double leg_speed(std::size_t k) const;

  PathFollowerParams p_;
  std::vector<PathPoint> pts_;
  std::size_t active_ = 1;
  bool arrived_ = false;
  double y_int_ = 0.0;
};

}  // namespace mpgc::guidance_control
