// Standard manoeuvring trials (IMO MSC.137(76) definitions) run on any ShipModel, and the
// turning-circle tables of seed 002 §2.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::ship_simulator {

struct TrialConditions {
  double approach_speed = 0.0;  // [m/s] straight-line speed at the execute point
  double rpm = 0.0;             // [1/min] propeller speed held through the trial
  double dt = 0.1;              // [s] integration step
  void validate() const;
};

struct TurningCircleResult {
  double rudder_deg;           // [deg] rudder ordered, positive to starboard
  double advance_m;            // [m] along the approach course when the heading has changed 90 deg
  double transfer_m;           // [m] across the approach course at 90 deg (positive magnitude)
  double tactical_diameter_m;  // [m] across the approach course at 180 deg
  double steady_diameter_m;    // [m] 2 U / r in the steady turn
  double speed_ratio_steady;   // [-] U in the steady turn / approach speed
  double time_to_90_s;         // [s]
  double time_to_180_s;        // [s]
  double steady_rate_deg_s;    // [deg/s] |r| in the steady turn
};

// Ship on a straight course at the approach speed, rudder put to `rudder` [rad] (signed,
// positive to starboard) at t = 0 at the model's rate. Runs until 720 deg of heading change
// (steady values are averaged over the last 360 deg). Throws std::runtime_error when the ship
// does not reach 180 deg within max_time_s.
TurningCircleResult turning_circle(ShipModel& model, double rudder, const TrialConditions& c,
                                   double max_time_s = 5000.0);

struct ZigzagResult {
  double angle_deg;              // [deg] rudder angle = heading change that triggers reversal
  int first_side;                // +1 starboard first, -1 port first
  std::vector<double> overshoots_deg;  // [deg] first, second, third overshoot
  std::vector<double> reversal_times_s;  // [s] times of the rudder reversals
};

// Zig-zag angle/angle: rudder to first_side * angle, reversed whenever the heading change
// reaches the same angle on that side; records the first `n_overshoots` overshoots.
ZigzagResult zigzag(ShipModel& model, double angle, int first_side, const TrialConditions& c,
                    int n_overshoots = 3, double max_time_s = 3000.0);

// One row of a turning-circle table (seed 002 eq. 1 state vector).
struct TableRow {
  double rudder_deg, r0_deg_s, t_s;
  double x, y, psi, r, u, v;  // [m] [m] [rad] [rad/s] [m/s] [m/s]
};

// Seed 002 §2, eq. 3: for every initial yaw rate r0 and rudder angle, start at x = y = psi = 0,
// u = approach speed, v = 0, r = r0, rudder 0; put the rudder over (rate-limited) and record the
// state every dt_out until `duration`. r0 and rudder in rad(/s).
std::vector<TableRow> turning_tables(ShipModel& model, const std::vector<double>& rudders,
                                     const std::vector<double>& r0s, const TrialConditions& c,
                                     double duration_s, double dt_out_s);
// One trial of the tables: (rudder, r0) from eq. 3, n rows every step_s [s] (a multiple of c.dt).
std::vector<TableRow> turning_trial(ShipModel& model, double rudder, double r0, const TrialConditions& c,
                                    double step_s, int n);
// The CSV read by opp::load_turning_tables (header comments name units and order; `notes` are
// written as further '#' lines: model, approach speed, ...).
void write_tables_csv(std::ostream& out, const std::vector<TableRow>& rows, const std::vector<std::string>& notes = {});

}  // namespace mpgc::ship_simulator
