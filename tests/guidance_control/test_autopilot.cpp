// Heading autopilot and speed controller: step responses on the first-order Nomoto plant (Mariner
// K, T from nomoto_kt.csv), anti-windup, limits, pole-placement tuning.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "mpgc/geo/angles.hpp"
#include "mpgc/guidance_control/autopilot.hpp"
#include "nomoto_plant.hpp"

namespace gc = mpgc::guidance_control;
using mpgc::geo::deg2rad;
using mpgc::geo::rad2deg;

namespace {

struct StepResult {
  double overshoot_pct = 0.0;  // [%] of the step
  double settling_s = -1.0;    // [s] last time |error| left the 2 % band (or 0.5 deg, whichever is larger)
  double late_peak_deg = 0.0;  // [deg] largest |error| in the last quarter of the run
  double late_rudder_deg = 0.0;  // [deg] largest |rudder| change in the last quarter
  double max_rudder_deg = 0.0;
  double max_rate_deg = 0.0;   // [deg/s] largest commanded rudder rate
};

StepResult heading_step(const gc::HeadingAutopilotParams& ap, gc::test::NomotoPlant plant, double step_rad,
                        double duration, double dt = 0.5) {
  gc::HeadingAutopilot pilot(ap);
  pilot.reset(0.0);
  StepResult res;
  const double band = std::max(0.02 * std::abs(step_rad), deg2rad(0.5));
  double last_cmd = 0.0, late_min_rudder = 1e9, late_max_rudder = -1e9;
  const int n = static_cast<int>(duration / dt);
  for (int i = 0; i < n; ++i) {
    const double t = i * dt;
    const double cmd = pilot.update(step_rad, plant.psi, plant.r, dt);
    res.max_rudder_deg = std::max(res.max_rudder_deg, std::abs(rad2deg(cmd)));
    if (i > 0) res.max_rate_deg = std::max(res.max_rate_deg, std::abs(rad2deg(cmd - last_cmd)) / dt);
    last_cmd = cmd;
    plant.step(dt, cmd, plant.rpm);
    const double err = step_rad - plant.psi;
    res.overshoot_pct = std::max(res.overshoot_pct, -err / step_rad * 100.0);
    if (std::abs(err) > band) res.settling_s = t + dt;
    if (t > 0.75 * duration) {
      res.late_peak_deg = std::max(res.late_peak_deg, std::abs(rad2deg(err)));
      late_min_rudder = std::min(late_min_rudder, cmd);
      late_max_rudder = std::max(late_max_rudder, cmd);
    }
  }
  res.late_rudder_deg = rad2deg(late_max_rudder - late_min_rudder);
  return res;
}

gc::test::NomotoPlant mariner_plant() {
  const auto row = gc::test::read_nomoto("Mariner");
  gc::test::NomotoPlant p;
  p.K = row.K;
  p.T = row.T;
  p.u = row.U;
  return p;
}

}  // namespace

TEST(PoleplacementTuning, MatchesClosedForm) {
  const gc::NomotoModel m{0.185, 107.3};
  const auto p = gc::tune_heading_pid(m, 0.05, 0.8);
  EXPECT_NEAR(p.kp, 107.3 * 0.0025 / 0.185, 1e-12);
  EXPECT_NEAR(p.kd, (2 * 0.8 * 0.05 * 107.3 - 1) / 0.185, 1e-12);
  EXPECT_NEAR(p.ki, 0.05 * p.kp / 10.0, 1e-12);
  EXPECT_THROW(gc::tune_heading_pid({0.0, 100.0}, 0.05, 0.8), std::invalid_argument);
  EXPECT_THROW(gc::tune_heading_pid({0.1, 100.0}, 0.001, 0.8), std::invalid_argument);  // kd < 0
  EXPECT_THROW(gc::tune_heading_pid({0.1, std::nan("")}, 0.05, 0.8), std::invalid_argument);
}

TEST(HeadingAutopilot, StepResponseOnMarinerNomoto) {
  auto plant = mariner_plant();
  const auto ap = gc::tune_heading_pid({plant.K, plant.T}, 0.05, 0.9);
  for (double step_deg : {10.0, 30.0}) {
    const auto r = heading_step(ap, plant, deg2rad(step_deg), 1200.0);
    std::printf("[figure] Mariner Nomoto K=%.3f T=%.1f, PID wn=0.05 zeta=0.9 (kp=%.2f kd=%.1f ki=%.4f): "
                "%.0f deg step: overshoot %.1f %%, settling (2 %%/0.5 deg) %.0f s, max rudder %.1f deg, "
                "max rate %.2f deg/s\n",
                plant.K, plant.T, ap.kp, ap.kd, ap.ki, step_deg, r.overshoot_pct, r.settling_s, r.max_rudder_deg,
                r.max_rate_deg);
    EXPECT_LT(r.overshoot_pct, 15.0) << step_deg;
    EXPECT_GT(r.settling_s, 0.0);
    EXPECT_LT(r.settling_s, 600.0) << step_deg;
    // No sustained oscillation: in the last quarter the heading is within 0.2 deg and the rudder still.
    EXPECT_LT(r.late_peak_deg, 0.2) << step_deg;
    EXPECT_LT(r.late_rudder_deg, 0.2) << step_deg;
    EXPECT_LE(r.max_rudder_deg, rad2deg(ap.max_rudder) + 1e-9);      // the ship's limits (35 deg,
    EXPECT_LE(r.max_rate_deg, rad2deg(ap.max_rudder_rate) + 1e-6);   // 2.32 deg/s) are never exceeded
  }
}

