#include "mpgc/ship_simulator/trials.hpp"

#include <cmath>
#include <iomanip>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::ship_simulator {
namespace {

void start_straight(ShipModel& model, const TrialConditions& c) {
  ShipState s;
  s.u = c.approach_speed;
  s.rpm = c.rpm;
  model.set_state(s);
}

}  // namespace

void TrialConditions::validate() const {
  if (!(approach_speed > 0.0) || !std::isfinite(approach_speed))
    throw std::invalid_argument("TrialConditions.approach_speed must be > 0");
  if (!(rpm >= 0.0) || !std::isfinite(rpm)) throw std::invalid_argument("TrialConditions.rpm must be >= 0");
  if (!(dt > 0.0) || dt > 5.0) throw std::invalid_argument("TrialConditions.dt must be in (0, 5] s");
}

TurningCircleResult turning_circle(ShipModel& model, double rudder, const TrialConditions& c, double max_time_s) {
  c.validate();
  if (!std::isfinite(rudder) || rudder == 0.0) throw std::invalid_argument("turning_circle: rudder must be finite and non-zero");
  const double side = rudder > 0.0 ? 1.0 : -1.0;
  start_straight(model, c);
  const ShipCommand cmd{rudder, c.rpm};
  TurningCircleResult res{};
  res.rudder_deg = geo::rad2deg(rudder);
  bool got90 = false, got180 = false;
  double sumU = 0.0, sumR = 0.0;
  long n = 0;
  ShipState prev = model.state();
  double t = 0.0;
  while (true) {
    model.step(c.dt, cmd);
    t += c.dt;
    const ShipState& s = model.state();
    const double dpsi = side * s.psi, dpsi_prev = side * prev.psi;
    auto interp = [&](double target, double a, double b) {
      const double w = (target - dpsi_prev) / (dpsi - dpsi_prev);
      return a + w * (b - a);
    };
    if (!got90 && dpsi >= geo::kPi / 2) {
      const double th = geo::kPi / 2;
      res.advance_m = interp(th, prev.x, s.x);
      res.transfer_m = side * interp(th, prev.y, s.y);
      res.time_to_90_s = interp(th, t - c.dt, t);
      got90 = true;
    }
    if (!got180 && dpsi >= geo::kPi) {
      res.tactical_diameter_m = side * interp(geo::kPi, prev.y, s.y);
      res.time_to_180_s = interp(geo::kPi, t - c.dt, t);
      got180 = true;
    }
    if (dpsi >= 2 * geo::kPi) {  // steady turn: average over the second full circle
      sumU += std::hypot(s.u, s.v);
      sumR += std::abs(s.r);
      ++n;
    }
    if (dpsi >= 4 * geo::kPi) break;
    if (t > max_time_s) {
      if (!got180) throw std::runtime_error("turning_circle: heading change of 180 deg not reached in time");
      break;  // a very slow turn: take what the last part gives
    }
    prev = s;
  }
  if (n == 0) throw std::runtime_error("turning_circle: no steady turn reached within max_time_s");
  const double U = sumU / static_cast<double>(n), r = sumR / static_cast<double>(n);
  res.steady_diameter_m = 2.0 * U / r;
  res.speed_ratio_steady = U / c.approach_speed;
  res.steady_rate_deg_s = geo::rad2deg(r);
  return res;
}

ZigzagResult zigzag(ShipModel& model, double angle, int first_side, const TrialConditions& c, int n_overshoots,
                    double max_time_s) {
  c.validate();
  if (!(angle > 0.0) || angle > model.max_rudder() + 1e-12)
    throw std::invalid_argument("zigzag: angle must be in (0, max_rudder]");
  if (first_side != 1 && first_side != -1) throw std::invalid_argument("zigzag: first_side must be +1 or -1");
  if (n_overshoots < 1 || n_overshoots > 10) throw std::invalid_argument("zigzag: n_overshoots must be in 1..10");
  start_straight(model, c);
  ZigzagResult res{geo::rad2deg(angle), first_side, {}, {}};
  double side = first_side;  // sign of the rudder now ordered
  int reversals = 0;
  double peak = 0.0;  // extreme of prev_side * psi since the last reversal
  double t = 0.0;
  while (static_cast<int>(res.overshoots_deg.size()) < n_overshoots) {
    model.step(c.dt, ShipCommand{side * angle, c.rpm});
    t += c.dt;
    if (t > max_time_s) throw std::runtime_error("zigzag: not completed within max_time_s");
    const double psi = model.state().psi;
    if (reversals > 0) peak = std::max(peak, -side * psi);  // heading still swinging the old way
    if (side * psi >= angle) {
      if (reversals > 0) res.overshoots_deg.push_back(geo::rad2deg(peak - angle));
      side = -side;
      ++reversals;
      res.reversal_times_s.push_back(t);
      peak = -side * psi;
    }
  }
  return res;
}

