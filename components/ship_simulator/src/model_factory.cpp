#include "mpgc/ship_simulator/model_factory.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "mpgc/ship_simulator/mmg_model.hpp"
#include "mpgc/ship_simulator/nomoto_model.hpp"

namespace mpgc::ship_simulator {

std::string default_ship_data_dir() {
  if (const char* d = std::getenv("MPGC_SHARED_DATA")) return std::string(d) + "/ship_models";
  return "../shared/data/ship_models";
}

std::unique_ptr<ShipModel> make_model(const ModelChoice& choice) {
  const std::string dir = choice.data_dir.empty() ? default_ship_data_dir() : choice.data_dir;
  const MmgParams mp = load_kvlcc2_csv(dir + "/kvlcc2_mmg_parameters.csv");
  if (choice.kind == "mmg") {
    if (choice.length > 0.0 || choice.beam > 0.0)
      throw std::invalid_argument("the mmg model is the KVLCC2 at full scale: length and beam are for nomoto only");
    return std::make_unique<MmgModel>(mp);
  }
  if (choice.kind == "nomoto") {
    NomotoParams np = load_nomoto_csv(dir + "/nomoto_kt.csv", choice.nomoto_ship, mp.service_speed);
    if (choice.length < 0.0 || choice.beam < 0.0 || !std::isfinite(choice.length) || !std::isfinite(choice.beam))
      throw std::invalid_argument("nomoto length and beam must be finite and >= 0");
    np.L = choice.length > 0.0 ? choice.length : mp.L;
    np.B = choice.beam > 0.0 ? choice.beam : mp.B * np.L / mp.L;
    np.service_speed = mp.service_speed;
    np.service_rpm = MmgModel(mp).self_propulsion_rpm(mp.service_speed);
    // Surge lag (m + m_x) / (dR/du) of the KVLCC2 at 15.5 kn, rounded.
    np.speed_time_constant = 300.0 * np.L / mp.L;
    np.max_rudder = mp.max_rudder;
    np.rudder_rate = mp.rudder_rate;
    np.rudder_servo_t = mp.rudder_servo_t;
    np.rpm_time_constant = mp.rpm_time_constant;
    np.max_rpm = mp.max_rpm;
    return std::make_unique<NomotoModel>(np);
  }
  throw std::invalid_argument("unknown ship model '" + choice.kind + "' (expected mmg or nomoto)");
}

double straight_rpm(const ShipModel& model, double u) {
  if (const auto* m = dynamic_cast<const MmgModel*>(&model)) return m->self_propulsion_rpm(u);
  if (const auto* n = dynamic_cast<const NomotoModel*>(&model))
    return u / n->params().service_speed * n->params().service_rpm;
  throw std::invalid_argument("straight_rpm: unknown model type " + model.name());
}

}  // namespace mpgc::ship_simulator
