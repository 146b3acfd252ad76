// mpgc_classify (./mpgc classify FILE...): COLREG classification, CPA and TCPA of every target of
// DNV ship-traffic-generator situations, next to the desiredEncounterType of the matching input
// file. Ends with one JSON line {"agree":N,"total":M} over the targets that have a desired type.
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
  CLI11_PARSE(app, argc, argv);

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

  int agree = 0, total = 0, failed = 0;
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
    } catch (const std::exception& e) {
      ++failed;
      std::fprintf(stderr, "mpgc_classify: %s\n", e.what());
    }
  }
  std::printf("%s\n", mpgc::json::Json{{"agree", agree}, {"total", total}}.dump().c_str());
  return failed ? 1 : 0;
}
