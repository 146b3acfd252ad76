// Seed 002 §2: the ship's state vector [x, y, psi, r, u, v] (eq. 1) predicted from turning-circle
// trial tables (written by `./mpgc trial table --out FILE`), by linear and bilinear table
// interpolation (Fig. 3) and by the convex-quadrilateral interpolation of eq. 4.
//
//   opp::TurningTables tt = opp::load_turning_tables_file("tables.csv");   // validated
//   opp::StateVector s = tt.at(rudder, r0, 42.0);      // Fig. 3: bilinear in (rudder, r0), linear in t
//   opp::StateVector w = opp::predict(tt, own, rudder, 42.0);  // the same, moved to the own ship
//   std::optional<opp::PointState> q = opp::state_at_point(tt, r0, {300.0, 120.0});  // eq. 4
//
// Table frame: eq. 3 starting conditions (x = y = psi = 0, r = r0, u = the trial's approach speed,
// v = 0, rudder 0 then put over at the steering gear's rate). Local NED as everywhere (x north,
// y east, psi clockwise, r and rudder positive to starboard); psi is not wrapped. Angles in rad.
// No DDS, no clock, no global state.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "mpgc/geom/vec2.hpp"

namespace mpgc::opp {

// Eq. 1.
struct StateVector {
  double x = 0.0;    // [m] north
  double y = 0.0;    // [m] east
  double psi = 0.0;  // [rad] heading, clockwise, unwrapped
  double r = 0.0;    // [rad/s] yaw rate, + to starboard
  double u = 0.0;    // [m/s] surge
  double v = 0.0;    // [m/s] sway, + to starboard
};

// Fig. 3, one row: f1 + (f2 - f1) (x - x1) / (x2 - x1), every component of the state alike.
double interpolate_linear(double x1, double f1, double x2, double f2, double x);
StateVector interpolate_linear(double x1, const StateVector& s1, double x2, const StateVector& s2, double x);

// Fig. 3 "two-line" (bilinear) interpolation on the rectangle [a1, a2] x [b1, b2]: fij at (ai, bj);
// linear in a on both edges b1 and b2, then linear in b.
double interpolate_bilinear(double a1, double a2, double b1, double b2, double f11, double f21, double f12,
                            double f22, double a, double b);

// Eq. 4: w_i = (sum_j d_j - d_i) / sum_j d_j, f0 = sum w_i f_i / sum w_i, d_i = |p - node_i|.
// The weights are returned normalised (they sum to 1). With p on a node (all d_i = 0 only if the
// four nodes coincide) the nodes are averaged. Note that eq. 4 is a weighted mean, not an
// interpolant: at a node it does not return that node's value (weights 1, (D - d_j)/D, ...).
std::array<double, 4> quad_weights(const std::array<geom::Vec2, 4>& nodes, geom::Vec2 p);
double quad_interpolate(const std::array<geom::Vec2, 4>& nodes, const std::array<double, 4>& f, geom::Vec2 p);

// Not in the paper; the interpolant eq. 4 is not: (s, t) in [0, 1]^2 with
// p = (1-s)(1-t) n0 + s(1-t) n1 + s t n2 + (1-s) t n3 (the quad's bilinear map inverted), so that
// f0 = (1-s)(1-t) f0 + ... reproduces the node values and every bilinear field. nullopt when p is
// not in the quad (tol in s, t).
std::optional<std::array<double, 2>> quad_inverse_bilinear(const std::array<geom::Vec2, 4>& nodes, geom::Vec2 p,
                                                           double tol = 1e-9);

// True when nodes (in order around the boundary, either sense) form a convex quadrilateral, which
// may be degenerate (two nodes coincide: the first quad of a fan at t = 0 is a triangle), and p is
// inside or on it (within tol [m]).
bool convex_quad_contains(const std::array<geom::Vec2, 4>& nodes, geom::Vec2 p, double tol = 1e-9);

// convex_quad_contains with the quad's edges and winding worked out once: a fan asks each of its
// quads for many points (the same answers, the same arithmetic).
struct QuadShape {
  std::array<geom::Vec2, 4> n{}, e{};  // nodes; edges n[i] -> n[i+1]
  std::array<double, 4> len{};         // [m] edge lengths
  double scale = 0.0;                  // [m] the longest edge
  int sign = 0;                        // winding: +1, -1; 0 when not convex or without area
  explicit QuadShape(const std::array<geom::Vec2, 4>& nodes);
  bool contains(geom::Vec2 p, double tol) const;
};

// The tables of one engine setting: one trial per (rudder, r0) node, each sampled at t = k dt,
// k = 0 .. n_times - 1.
class TurningTables {
 public:
  // rudders [rad] and r0s [rad/s] strictly increasing; dt [s] > 0; samples[(i * r0s.size() + j) *
  // n_times + k] = trial (rudders[i], r0s[j]) at k dt. Throws std::invalid_argument naming what is
  // wrong (sizes, order, non-finite values, a t = 0 row that is not eq. 3).
  TurningTables(std::vector<double> rudders, std::vector<double> r0s, double dt, int n_times,
                std::vector<StateVector> samples, std::string source = "tables");