std::vector<TableRow> turning_trial(ShipModel& model, double rudder, double r0, const TrialConditions& c,
                                    double step_s, int n) {
  c.validate();
  if (!std::isfinite(rudder) || std::abs(rudder) > model.max_rudder() + 1e-12)
    throw std::invalid_argument("turning_tables: rudder angle outside the rudder limit");
  if (!std::isfinite(r0) || std::abs(r0) > 0.1) throw std::invalid_argument("turning_tables: |r0| must be <= 0.1 rad/s");
  if (!(step_s >= c.dt) || !std::isfinite(step_s)) throw std::invalid_argument("turning_tables: dt_out must be >= dt");
  const long per_out = std::lround(step_s / c.dt);
  if (std::abs(per_out * c.dt - step_s) > 1e-9 * step_s)
    throw std::invalid_argument("turning_tables: dt_out must be a multiple of dt");
  if (n < 1 || n > 1000000) throw std::invalid_argument("turning_trial: n must be in 1..1e6");
  ShipState s;
  s.u = c.approach_speed;
  s.r = r0;
  s.rpm = c.rpm;
  model.set_state(s);
  std::vector<TableRow> rows;
  rows.reserve(static_cast<std::size_t>(n));
  auto record = [&](double t) {
    const ShipState& q = model.state();
    rows.push_back({geo::rad2deg(rudder), geo::rad2deg(r0), t, q.x, q.y, q.psi, q.r, q.u, q.v});
  };
  record(0.0);
  for (long k = 1; static_cast<long>(rows.size()) < n; ++k) {
    model.step(c.dt, ShipCommand{rudder, c.rpm});
    if (k % per_out == 0) record(static_cast<double>(k) * c.dt);
  }
  return rows;
}

std::vector<TableRow> turning_tables(ShipModel& model, const std::vector<double>& rudders,
                                     const std::vector<double>& r0s, const TrialConditions& c, double duration_s,
                                     double dt_out_s) {
  c.validate();
  if (rudders.empty() || r0s.empty()) throw std::invalid_argument("turning_tables: empty rudder or r0 grid");
  if (rudders.size() * r0s.size() > 10000) throw std::invalid_argument("turning_tables: grid larger than 10000 trials");
  if (!(duration_s > 0.0) || duration_s > 36000.0) throw std::invalid_argument("turning_tables: duration must be in (0, 36000] s");
  if (!(dt_out_s >= c.dt) || !std::isfinite(dt_out_s)) throw std::invalid_argument("turning_tables: dt_out must be >= dt");
  const long n = std::lround(std::floor(duration_s / dt_out_s + 1e-9)) + 1;
  std::vector<TableRow> rows;
  for (double d : rudders)
    for (double r0 : r0s) {
      const auto trial = turning_trial(model, d, r0, c, dt_out_s, static_cast<int>(n));
      rows.insert(rows.end(), trial.begin(), trial.end());
    }
  return rows;
}

void write_tables_csv(std::ostream& out, const std::vector<TableRow>& rows, const std::vector<std::string>& notes) {
  out << "# turning-circle tables (seed 002 eq. 1): state [x, y, psi, r, u, v] per trial; NED, psi clockwise\n";
  out << "# one block per trial, ordered by rudder then r0 (ascending), rows every dt_out from t = 0;\n";
  out << "# eq. 3 start: x = y = psi = v = 0, r = r0, u = approach speed, rudder 0 then put over (rate-limited)\n";
  out << "# units: rudder [deg, + starboard], r0 [deg/s], t [s], x north [m], y east [m], psi [rad, unwrapped],\n";
  out << "#        r [rad/s, + starboard], u surge [m/s], v sway [m/s, + starboard]\n";
  for (const auto& n : notes) out << "# " << n << "\n";
  out << "rudder_deg,r0_deg_s,t_s,x_m,y_m,psi_rad,r_rad_s,u_m_s,v_m_s\n";
  out << std::setprecision(10);
  for (const auto& r : rows)
    out << r.rudder_deg << ',' << r.r0_deg_s << ',' << r.t_s << ',' << r.x << ',' << r.y << ',' << r.psi << ','
        << r.r << ',' << r.u << ',' << r.v << '\n';
}

}  // namespace mpgc::ship_simulator
