// MMG standard method (Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol. 20:37-52) for a single-
// screw, single-rudder ship: hull + propeller + rudder forces in midship-fixed axes.
#pragma once

#include <string>

#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::ship_simulator {

// Coefficients of the MMG standard method. Primed values are non-dimensional as in the paper
// (forces by 0.5 rho L d U^2, moments by 0.5 rho L^2 d U^2, masses by 0.5 rho L^2 d, inertia by
// 0.5 rho L^4 d).
struct MmgParams {
  double rho = 1025.0;     // [kg/m^3] sea water density
  double L = 0.0;          // [m] Lpp
  double B = 0.0;          // [m] breadth
  double d = 0.0;          // [m] draught
  double nabla = 0.0;      // [m^3] displacement volume
  double x_G = 0.0;        // [m] centre of gravity from midship, forward positive
  double D_p = 0.0;        // [m] propeller diameter
  double H_R = 0.0;        // [m] rudder span
  double A_R = 0.0;        // [m^2] rudder area
  double m_x = 0.0, m_y = 0.0, J_z = 0.0;  // [-] added masses and inertia (primed)
  double R_0 = 0.0;        // [-] resistance coefficient in straight motion
  double X_vv = 0.0, X_vr = 0.0, X_rr = 0.0, X_vvvv = 0.0;                            // [-]
  double Y_v = 0.0, Y_r = 0.0, Y_vvv = 0.0, Y_vvr = 0.0, Y_vrr = 0.0, Y_rrr = 0.0;    // [-]
  double N_v = 0.0, N_r = 0.0, N_vvv = 0.0, N_vvr = 0.0, N_vrr = 0.0, N_rrr = 0.0;    // [-]
  double t_P = 0.0;        // [-] thrust deduction
  double w_P0 = 0.0;       // [-] wake fraction in straight motion
  double k_0 = 0.0, k_1 = 0.0, k_2 = 0.0;  // [-] K_T(J) = k0 + k1 J + k2 J^2
  double x_P = 0.0;        // [-] propeller position / L
  double C_1 = 0.0;        // [-] wake change in manoeuvring
  double C_2_pos = 0.0;    // [-] C_2 for beta_P > 0
  double C_2_neg = 0.0;    // [-] C_2 for beta_P <= 0
  double t_R = 0.0;        // [-] steering resistance deduction
  double a_H = 0.0;        // [-] rudder force increase factor
  double x_H = 0.0;        // [-] position of the additional lateral force / L
  double x_R = 0.0;        // [-] rudder position / L
  double epsilon = 0.0;    // [-] wake ratio (1-w_R)/(1-w_P)
  double kappa = 0.0;      // [-] constant for u_R
  double l_R = 0.0;        // [-] effective longitudinal rudder coordinate / L
  double gamma_R_neg = 0.0;  // [-] flow straightening, beta_R < 0
  double gamma_R_pos = 0.0;  // [-] flow straightening, beta_R >= 0
  double f_alpha = 0.0;    // [-] rudder lift gradient coefficient
  // Actuators and operating point.
  double max_rudder = 0.0;     // [rad] rudder angle limit
  double rudder_rate = 0.0;    // [rad/s] rudder rate limit
  double rudder_servo_t = 0.0; // [s] rudder servo lag (below the rate limit)
  double rpm_time_constant = 0.0;  // [s] propeller speed lag
  double max_rpm = 0.0;        // [1/min] largest propeller speed
  double service_speed = 0.0;  // [m/s] approach speed U0
  double service_rpm = 0.0;    // [1/min] propeller speed measured at U0 (reference only)
  // Wind (simple Isherwood-type coefficients, only used when wind_speed > 0).
  double rho_air = 1.225;      // [kg/m^3]
  double area_front = 0.0;     // [m^2] projected frontal windage area
  double area_lateral = 0.0;   // [m^2] projected lateral windage area
  double c_wx = 0.7, c_wy = 0.9, c_wn = 0.1;  // [-] wind force and moment coefficients

  // Throws std::invalid_argument naming the first bad field.
  void validate() const;
};

// The KVLCC2 full-scale set read from kvlcc2_mmg_parameters.csv (column value_full_scale).
// Where the three transcriptions differ the CSV's value_full_scale column already holds
// Yasukawa & Yoshimura's published value, and we keep it (see the comment in mmg_model.cpp).
// Throws std::runtime_error naming the file and the missing or malformed symbol.
MmgParams load_kvlcc2_csv(const std::string& path);
// The same set compiled in (checked equal to the CSV in a unit test).
MmgParams kvlcc2_params();

class MmgModel final : public RK4ShipModel {
 public:
  explicit MmgModel(MmgParams p);
  std::string name() const override { return "mmg"; }
  std::array<double, ShipState::kSize> derivative(const ShipState& s, const ShipCommand& cmd) const override;
  double length() const override { return p_.L; }
  double beam() const override { return p_.B; }
  ship::ActuatorLimits actuator_limits() const override { return {p_.max_rudder, p_.rudder_rate, 0.0, p_.max_rpm}; }
  const MmgParams& params() const { return p_; }

  // Forces in midship axes for a state (for tests and the self-propulsion search).
  struct Forces {
    double X_H, Y_H, N_H, X_P, X_R, Y_R, N_R, X_W, Y_W, N_W;  // [N], [N m]
  };
  Forces forces(const ShipState& s) const;
  // Propeller speed [1/min] at which the ship runs straight at speed u [m/s] in calm water
  // (X_H + X_P = 0), by bisection.
  double self_propulsion_rpm(double u) const;

 private:
  MmgParams p_;
  double m_, mx_, my_, Jz_, Izg_;
};

}  // namespace mpgc::ship_simulator