  const std::vector<double>& rudders() const { return rudders_; }  // [rad]
  const std::vector<double>& r0s() const { return r0s_; }          // [rad/s]
  double dt() const { return dt_; }                                // [s]
  int n_times() const { return n_times_; }
  double duration() const { return dt_ * (n_times_ - 1); }  // [s]
  double approach_speed() const;                            // [m/s] u at t = 0
  const StateVector& node(std::size_t i_rudder, std::size_t j_r0, int k) const;

  // Fig. 3: row k of the table of any (rudder, r0) inside the grid, bilinear between the four
  // trials around it (linear along an axis with one node). Throws std::out_of_range outside.
  StateVector row(double rudder, double r0, int k) const;
  // The same at any t in [0, duration()], linear in t between rows.
  StateVector at(double rudder, double r0, double t) const;

 private:
  std::size_t bracket(const std::vector<double>& axis, double value, const char* what, double& w) const;
  std::vector<double> rudders_, r0s_;
  double dt_;
  int n_times_;
  std::vector<StateVector> samples_;
  std::string source_;
};

// Reads the CSV of `./mpgc trial table`: '#' comment lines, the header
// rudder_deg,r0_deg_s,t_s,x_m,y_m,psi_rad,r_rad_s,u_m_s,v_m_s, then one row per sample ordered by
// rudder, r0, t (each ascending, every trial on the same time grid from 0). Throws
// std::runtime_error "SOURCE:LINE: what is wrong" for a malformed file: a wrong header, a cell that is
// not a finite number, a missing row or trial, a grid out of order or uneven.
TurningTables load_turning_tables(std::istream& in, const std::string& source = "tables");
TurningTables load_turning_tables_file(const std::string& path);

// §2: the table frame moved to a start state (translated to its position, turned by its course).
// Only x, y, psi change; the start's r selects the table (r0) and its u must be the tables'.
StateVector to_world(const StateVector& start, const StateVector& table_state);
// The state t [s] after putting the rudder [rad] over from `start` (r0 = start.r).
StateVector predict(const TurningTables& tables, const StateVector& start, double rudder, double t);

// Eq. 4 on the tables (Fig. 4): the state at a point p of the table frame, for initial yaw rate r0.
// The trials of every table rudder at r0 (Fig. 3, linear in r0) make a fan of quadrilaterals
// (rudders i, i+1 x times k, k+1); the earliest convex one containing p gives psi, r, u, v, the
// time to reach p and the rudder setting, each by eq. 4. nullopt when no quad contains p.
struct PointState {
  StateVector state;          // x, y = p
  double t = 0.0;             // [s] time to reach p
  double rudder = 0.0;        // [rad] steady rudder setting that reaches p
  std::array<geom::Vec2, 4> nodes{};                 // the quad used (table frame)
  std::array<StateVector, 4> node_states{};          // its nodes' states
  std::array<double, 4> node_t{}, node_rudder{};     // their times [s] and rudders [rad]
};
// rule kEq4 is the paper's; kInverseBilinear uses quad_inverse_bilinear on the same quad.
enum class QuadRule { kEq4, kInverseBilinear };
std::optional<PointState> state_at_point(const TurningTables& tables, double r0, geom::Vec2 p,
                                         QuadRule rule = QuadRule::kEq4);

// state_at_point's fan at one r0, built once for many points: dijkstra-sv asks it for every leg at
// the same yaw rate (the fan's 900 table rows and its quads' shapes were three quarters of its
// planning time when rebuilt per leg). The same answers as state_at_point, bit for bit.
class TurningFan {
 public:
  TurningFan(const TurningTables& tables, double r0);
  std::optional<PointState> state_at(geom::Vec2 p, QuadRule rule = QuadRule::kEq4) const;
  double r0() const { return r0_; }

