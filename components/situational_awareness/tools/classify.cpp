// mpgc_classify (./mpgc classify FILE...): COLREG classification, CPA and TCPA of every target of
// DNV ship-traffic-generator situations, next to the desiredEncounterType of the matching input
// file. Ends with one JSON line {"agree":N,"total":M} over the targets that have a desired type.
// --escape NM: also the widest single manoeuvre of each start (colreg::best_escape: one turn on a
// circle of --turn-radius to a course and --escape-speeds held; --escape-starboard: no port
// alteration; --escape-max-turn: none larger) and whether it keeps NM to every target: which starts allow seed 002's 0.7 NM at
// all (issue 18); the JSON adds "escape_allows".
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "mpgc/colreg/colreg.hpp"
#include "mpgc/json/json.hpp"
#include "mpgc/dnv/situation.hpp"

namespace cr = mpgc::colreg;
namespace geo = mpgc::geo;

int main(int argc, char** argv) {
  CLI::App app{"COLREG classification of DNV ship-traffic-generator situations"};
  std::vector<std::string> files;
  std::string settings;
  double d_colreg_nm = std::numeric_limits<double>::infinity();
  double cpa_risk_nm = 0.7;
  double tcpa_max_min = std::numeric_limits<double>::infinity();
  app.add_option("files", files, "generated situation files (traffic_situation_NN.json)")->required();
  app.add_option("--settings", settings,
                 "DNV encounter_settings.json: take the sector angles from it (default: seed 000, "
                 "abaft_beam = head_on_sector = 22.5 deg, DNV aspect tolerances)");
  app.add_option("--d-colreg", d_colreg_nm, "[NM] no risk beyond this range (default: no limit; the DNV "
                                            "situations start up to 8.3 NM apart by design)");
  app.add_option("--cpa-risk", cpa_risk_nm, "[NM] no risk when the CPA is wider (default 0.7 NM, seed 002)");
  app.add_option("--tcpa-max", tcpa_max_min, "[min] no risk when the CPA is later (default: no limit)");
  double escape_nm = std::nan("");
  cr::EscapeParams ep;
  app.add_option("--escape", escape_nm, "[NM] also the widest single manoeuvre from each start, and whether it keeps this "
                                        "distance to every target (e.g. 0.7)")->check(CLI::PositiveNumber);
  app.add_option("--turn-radius", ep.turn_radius, "[m] --escape: the turn's radius (0: instant, the bound from above)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--escape-starboard", ep.starboard_only, "--escape: alterations to starboard only (and speed)");
  double max_turn_deg = 180.0;
  app.add_option("--escape-max-turn", max_turn_deg, "[deg] --escape: no larger alteration (a planner's reach)")
      ->check(CLI::Range(0.0, 180.0));
  app.add_option("--escape-speeds", ep.speed_fractions, "--escape: comma-separated speed fractions tried, each in (0, 1] (default 1)")
      ->delimiter(',')
      ->allow_extra_args(false);
  CLI11_PARSE(app, argc, argv);
  ep.max_alteration = geo::deg2rad(max_turn_deg);
  const bool escape = std::isfinite(escape_nm);
  try {
    ep.validate();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mpgc_classify: %s\n", e.what());
    return 2;
  }

  cr::ColregParams p;
  try {
    if (!settings.empty()) p = cr::ColregParams::from_dnv_settings(settings);
    p.d_colreg = d_colreg_nm * geo::kNauticalMile;
    p.cpa_risk = cpa_risk_nm * geo::kNauticalMile;
    p.tcpa_max = tcpa_max_min * 60.0;
    p.validate();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mpgc_classify: %s\n", e.what());
    return 2;
  }
  std::printf("# sectors: abaft_beam %.1f deg, head_on_sector %.1f deg, overtake aspect %.1f deg, crossing aspect %.1f deg; "
              "risk: d_colreg %.1f NM, cpa %.2f NM, tcpa %.1f min\n",
              geo::rad2deg(p.abaft_beam), geo::rad2deg(p.head_on_sector), geo::rad2deg(p.overtake_aspect),
              geo::rad2deg(p.crossing_aspect), d_colreg_nm, cpa_risk_nm, tcpa_max_min);

  int agree = 0, total = 0, failed = 0, allows = 0, starts = 0;
  for (const std::string& f : files) {
    try {
      mpgc::dnv::Situation s = mpgc::dnv::read_situation(f);
      if (s.desired.empty()) {
        const std::string in = mpgc::dnv::find_input(f);
        if (!in.empty()) s.desired = mpgc::dnv::read_desired(in);
      }
      const auto res = mpgc::dnv::assess(s, p);
      for (size_t i = 0; i < res.size(); ++i) {
        const cr::Assessment& a = res[i].assessment;
        const bool has_desired = i < s.desired.size();
        const char* computed = cr::dnv_name(a.type);
        std::string verdict;
        if (has_desired) {
          ++total;
          const bool ok = s.desired[i] == computed;
          agree += ok;
          verdict = std::string(" desired ") + s.desired[i] + (ok ? " [agree]" : " [DIFFER]");
        }
        std::printf("%s \"%s\" target %zu: %s (sector %s) beta %+.1f deg alpha %+.1f deg range %.0f m "
                    "CPA %.1f m TCPA %.2f min%s\n",
                    f.c_str(), s.title.c_str(), i + 1, computed, cr::dnv_name(a.sector), geo::rad2deg(a.beta),
                    geo::rad2deg(a.alpha), a.cpa.range, a.cpa.dcpa, a.cpa.tcpa / 60.0, verdict.c_str());
      }
      if (escape) {
        std::vector<cr::ShipKinematics> tg;
        for (const auto& r : res) tg.push_back(r.target);
        const cr::Escape e = cr::best_escape(res.empty() ? cr::ShipKinematics{} : res.front().own, tg, ep);
        const double keep = escape_nm * geo::kNauticalMile;
        const bool ok = e.min_distance >= keep;
        ++starts;
        allows += ok;
        char turn[64];
        if (e.alteration == 0.0)
          std::snprintf(turn, sizeof turn, "course held");
        else
          std::snprintf(turn, sizeof turn, "%.0f deg to %s", std::fabs(geo::rad2deg(e.alteration)), e.alteration > 0 ? "starboard" : "port");
        std::printf("%s \"%s\" escape: %s at %.0f %% speed keeps %.0f m (target %d): %s %.2f NM\n", f.c_str(),
                    s.title.c_str(), turn,
                    res.empty() || res.front().own.speed() <= 0 ? 100.0 : 100.0 * e.speed / res.front().own.speed(),
                    e.min_distance, e.target + 1, ok ? "allows" : "does not allow", escape_nm);
      }
    } catch (const std::exception& e) {
      ++failed;
      std::fprintf(stderr, "mpgc_classify: %s\n", e.what());
    }
  }
  mpgc::json::Json out{{"agree", agree}, {"total", total}};
  if (escape) out["escape_allows"] = allows, out["escape_total"] = starts;
  std::printf("%s\n", out.dump().c_str());
  return failed ? 1 : 0;
}
