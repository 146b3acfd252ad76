// mpgc_trial: manoeuvring trials of the own-ship model (./mpgc trial ...). Prints one JSON object.
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "mpgc/geo/angles.hpp"
#include "mpgc/json/json.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/trials.hpp"

namespace sim = mpgc::ship_simulator;
namespace geo = mpgc::geo;

namespace {

std::vector<double> parse_list(const std::string& text, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(cell, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || !std::isfinite(v)) throw std::invalid_argument(what + ": '" + cell + "' is not a number");
    out.push_back(v);
  }
  if (out.empty()) throw std::invalid_argument(what + ": empty list");
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mpgc trial: manoeuvring trials of the own-ship model (prints JSON)"};
  sim::ModelChoice choice;
  double speed_kn = 0.0, dt = 0.1;
  app.add_option("--model", choice.kind, "ship model: mmg | nomoto")->check(CLI::IsMember({"mmg", "nomoto"}));
  app.add_option("--data-dir", choice.data_dir, "folder with kvlcc2_mmg_parameters.csv and nomoto_kt.csv");
  app.add_option("--speed-kn", speed_kn, "approach speed [kn] (default: the model's service speed, 15.5 kn)");
  app.add_option("--dt", dt, "integration step [s]")->check(CLI::Range(0.001, 5.0));
  app.require_subcommand(1);

  auto* tc = app.add_subcommand("turning-circle", "turning circle with the rudder hard over");
  double tc_rudder = 35.0;
  std::string tc_side = "starboard";
  tc->add_option("--rudder-deg", tc_rudder, "rudder angle [deg]")->check(CLI::Range(1.0, 35.0));
  tc->add_option("--side", tc_side, "starboard | port")->check(CLI::IsMember({"starboard", "port"}));

  auto* zz = app.add_subcommand("zigzag", "zig-zag test angle/angle");
  double zz_angle = 10.0;
  std::string zz_side = "starboard";
  zz->add_option("--angle-deg", zz_angle, "rudder angle and heading-change trigger [deg]")->check(CLI::Range(1.0, 35.0));
  zz->add_option("--side", zz_side, "side of the first rudder order: starboard | port")
      ->check(CLI::IsMember({"starboard", "port"}));

  auto* tb = app.add_subcommand("table", "turning-circle tables of seed 002 §2 as CSV");
  std::string out_path, rudders_text = "-35,-25,-15,-5,5,15,25,35", r0_text = "-0.3,0,0.3";
  double duration = 600.0, dt_out = 10.0;
  tb->add_option("--out", out_path, "output CSV file")->required();
  tb->add_option("--rudders-deg", rudders_text, "comma-separated rudder angles [deg], + starboard");
  tb->add_option("--r0-deg-s", r0_text, "comma-separated initial yaw rates [deg/s]");
  tb->add_option("--duration", duration, "length of each trial [s]");
  tb->add_option("--dt-out", dt_out, "recording interval [s]");

  CLI11_PARSE(app, argc, argv);
  try {
    auto model = sim::make_model(choice);
    sim::TrialConditions c;
    c.dt = dt;
    c.approach_speed = speed_kn > 0.0 ? speed_kn * geo::kKnot : 7.97;
    c.rpm = sim::straight_rpm(*model, c.approach_speed);
    using mpgc::json::number;
    mpgc::json::Json js;  // one line; a figure the trial could not measure is null
    js["model"] = model->name();
    js["approach_speed_m_s"] = number(c.approach_speed);
    js["rpm"] = number(c.rpm);
    js["dt_s"] = number(c.dt);
    if (*tc) {
      const double side = tc_side == "starboard" ? 1.0 : -1.0;
      const auto r = sim::turning_circle(*model, side * geo::deg2rad(tc_rudder), c);
      js["trial"] = "turning-circle";
      js["side"] = tc_side;
      js["rudder_deg"] = number(tc_rudder);
      js["advance_m"] = number(r.advance_m);
      js["transfer_m"] = number(r.transfer_m);
      js["tactical_diameter_m"] = number(r.tactical_diameter_m);
      js["steady_diameter_m"] = number(r.steady_diameter_m);
      js["speed_ratio_steady"] = number(r.speed_ratio_steady);
      js["time_to_90_s"] = number(r.time_to_90_s);
      js["time_to_180_s"] = number(r.time_to_180_s);
      js["steady_rate_deg_s"] = number(r.steady_rate_deg_s);
      js["length_m"] = number(model->length());
    } else if (*zz) {
      const int side = zz_side == "starboard" ? 1 : -1;
      const auto r = sim::zigzag(*model, geo::deg2rad(zz_angle), side, c, 3);
      js["trial"] = "zigzag";
      js["side"] = zz_side;
      js["angle_deg"] = number(zz_angle);
      js["first_overshoot_deg"] = number(r.overshoots_deg.at(0));
      js["second_overshoot_deg"] = number(r.overshoots_deg.at(1));
      js["third_overshoot_deg"] = number(r.overshoots_deg.at(2));
      js["reversal_times_s"] = mpgc::json::Json::array();
      for (const double t : r.reversal_times_s) js["reversal_times_s"].push_back(number(t));
    } else {
      std::vector<double> rud = parse_list(rudders_text, "--rudders-deg"), r0 = parse_list(r0_text, "--r0-deg-s");
      for (double& d : rud) d = geo::deg2rad(d);
      for (double& d : r0) d = geo::deg2rad(d);
      const auto rows = sim::turning_tables(*model, rud, r0, c, duration, dt_out);
      std::ofstream out(out_path);
      if (!out) throw std::runtime_error("cannot write '" + out_path + "'");
      sim::write_tables_csv(out, rows);
      if (!out) throw std::runtime_error("write to '" + out_path + "' failed");
      js["trial"] = "table";
      js["out"] = out_path;
      js["rows"] = rows.size();
      js["trials"] = rud.size() * r0.size();
    }
    std::cout << js.dump() << std::endl;
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "mpgc trial: " << e.what() << "\n";
    return 1;
  }
}