TEST(HeadingAutopilot, AntiWindupBoundsOvershootOfLargeSaturatingStep) {
  auto plant = mariner_plant();
  auto ap = gc::tune_heading_pid({plant.K, plant.T}, 0.05, 0.9);
  ap.integral_limit = ap.max_rudder;  // let the integral grow as far as it likes
  const auto r = heading_step(ap, plant, deg2rad(120.0), 1500.0);
  std::printf("[figure] Mariner 120 deg step (saturating): overshoot %.1f %%, settling %.0f s\n", r.overshoot_pct,
              r.settling_s);
  EXPECT_LT(r.overshoot_pct, 10.0);
  EXPECT_LT(r.late_peak_deg, 0.2);
}

TEST(HeadingAutopilot, LimitsSignsAndBadInput) {
  gc::HeadingAutopilotParams p;
  gc::HeadingAutopilot a(p);
  a.reset(0.0);
  // Desired heading to starboard -> positive (starboard) rudder, limited by the rate.
  const double d1 = a.update(deg2rad(20), 0.0, 0.0, 1.0);
  EXPECT_GT(d1, 0.0);
  EXPECT_NEAR(d1, p.max_rudder_rate * 1.0, 1e-12);
  for (int i = 0; i < 100; ++i) a.update(deg2rad(90), 0.0, 0.0, 1.0);
  EXPECT_NEAR(a.update(deg2rad(90), 0.0, 0.0, 1.0), p.max_rudder, 1e-12);
  // Wrap: desired 179 deg, heading -179 deg is a 2 deg error to port.
  gc::HeadingAutopilot b(p);
  EXPECT_LT(b.update(deg2rad(179), deg2rad(-179), 0.0, 0.1), 0.0);
  // Turning to starboard with no heading error -> counter rudder (derivative on yaw rate).
  gc::HeadingAutopilot c(p);
  EXPECT_LT(c.update(0.0, 0.0, 0.01, 0.1), 0.0);
  EXPECT_THROW(c.update(std::nan(""), 0.0, 0.0, 0.1), std::invalid_argument);
  EXPECT_THROW(c.update(0.0, 0.0, 0.0, -1.0), std::invalid_argument);
  gc::HeadingAutopilotParams bad;
  bad.max_rudder_rate = 0.0;
  EXPECT_THROW(gc::HeadingAutopilot{bad}, std::invalid_argument);
}

TEST(SpeedController, FeedforwardAndPiReachTheSpeed) {
  gc::SpeedControllerParams sp;
  gc::SpeedController s(sp);
  EXPECT_NEAR(s.feedforward(4.0), 52.7, 1e-9);
  EXPECT_NEAR(s.feedforward(9.0), 118.575, 1e-9);  // linear extrapolation
  // Plant whose calm-water rpm map is 10 % off the controller's: the PI removes the offset.
  gc::test::NomotoPlant plant;
  plant.rpm_per_mps = 1.1 * 13.175;
  plant.u = 3.0;
  s.reset(3.0 * 13.175);
  const double dt = 1.0;
  double max_u = 0.0;
  for (int i = 0; i < 3000; ++i) {
    const double n = s.update(6.0, plant.u, dt);
    EXPECT_LE(n, sp.max_rpm);
    EXPECT_GE(n, sp.min_rpm);
    plant.step(dt, 0.0, n);
    max_u = std::max(max_u, plant.u);
  }
  std::printf("[figure] speed 3 -> 6 m/s with a 10 %% map error: final %.3f m/s, peak %.3f m/s\n", plant.u, max_u);
  EXPECT_NEAR(plant.u, 6.0, 0.05);
  EXPECT_LT(max_u, 6.0 * 1.05);
  gc::SpeedControllerParams bad;
  bad.map_speed = {0.0, 0.0};
  EXPECT_THROW(gc::SpeedController{bad}, std::invalid_argument);
  bad = {};
  bad.map_rpm = {0.0};
  EXPECT_THROW(gc::SpeedController{bad}, std::invalid_argument);
}
