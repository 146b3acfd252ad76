// mpgc_trial: manoeuvring trials of the own-ship model (./mpgc trial ...). Prints one JSON object.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>

#include "mpgc/geo/angles.hpp"
#include "mpgc/json/json.hpp"
#include "mpgc/opp/turning_tables.hpp"
#include "mpgc/ship_simulator/model_factory.hpp"
#include "mpgc/ship_simulator/trials.hpp"

namespace sim = mpgc::ship_simulator;
namespace geo = mpgc::geo;
namespace opp = mpgc::opp;

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
  // The own ship of a world file (own_ship: model, nomoto_ship, length_m, beam_m), so mpgc_run can
  // make a scenario's own tables for dijkstra-sv.
  app.add_option("--nomoto-ship", choice.nomoto_ship, "nomoto only: the row of nomoto_kt.csv to scale from");
  app.add_option("--length-m", choice.length, "nomoto only: hull length [m] (default: the KVLCC2's)")
      ->check(CLI::Range(10.0, 500.0));
  app.add_option("--beam-m", choice.beam, "nomoto only: beam [m] (default: scaled with the length)")
      ->check(CLI::Range(1.0, 100.0));
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

  auto* tb = app.add_subcommand("table", "turning-circle tables of seed 002 §2 as CSV (alias: tables)");
  tb->alias("tables");
  // Defaults: both grids through 0 (§2), fine enough for Fig. 3's interpolation to stay within 10 %
  // of the node spread in the median case (table-check; tests/opp/test_turning_tables.cpp).
  std::string out_path, rudders_text, r0_text = "-0.4,-0.3,-0.2,-0.1,0,0.1,0.2,0.3,0.4";
  {
    std::ostringstream o;
    for (int i = -14; i <= 14; ++i) o << (i > -14 ? "," : "") << 2.5 * i;  // -35, -32.5, ... 35
    rudders_text = o.str();
  }
  double duration = 300.0, dt_out = 10.0;
  tb->add_option("--out", out_path, "output CSV file")->required();
  tb->add_option("--rudders-deg", rudders_text, "comma-separated rudder angles [deg], + starboard");
  tb->add_option("--r0-deg-s", r0_text, "comma-separated initial yaw rates [deg/s]");
  tb->add_option("--duration", duration, "length of each trial [s]");
  tb->add_option("--dt-out", dt_out, "recording interval [s]");

  auto* ck = app.add_subcommand("table-check",
                                "seed 002 §2 accuracy check of a table file against this model (prints JSON)");
  std::string ck_path;
  opp::AccuracyParams ck_params;
  ck->add_option("--tables", ck_path, "CSV written by 'trial table' with the same --model and --speed-kn")->required();
  ck->add_option("--cases", ck_params.cases, "random starting conditions and rudder settings");
  ck->add_option("--seed", ck_params.seed, "random seed");

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
    } else if (*ck) {
      const auto tables = opp::load_turning_tables_file(ck_path);
      if (std::abs(tables.approach_speed() - c.approach_speed) > 1e-6 * c.approach_speed)
        throw std::invalid_argument(ck_path + ": tables made at " + std::to_string(tables.approach_speed()) +
                                    " m/s, this check at " + std::to_string(c.approach_speed) + " m/s (--speed-kn)");
      const opp::TrialFn truth = [&](double r0, double rudder, double step, int n) {
        std::vector<opp::StateVector> out;
        for (const auto& q : sim::turning_trial(*model, rudder, r0, c, step, n))
          out.push_back({q.x, q.y, q.psi, q.r, q.u, q.v});
        return out;
      };
      const auto rep = opp::check_accuracy(tables, truth, ck_params);
      js["trial"] = "table-check";
      js["tables"] = ck_path;
      js["cases"] = ck_params.cases;
      js["seed"] = ck_params.seed;
      js["fig3_max_pct"] = number(opp::max_of(rep.fig3_pct));
      js["fig3_median_pct"] = number(opp::median_of(rep.fig3_pct));
      js["fig3_worst"] = rep.fig3_worst;
      js["eq4_located"] = rep.eq4_pct.size();
      js["eq4_other_rudder"] = rep.eq4_other_rudder;
      js["eq4_max_pct"] = number(opp::max_of(rep.eq4_pct));
      js["eq4_median_pct"] = number(opp::median_of(rep.eq4_pct));
      js["eq4_worst"] = rep.eq4_worst;
      auto within = [](const std::vector<double>& v) {
        return static_cast<long>(std::count_if(v.begin(), v.end(), [](double e) { return e <= 10.0; }));
      };
      for (const auto& [name, v] : rep.fig3_by_param) js["fig3_median_pct_by_param"][name] = number(opp::median_of(v));
      for (const auto& [name, v] : rep.eq4_by_param) js["eq4_median_pct_by_param"][name] = number(opp::median_of(v));
      js["inverse_bilinear_located"] = rep.inv_pct.size();
      js["inverse_bilinear_max_pct"] = number(opp::max_of(rep.inv_pct));
      js["inverse_bilinear_median_pct"] = number(opp::median_of(rep.inv_pct));
      for (const auto& [name, v] : rep.inv_by_param)
        js["inverse_bilinear_median_pct_by_param"][name] = number(opp::median_of(v));
      js["fig3_cases_within_10pct"] = within(rep.fig3_pct);
      js["eq4_cases_within_10pct"] = within(rep.eq4_pct);
      js["inverse_bilinear_cases_within_10pct"] = within(rep.inv_pct);
    } else {
      std::vector<double> rud = parse_list(rudders_text, "--rudders-deg"), r0 = parse_list(r0_text, "--r0-deg-s");
      for (double& d : rud) d = geo::deg2rad(d);
      for (double& d : r0) d = geo::deg2rad(d);
      const auto rows = sim::turning_tables(*model, rud, r0, c, duration, dt_out);
      std::ofstream out(out_path);
      if (!out) throw std::runtime_error("cannot write '" + out_path + "'");
      std::ostringstream note;
      note.precision(10);
      note << "model " << model->name() << ", approach speed " << c.approach_speed << " m/s, rpm " << c.rpm
           << ", integration dt " << c.dt << " s, dt_out " << dt_out << " s, duration " << duration << " s";
      sim::write_tables_csv(out, rows, {note.str()});
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