 private:
  double r0_, dt_;
  std::vector<double> rudders_;
  int nt_;
  std::vector<StateVector> fan_;  // [rudder i][time k]
  std::vector<QuadShape> quads_;  // [time k][rudder i]: rudders i, i+1 x times k, k+1
};

// The accuracy check of §2 (after eq. 4): random starting conditions r0 and rudder settings
// (seeded), the model itself simulated from eq. 3 against the tables' interpolation. The paper's
// measure, kept here: the interpolation error of each state parameter as a fraction of the node
// spread |max{f1..f4} - min{f1..f4}| of that parameter over the four interpolation nodes, the
// worst parameter counting for the case ("did not exceed 10 %" in all 200 cases). Two checks:
//  - Fig. 3: the table row of (rudder, r0) at every table time t = k dt, k >= 1, bilinear between
//    the four trials around it; parameters x, y, psi, r, u, v; the case's worst over k.
//  - eq. 4: one random time t* in [dt, duration], the model's position p(t*) located in the fan at
//    r0 (state_at_point); parameters psi, r, u, v and the time to reach p.
// A spread below the parameter's floor (the resolution worth resolving) is replaced by the floor, so
// a parameter that hardly varies between the nodes cannot turn a tiny absolute error into a large
// fraction.
struct AccuracyParams {
  int cases = 200;                // [-] random (r0, rudder) pairs, 1..100000
  uint64_t seed = 1;              // [-] std::mt19937_64 seed
  int substeps = 10;              // [-] truth samples per table step (t* on dt / substeps), 1..1000
  double floor_xy = 0.5;          // [m]
  double floor_psi = 1e-3;        // [rad] (0.057 deg)
  double floor_r = 1e-5;          // [rad/s] (0.00057 deg/s)
  double floor_uv = 1e-3;         // [m/s]
  double floor_t = 0.1;           // [s]
  void validate() const;          // throws std::invalid_argument naming the field
};
// The model: the state every `step` [s], n samples from t = 0, after eq. 3 with the given r0 and
// rudder (both in the tables' range).
using TrialFn = std::function<std::vector<StateVector>(double r0, double rudder, double step, int n)>;
struct AccuracyReport {
  std::vector<double> fig3_pct;  // [%] per case, worst parameter and time
  std::vector<double> eq4_pct;   // [%] per located case, worst parameter
  int eq4_not_located = 0;       // cases whose point p(t*) lies in no quad of the fan
  // located cases whose (earliest) quad is not between the rudders around the case's own: the fan
  // folds (early in a turn the rudder's kick makes trials cross), another rudder reaches p too
  int eq4_other_rudder = 0;
  std::string fig3_worst, eq4_worst;  // the worst case, described
  // [%] the same per parameter (x, y, psi, r, u, v; psi, r, u, v, t), every case
  std::map<std::string, std::vector<double>> fig3_by_param, eq4_by_param;
  // [%] the same point check with QuadRule::kInverseBilinear instead of eq. 4 (not the paper's)
  std::vector<double> inv_pct;
  std::map<std::string, std::vector<double>> inv_by_param;
};
AccuracyReport check_accuracy(const TurningTables& tables, const TrialFn& truth, const AccuracyParams& params);
// Largest and median of a list of percentages (NaN for an empty list).
double max_of(const std::vector<double>& v);
double median_of(std::vector<double> v);

}  // namespace mpgc::opp
