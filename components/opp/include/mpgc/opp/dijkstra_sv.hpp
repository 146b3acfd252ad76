// Seed 002's planner (Borkowski et al. 2021, Sensors 21, 5332, §3) behind the planning interface,
// plan.planner=dijkstra-sv: a regular grid aligned with the current course (Fig. 5), its vertices
// reached through areas of steady rudder setting predicted from the turning-circle tables (§2, eq. 4
// by state_at_point), the modified Dijkstra over it with the route-departure and rudder-change costs
// (Steps 3-5), starboard first with the port alternative, and the return to the route (eq. 5, Step 6).
//
//   auto p = opp::make_planner("dijkstra-sv");  p->declare(ps);  ps.validate_and_apply();
//   opp::Result r = p->solve({problem, constraints, objective, budget});   // plan.dsv.tables set
//
// Whether a leg may be sailed (fixed obstacles, targets at d_safety by linear prediction, COLREG)
// is the shared ValidityChecker's; its cost is the shared Objective's plus the two terms of §3.
// This file has no clearance, CPA or COLREG code. Deterministic; no clock except Hooks::elapsed.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "mpgc/opp/planner.hpp"
#include "mpgc/opp/turning_tables.hpp"

namespace mpgc::opp {

struct DsvParams {
  std::string tables;               // file of `./mpgc trial tables` for the own ship ("" = none)
  int rows = 12;                    // [-] grid rows ahead (the last is the target row), Fig. 5
  int cols = 20;                    // [-] grid columns to one side (starboard; the port grid mirrors it)
  double row_m = 500.0;             // [m] spacing along the course
  double col_m = 250.0;             // [m] spacing across the course
  int area_rows = 3;                // [-] area of steady rudder setting: rows ahead (§3 Step 2)
  int area_cols = 4;                // [-] ... and columns aside (one side)
  double departure_weight = 0.5;    // [1/m] cost per metre of cross-track at every vertex reached (§3)
  double rudder_change_weight = 300.0;  // [1/rad] cost per radian of rudder change between areas (§3)
  double return_smoothness = 20.0;  // [%] d1 of eq. 5
  double safe_cpa = 0.0;           // [m] the paper's safe CPA as d_safety when larger (0: the problem's)
  double axis_tolerance = 0.7853981633974483;  // [rad] grid along the heading within this of the route's course, else along the route
  bool arc_state = false;          // next area from the arc's eq. 4 state (false: the leg's course, r = 0)
  bool inverse_bilinear = false;    // state at a vertex by the quad's inverse bilinear map (false: eq. 4)
  void validate() const;            // throws std::invalid_argument naming the field
};

class DijkstraSv final : public Planner {
 public:
  std::string name() const override { return "dijkstra-sv"; }
  void declare(rt::ParamSet& ps) override;
  Result solve(const Request& rq, const Hooks& hooks = {}) override;
  bool keeps_plan() const override { return true; }  // §3 Step 1 on the manoeuvre being sailed
  DsvParams& params() { return p_; }
  // Tables given directly (tests, a caller that generated them); they win over params().tables.
  void set_tables(TurningTables t);

 private:
  // The tables of params().tables, loaded once per file name (under mu_: concurrent solves share
  // them read-only); "" or the loader's message.
  std::string ensure_tables(std::shared_ptr<const TurningTables>& out);
  // One attempt of Steps 1-6: its constraints and COLREG level; Step 1 only at the strictest level,
  // the previous plan kept only when `keep` (at the unreduced safe CPA).
  struct Attempt {
    const ConstraintParams& c;
    ColregLevel level;
    bool strictest, keep;
  };
  // What the attempts of one solve add up: the no-path notes, the edge checks, the grid vertices
  // expanded, and the legs COLREG refused (at the level being tried).
  struct Tally {
    std::string notes;
    uint64_t checks = 0;
    int expanded = 0;
    int colreg_rejects = 0;
  };
  // nullopt with tally.notes extended when the grid has no path.
  std::optional<Result> plan(const Problem& pb, const Attempt& a, const Request& rq, const Hooks& hooks,
                             const TurningTables& tt, Tally& tally) const;
  std::mutex mu_;
  DsvParams p_;
  std::shared_ptr<const TurningTables> tables_;
  std::string loaded_from_;
  bool injected_ = false;
};

}  // namespace mpgc::opp
