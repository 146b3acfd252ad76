// Seed 003's planner (Zhang et al. 2021, J. Mar. Sci. Eng. 9, 761) behind the planning interface,
// plan.planner=apf-vo: a global path by the improved artificial potential field over the fixed
// obstacles (§4.2, eq. 1-2 and the tangent force of eq. 9-10), compressed by Douglas-Peucker
// (Algorithm 1); then the modified velocity obstacle against the moving targets (§4.3): risk when
// the own velocity lies in the time-thresholded VO set (DCPA below the safety distance and
// 0 <= TCPA <= epsilon, eq. 11-14, 18), the side of the avoidance set chosen by COLREG (starboard
// for head-on and crossing give-way, the larger set when overtaking, eq. 21), the centre of that set
// as the avoidance course (eq. 19-20), held until the target's TCPA is 0 (stage 3), then back to
// a global path from there.
//
//   auto p = opp::make_planner("apf-vo");  p->declare(ps);  ps.validate_and_apply();
//   opp::Result r = p->solve({problem, constraints, objective, budget});
//
// Clearance, CPA and the COLREG encounter type are the project's (ValidityChecker, colreg::cpa,
// colreg::assess); this file computes only the potential field and the VO's course sets.
// Deterministic: no randomness (Budget::seed is unused), Budget::max_iterations bounds the APF steps.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "mpgc/opp/planner.hpp"

namespace mpgc::opp {

class ValidityChecker;

struct ApfParams {
  double step = 200.0;         // [m] APF step, Table 4
  // [m] rho_0 of eq. 1, measured beyond d_safety from the nearest fixed obstacle. Table 4 sets it
  // as 3-4 R_o from a circle's centre; a chart has no circles, so the range is a distance here.
  double rho0 = 1000.0;
  double dp_epsilon = 500.0;   // [m] epsilon of Algorithm 1, Table 4
  bool tangent_force = true;   // eq. 9-10 (false: the typical APF of eq. 1-2)
  // [rad] F_rep within this of -F_att counts as "F_rep = -F_att" (eq. 9-10): exact opposition
  // never happens in floating point off a symmetry line.
  double opposed_angle = 0.0872664625997;  // 5 deg
  int stall_steps = 25;        // [-] steps without getting nearer the goal: a local minimum too
};

struct VoParams {
  double tcpa_threshold = 900.0;  // [s] epsilon of §4.3 (the paper gives no value)
  double dcpa_factor = 1.2;       // [-] a target is a risk when DCPA < this x (d_safety + its margin)
  double max_change = 1.5707963267949;  // [rad] feasible course change, constraint (2): 90 deg
  double resolution = 0.00872664625997;  // [rad] course grid of the VO sets (0.5 deg)
  double extend = 60.0;           // [s] an avoidance leg whose return is not yet valid is held this much longer
  int max_manoeuvres = 20;        // [-] avoidance legs in one plan
  // Stage 1 also starts a manoeuvre where the course held fails the shared ValidityChecker's COLREG
  // for a target (the project's obligations pinned when the risk first appears, which may be
  // before TCPA falls to epsilon). false: the paper's VO set alone.
  bool checker_trigger = true;
};

// The improved APF of §4.2 from `from` to `to` over the fixed obstacles of `check` (its clearance
// to the nearest obstacle; the repulsion acts within rho0 beyond d_safety). Every step is clear of
// fixed obstacles by d_safety (checked). Empty with `why` set when it is stuck in a local minimum,
// runs out of `max_steps`. Each step turns at most the checker's max_turn from the one before
// (from `dir0` at the first, unless it is zero).
std::vector<Vec2> apf_path(const ValidityChecker& check, Vec2 from, Vec2 to, const ApfParams& p, int max_steps,
                           int* steps, std::string* why, Vec2 dir0 = {0, 0});

// Algorithm 1 (Douglas-Peucker): keeps the endpoints and the points farther than `epsilon` from
// the chord of their span; with `keep_whole`, also splits a span whose chord it refuses (a chord
// through an obstacle).
std::vector<Vec2> douglas_peucker(const std::vector<Vec2>& pts, double epsilon,
                                  const std::function<bool(Vec2, Vec2)>& keep_whole = {});

// Which side the modified VO passes a target on (stage 2). Starboard for head-on and crossing
// give-way (rules 14-15), eq. 21 when overtaking (the wider avoidance set, starboard on a tie),
// none when standing on (constraint 5) or there is no risk. With COLREG not required
// (Problem::colreg false): the side of the smaller alteration to the VO's edge, for every target.
enum class VoSide { kNone, kStarboard, kPort };
struct VoDecision {
  VoSide side = VoSide::kNone;
  double course = 0.0;   // [rad] avoidance course, eq. 20 (when side != kNone)
  double c1 = 0.0;       // [rad] edge of the VO on that side, eq. 19
  double width_starboard = 0.0, width_port = 0.0;  // [rad] S_VA_R and S_VA_L
  colreg::EncounterType situation = colreg::EncounterType::kNone;
  bool risk = false;     // the velocity along `course0` lies in the VO set (eq. 18)
  int target = -1;       // index of the target that decided
};
// Own ship at x at time t (targets at eq. 3 positions), speed u on course0. `forced` >= 0: that
// target decides as a risk even outside its VO (the shared checker refused the course held for
// it: an obligation pinned for the encounter, VoParams::checker_trigger); unpinned, its encounter
// is the one of the checker's per-leg model (colreg_check), which refused the course.
VoDecision vo_decide(const Problem& pb, const ConstraintParams& c, const VoParams& p, Vec2 x, double t, double u,
                     double course0, int forced = -1);

class ApfVo final : public Planner {
 public:
  std::string name() const override { return "apf-vo"; }
  void declare(rt::ParamSet& ps) override;
  Result solve(const Request& rq, const Hooks& hooks = {}) override;
  ApfParams& apf() { return apf_; }
  VoParams& vo() { return vo_; }

 private:
  ApfParams apf_;
  VoParams vo_;
};

}  // namespace mpgc::opp
