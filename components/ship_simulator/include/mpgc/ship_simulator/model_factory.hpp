// Builds the own-ship model by name from the shared data files.
#pragma once

#include <memory>
#include <string>

#include "mpgc/ship_simulator/ship_model.hpp"

namespace mpgc::ship_simulator {

struct ModelChoice {
  std::string kind = "mmg";            // mmg | nomoto
  std::string data_dir;                // [-] folder with kvlcc2_mmg_parameters.csv and nomoto_kt.csv
  std::string nomoto_ship = "Mariner"; // row of nomoto_kt.csv to scale from
  double length = 0.0;                 // [m] nomoto only: hull length; 0 = KVLCC2 (320 m)
  double beam = 0.0;                   // [m] nomoto only: beam; 0 = KVLCC2's, scaled with the length
};

// "mmg": KVLCC2 full scale from kvlcc2_mmg_parameters.csv. "nomoto": KVLCC2 size and actuators,
// K and T scaled from the chosen nomoto_kt.csv row (K' and T' kept), speed proportional to rpm
// with the MMG model's self-propulsion point, so one rpm gives the same straight speed in both.
// A "nomoto" ship of another `length` keeps K', T' (K = K'U/L, T = T'L/U), the actuators and the
// rpm-speed relation, and scales the surge lag with L (same speed: time scale L/U).
// Throws std::invalid_argument (unknown kind) or std::runtime_error (file problems).
std::unique_ptr<ShipModel> make_model(const ModelChoice& choice);

// Propeller speed [1/min] for which `model` runs straight at speed u [m/s] (found by a 2000 s
// straight run for models without an analytic answer; exact for MMG).
double straight_rpm(const ShipModel& model, double u);

// $MPGC_SHARED_DATA/ship_models, or ../shared/data/ship_models from the working directory.
std::string default_ship_data_dir();

}  // namespace mpgc::ship_simulator
