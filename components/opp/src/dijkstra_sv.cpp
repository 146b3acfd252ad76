#include "mpgc/opp/dijkstra_sv.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <queue>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"
#include "mpgc/opp/validity.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::opp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec2 unit_of(double course) { return {std::cos(course), std::sin(course)}; }

// The best way found to a vertex (the modified Dijkstra keeps one label per vertex: the ship's
// state there is that of its cheapest path, §3 Step 4).
struct Label {
  double cost = kInf;
  StateVector s;        // ship state on arrival (world frame; r at the ship's speed)
  double rudder = 0.0;  // [rad] steady rudder of the area that reached it
  double len = 0.0;     // [m] path length from the start (time = len / speed, as the checker times legs)
  Vec2 dir;             // unit direction of the leg that reached it
  int pred = -1;
  bool done = false;
};

struct SideResult {
  bool ok = false;
  std::vector<Vec2> pts;
  double cost = kInf;
  std::string why;
  int expanded = 0;
  uint64_t checks = 0;
  int colreg_rejects = 0;  // legs refused for COLREG alone: relaxing it can help only if > 0
};

struct Search {
  const Problem& pb;
  const ConstraintParams& c;
  const DsvParams& p;
  const TurningTables& tt;
  const ValidityChecker& check;
  const Objective& objective;
  const Budget& budget;
  const Hooks& hooks;

  // A leg a -> b available at `level`: turn limit (eq. 2), fixed clearance and targets/COLREG, all
  // by the shared checker (§3 Step 3's "excessive approach at the time it is reached").
  ValidityChecker::Reject leg_ok(Vec2 dir, Vec2 a, Vec2 b, double ta, bool at_root, ColregLevel level,
                                 uint64_t& checks) const {
    const Vec2 seg = b - a;
    const double len = norm(seg);
    if (!(len > 1e-9)) return ValidityChecker::kTurn;
    ++checks;
    if (!check.turn_ok(dir, seg, len, at_root)) return ValidityChecker::kTurn;
    const bool esc = at_root && c.escape_start;
    if (!check.fixed_clear(a, b, check.fixed_distance(esc))) return ValidityChecker::kFixed;
    return check.moving(a, ta, b, len, level, esc);
  }

  // side = +1 starboard grid (columns to the right of the course), -1 its mirror to port.
  SideResult run(int side, ColregLevel level) const {
    SideResult out;
    const double u = pb.speed, u_tab = tt.approach_speed();
    const Vec2 route = pb.goal.p - pb.start;
    const double route_len = norm(route);
    const Vec2 ur = (1.0 / route_len) * route;
    // Fig. 5: the grid along the current course. A ship far off the route's course (mid-manoeuvre,
    // re-planned from where it is) would lay it away from the goal, with no target row before it:
    // then at axis_tolerance from the route's course on the heading's side, so that the grid leads
    // towards the goal and its first legs stay within the turn limit from the heading.
    const Vec2 h = unit_of(pb.heading);
    const double off = std::clamp(std::atan2(cross(ur, h), dot(ur, h)), -p.axis_tolerance, p.axis_tolerance);
    const Vec2 f{ur.x * std::cos(off) - ur.y * std::sin(off), ur.x * std::sin(off) + ur.y * std::cos(off)};
    const Vec2 stb{-f.y, f.x};
    // The target row lies before the goal: a grid past it would plan beyond the voyage's end.
    const int R = std::min(p.rows, static_cast<int>(std::floor(dot(route, f) / p.row_m)));
    if (R < 1) {
      out.why = "the goal is less than one grid row (" + fmt(p.row_m) + " m) ahead";
      return out;
    }
    const int C = p.cols;
    auto vid = [&](int i, int j) { return i * (C + 1) + j; };
    auto pos = [&](int i, int j) { return pb.start + (i * p.row_m) * f + (side * j * p.col_m) * stb; };
    auto xtrack = [&](Vec2 q) { return std::fabs(cross(ur, q - pb.start)); };
    const double r0_lo = tt.r0s().front(), r0_hi = tt.r0s().back();
    const QuadRule rule = p.inverse_bilinear ? QuadRule::kInverseBilinear : QuadRule::kEq4;
    // The fan of each yaw rate met, built once (without arc_state every vertex starts at r = 0);
    // with arc_state the rates vary continuously: a few kept, the rest built per leg.
    std::vector<TurningFan> fans;
    auto state_at = [&](double r0, Vec2 q) {
      for (const TurningFan& fan : fans)
        if (fan.r0() == r0) return fan.state_at(q, rule);
      if (fans.size() < 8) return fans.emplace_back(tt, r0).state_at(q, rule);
      return state_at_point(tt, r0, q, rule);
    };

    std::vector<Label> L(static_cast<size_t>((R + 1) * (C + 1)));
    Label& root = L[0];
    root.cost = 0.0;
    // The problem carries no yaw rate: the ship is taken on a steady course, rudder amidships.
    root.s = {pb.start.x, pb.start.y, pb.heading, 0.0, u_tab, 0.0};
    root.dir = h;
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
    open.push({0.0, 0});
    int rejects[ValidityChecker::kRejectCount] = {};
    int unreachable = 0;
    std::vector<int> ends;
    while (!open.empty()) {
      const auto [cst, id] = open.top();
      open.pop();
      Label& a = L[id];
      if (a.done || cst > a.cost) continue;
      a.done = true;
      if (++out.expanded > budget.max_iterations || (hooks.stop && hooks.stop())) {
        out.why = "stopped after " + std::to_string(out.expanded) + " vertices (budget or stop)";
        return out;
      }
      const int i = id / (C + 1), j = id % (C + 1);
      if (i == R) {  // a vertex of the target row: not expanded (Step 5)
        ends.push_back(id);
        continue;
      }
      const Vec2 va = pos(i, j);
      const double ta = a.len / u;
      // The area of steady rudder setting (§3 Step 2-3): area_rows ahead x area_cols to this side.
      for (int di = 1; di <= p.area_rows && i + di <= R; ++di)
        for (int dj = 0; dj <= p.area_cols && j + dj <= C; ++dj) {
          const int nid = vid(i + di, j + dj);
          if (L[nid].done) continue;
          const Vec2 vb = pos(i + di, j + dj);
          const auto why = leg_ok(a.dir, va, vb, ta, id == 0, level, out.checks);
          if (why != ValidityChecker::kValid) {
            ++rejects[why];
            continue;
          }
          // Reachable with one steady rudder from a's state (§2 Fig. 4, eq. 4): the vertex in the
          // table frame of a (turned back by a's heading), at the table of a's yaw rate. The tables
          // are for one approach speed; the turn's geometry is taken as the same at the ship's speed
          // and yaw rates scale with it (clamped to the tables' r0 range).
          const Vec2 d = vb - va;
          const double cp = std::cos(a.s.psi), sp = std::sin(a.s.psi);
          const Vec2 local{cp * d.x + sp * d.y, -sp * d.x + cp * d.y};
          const double r0 = std::clamp(a.s.r * u_tab / u, r0_lo, r0_hi);
          const std::optional<PointState> q = state_at(r0, local);
          if (!q) {
            ++unreachable;
            continue;
          }
          const double len = norm(d);
          const double nc = a.cost + objective.edge_cost(a.dir, id == 0, d, len, objective.fixed_term(vb), vb, (a.len + len) / u) +
                            p.departure_weight * xtrack(vb) + p.rudder_change_weight * std::fabs(q->rudder - a.rudder);
          Label& b = L[nid];
          if (nc < b.cost) {
            b.cost = nc;
            // The next area starts from the state found (§3 Step 4) or, by default, from the leg's
            // course at a steady rate: guidance sails the straight legs between the vertices, not
            // the steady-rudder arc, so the ship arrives on the leg's course (an arc that reaches a
            // vertex 37 deg off the bow ends 75-105 deg off it, a heading the ship never sails).
            if (p.arc_state)
              b.s = {vb.x, vb.y, a.s.psi + q->state.psi, q->state.r * u / u_tab, q->state.u, q->state.v};
            else
              b.s = {vb.x, vb.y, std::atan2(d.y, d.x), 0.0, u_tab, 0.0};
            b.rudder = q->rudder;
            b.len = a.len + len;
            b.dir = (1.0 / len) * d;
            b.pred = id;
            open.push({nc, nid});
          }
        }
    }
    out.colreg_rejects = rejects[ValidityChecker::kColreg];
    if (ends.empty()) {
      out.why = "no vertex of the last row is available (legs refused: " + std::to_string(rejects[ValidityChecker::kTarget]) +
                " target, " + std::to_string(rejects[ValidityChecker::kColreg]) + " COLREG, " +
                std::to_string(rejects[ValidityChecker::kFixed]) + " fixed, " + std::to_string(rejects[ValidityChecker::kTurn]) +
                " turn; " + std::to_string(unreachable) + " out of the tables' reach)";
      return out;
    }
    // Step 6, eq. 5: back to the route at R, where the circle of radius r = (100 + d1)/100 d about
    // the start O (d = |OE|; the route passes through O) meets the route ahead; the goal itself when
    // R would lie beyond it. The end whose path plus return costs least and whose return legs are
    // available.
    std::string last_fail;
    for (int e : ends) {
      const Label& E = L[e];
      const Vec2 ve{E.s.x, E.s.y};
      // d1 doubled while the return is not available and R is still before the goal: a longer,
      // smoother return ("the longer the return, the higher the indicator") that the turn limit
      // and the targets may allow where d1 itself does not.
      // Then the same after one row sailed parallel to the route: a last leg far to the grid's
      // side turns back to R by more than the turn limit (eq. 2), the straightening leg halves it.
      bool found = false;
      for (int straighten = 0; straighten < 2 && !found; ++straighten)
      for (double d1 = p.return_smoothness;; d1 = std::max(2.0 * d1, 10.0)) {
        const double r = (100.0 + d1) / 100.0 * norm(ve - pb.start);
        std::vector<Vec2> back;
        if (straighten) {
          const Vec2 e2 = ve + p.row_m * ur;
          if (dot(e2 - pb.start, ur) >= route_len - 1e-6) break;  // would pass the goal
          back.push_back(e2);
        }
        const Vec2 from = back.empty() ? ve : back.back();
        const bool has_r = r < route_len - 1e-6 && r > dot(from - pb.start, ur);  // R ahead, before the goal
        if (has_r) back.push_back(pb.start + r * ur);
        back.push_back(pb.goal.p);
        Vec2 a = ve, dir = E.dir;
        double len = E.len, cost = E.cost;
        bool ok = true;
        for (size_t k = 0; k < back.size() && ok; ++k) {
          const Vec2 b = back[k];
          const auto why = leg_ok(dir, a, b, len / u, false, level, out.checks);
          const Vec2 seg = b - a;
          const double l = norm(seg);
          if (why != ValidityChecker::kValid || (k + 1 == back.size() && !check.goal_heading_ok(seg))) {
            ok = false;
            if (why == ValidityChecker::kColreg) ++out.colreg_rejects;
            last_fail = why == ValidityChecker::kTarget   ? "target"
                        : why == ValidityChecker::kColreg ? "COLREG"
                        : why == ValidityChecker::kFixed  ? "fixed obstacle"
                        : why == ValidityChecker::kTurn   ? "turn limit"
                                                          : "arrival heading";
            break;
          }
          cost += objective.edge_cost(dir, false, seg, l, objective.fixed_term(b), b, (len + l) / u) +
                  p.departure_weight * xtrack(b);
          dir = (1.0 / l) * seg;
          len += l;
          a = b;
        }
        if (ok) {
          found = true;
          if (cost < out.cost) {
            out.ok = true;
            out.cost = cost;
            out.pts.clear();
            for (int v = e; v >= 0; v = L[v].pred) out.pts.push_back(v == 0 ? pb.start : Vec2{L[v].s.x, L[v].s.y});
            std::reverse(out.pts.begin(), out.pts.end());
            out.pts.insert(out.pts.end(), back.begin(), back.end());
          }
          break;
        }
        if (!has_r) break;  // already straight to the goal
      }
    }
    if (!out.ok)
      out.why = std::to_string(ends.size()) + " vertices of the last row reached, none returns to the route (eq. 5; last refused for " +
                last_fail + ")";
    return out;
  }
};

const char* level_name(ColregLevel l) {
  switch (l) {
    case ColregLevel::kFull: return "full COLREG";
    case ColregLevel::kPinned17c: return "pinned duties and 17(c)";
    case ColregLevel::kPinned: return "pinned duties";
    case ColregLevel::kNone: return "no COLREG";
  }
  return "?";
}

}  // namespace

void DsvParams::validate() const {
  auto need = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("dijkstra-sv: ") + what);
  };
  need(rows >= 1 && rows <= 200, "plan.dsv.rows must be in [1, 200]");
  need(cols >= 0 && cols <= 200, "plan.dsv.cols must be in [0, 200]");
  need(std::isfinite(row_m) && row_m >= 1.0, "plan.dsv.row_m must be finite and >= 1 m");
  need(std::isfinite(col_m) && col_m >= 1.0, "plan.dsv.col_m must be finite and >= 1 m");
  need(area_rows >= 1 && area_rows <= 50, "plan.dsv.area_rows must be in [1, 50]");
  need(area_cols >= 0 && area_cols <= 50, "plan.dsv.area_cols must be in [0, 50]");
  need(std::isfinite(departure_weight) && departure_weight >= 0.0, "plan.dsv.departure_weight must be finite and >= 0");
  need(std::isfinite(rudder_change_weight) && rudder_change_weight >= 0.0,
       "plan.dsv.rudder_change_weight must be finite and >= 0");
  need(std::isfinite(axis_tolerance) && axis_tolerance >= 0.0 && axis_tolerance <= 3.15,
       "plan.dsv.axis_tolerance must be in [0, pi] rad");
  need(std::isfinite(safe_cpa) && safe_cpa >= 0.0, "plan.dsv.safe_cpa must be finite and >= 0 m");
  need(std::isfinite(return_smoothness) && return_smoothness >= 0.0 && return_smoothness <= 1000.0,
       "plan.dsv.return_smoothness must be in [0, 1000] %");
}

void DijkstraSv::declare(rt::ParamSet& ps) {
  ps.add("plan.dsv.tables", &p_.tables, "",
         "dijkstra-sv: turning-circle tables of the own ship (`./mpgc trial tables --out F`); required");
  ps.add("plan.dsv.rows", &p_.rows, 12, "-", 1, 200, "dijkstra-sv: grid rows ahead, the last the target row (Fig. 5)");
  ps.add("plan.dsv.cols", &p_.cols, 20, "-", 0, 200, "dijkstra-sv: grid columns to one side (Fig. 5)");
  ps.add("plan.dsv.row_m", &p_.row_m, 500.0, "m", 1.0, 1e5, "dijkstra-sv: grid spacing along the course");
  ps.add("plan.dsv.col_m", &p_.col_m, 250.0, "m", 1.0, 1e5, "dijkstra-sv: grid spacing across the course");
  ps.add("plan.dsv.area_rows", &p_.area_rows, 3, "-", 1, 50, "dijkstra-sv: area of steady rudder setting, rows ahead (§3)");
  ps.add("plan.dsv.area_cols", &p_.area_cols, 4, "-", 0, 50, "dijkstra-sv: area of steady rudder setting, columns aside (§3)");
  ps.add("plan.dsv.departure_weight", &p_.departure_weight, 0.5, "1/m", 0.0, 1e6,
         "dijkstra-sv: cost per metre of cross-track from the route at every vertex reached (§3)");
  ps.add("plan.dsv.rudder_change_weight", &p_.rudder_change_weight, 300.0, "1/rad", 0.0, 1e9,
         "dijkstra-sv: cost per radian of rudder change from one area to the next (§3)");
  ps.add("plan.dsv.return_smoothness", &p_.return_smoothness, 20.0, "%", 0.0, 1000.0,
         "dijkstra-sv: d1 of eq. 5, the return to the route");
  ps.add("plan.dsv.safe_cpa", &p_.safe_cpa, 0.0, "m", 0.0, 1e5,
         "dijkstra-sv: the paper's safe CPA, used as d_safety when larger (0: the problem's d_safety)");
  ps.add("plan.dsv.axis_tolerance", &p_.axis_tolerance, geo::deg2rad(45.0), "rad", 0.0, geo::kPi,
         "dijkstra-sv: the grid along the heading while it is within this of the route's course, else this off the route");
  ps.add("plan.dsv.arc_state", &p_.arc_state, false,
         "dijkstra-sv: the next area starts from the arc's state by eq. 4 (false: on the leg's course, as guidance sails it)");
  ps.add("plan.dsv.inverse_bilinear", &p_.inverse_bilinear, false,
         "dijkstra-sv: state at a vertex by the quad's inverse bilinear map (false: eq. 4)");
}

void DijkstraSv::set_tables(TurningTables t) {
  std::lock_guard<std::mutex> lock(mu_);
  tables_ = std::make_shared<const TurningTables>(std::move(t));
  loaded_from_.clear();
  injected_ = true;
}

std::string DijkstraSv::ensure_tables(std::shared_ptr<const TurningTables>& out) {
  std::lock_guard<std::mutex> lock(mu_);
  out.reset();
  if (injected_) {
    out = tables_;
    return "";
  }
  if (p_.tables.empty()) {
    tables_.reset();
    return "dijkstra-sv: no turning-circle tables: set plan.dsv.tables to a file of `./mpgc trial tables --out FILE`";
  }
  if (!tables_ || loaded_from_ != p_.tables) try {
    tables_ = std::make_shared<const TurningTables>(load_turning_tables_file(p_.tables));
    loaded_from_ = p_.tables;
  } catch (const std::exception& e) {
    tables_.reset();
    loaded_from_.clear();
    return std::string("dijkstra-sv: plan.dsv.tables: ") + e.what();
  }
  out = tables_;
  return "";
}

Result DijkstraSv::solve(const Request& rq, const Hooks& hooks) {
  const Problem& pb = rq.problem;
  const double t0 = hooks.elapsed ? hooks.elapsed() : 0.0;
  auto done = [&](Result r) {
    r.stats.planning_time = hooks.elapsed ? hooks.elapsed() - t0 : 0.0;
    return r;
  };
  auto invalid = [&](const std::string& why) {
    Result r;
    r.status = Status::kInvalidInput;
    r.reason = why;
    return done(r);
  };
  try {
    rq.constraints.validate();
    rq.objective.validate();
    rq.budget.validate();
    p_.validate();
  } catch (const std::exception& e) {
    return invalid(e.what());
  }
  if (std::string why = check_problem(pb, rq.constraints); !why.empty()) return invalid(why);
  if (!std::isfinite(pb.heading)) return invalid("own heading is not finite");
  std::shared_ptr<const TurningTables> tables;
  if (std::string why = ensure_tables(tables); !why.empty()) return invalid(why);
  const TurningTables& tt = *tables;
  if (tt.rudders().size() < 2 || !(tt.approach_speed() > 0.0))
    return invalid("dijkstra-sv: the tables need at least two rudder settings and a positive approach speed");

  // The paper's safe CPA (plan.dsv.safe_cpa) as the checker's d_safety when it is larger than the
  // problem's; with no path there, the problem's own d_safety (§3 Step 5: "reduce the safe CPA"),
  // at each COLREG level before the next relaxation: the rules come before the extra margin.
  std::vector<ConstraintParams> tries{rq.constraints};
  if (p_.safe_cpa > rq.constraints.safety_distance) {
    ConstraintParams c = rq.constraints;
    c.safety_distance = p_.safe_cpa;
    c.colreg_distance = std::max(c.colreg_distance, 1.5 * p_.safe_cpa);  // d_COLREG > d_safety
    if (check_problem(pb, c).empty()) tries.insert(tries.begin(), c);
  }
  const ColregLevel full = pb.colreg ? ColregLevel::kFull : ColregLevel::kNone;
  std::vector<ColregLevel> levels{full};
  if (pb.colreg) levels = {ColregLevel::kFull, ColregLevel::kPinned17c, ColregLevel::kPinned, ColregLevel::kNone};
  Tally tally;
  for (const ColregLevel lv : levels) {
    tally.colreg_rejects = 0;
    for (const ConstraintParams& c : tries) {
      std::optional<Result> r = plan(pb, {c, lv, lv == full, &c == &tries.front()}, rq, hooks, tt, tally);
      if (!r) continue;
      r->margin_reduced = c.safety_distance < tries.front().safety_distance;
      if (r->margin_reduced)
        r->reason = "safe CPA " + fmt(tries.front().safety_distance) + " m reduced to d_safety " + fmt(c.safety_distance) +
                    " m: " + r->reason;
      if (lv != full) r->reason = std::string("relaxed to ") + level_name(lv) + ": " + r->reason + "; " + tally.notes;
      return done(*r);
    }
    if (tally.colreg_rejects == 0) break;  // COLREG refused nothing: relaxing it cannot help
  }
  Result r;
  r.status = Status::kNoPath;
  r.reason = "no path on the grid (widen it or reduce the safe CPA): " + tally.notes;
  r.stats.iterations = tally.expanded;
  r.stats.edge_checks = tally.checks;
  return done(r);
}

std::optional<Result> DijkstraSv::plan(const Problem& pb, const Attempt& a, const Request& rq, const Hooks& hooks,
                                       const TurningTables& tt, Tally& tally) const {
  const ConstraintParams& c = a.c;
  const ColregLevel lv = a.level;
  const ValidityChecker check(pb, c);
  const Objective objective(pb, rq.objective);
  const Search search{pb, c, p_, tt, check, objective, rq.budget, hooks};
  const Vec2 route = pb.goal.p - pb.start;
  const std::string at = "at safe CPA " + fmt(c.safety_distance) + " m, ";  // every reason says which

  // Step 1: no danger on the pre-set route (the straight leg to the goal is available): keep it.
  if (a.strictest &&
      search.leg_ok(unit_of(pb.heading), pb.start, pb.goal.p, 0.0, true, lv, tally.checks) == ValidityChecker::kValid &&
      check.goal_heading_ok(route)) {
    Result r = finish(pb, {pb.start, pb.goal.p}, false, check, objective);
    r.reason = "route clear at safe CPA " + fmt(c.safety_distance) + " m: no manoeuvre (§3 Step 1)";
    r.stats.edge_checks = tally.checks;
    r.stats.nodes = 2;
    return r;
  }

  // Step 1 for the manoeuvre being sailed: while the previous plan (the waypoints still ahead)
  // is clear under this attempt's safe CPA and COLREG level, it is kept. A fresh grid search at
  // each re-plan would take whichever side is cheaper now, and side flips make a succession of
  // small alterations instead of the one readily apparent one that rule 8(b) asks for (DNV 34:
  // port and starboard in turn at the reduced safe CPA, every plan on a tie of costs). A stricter
  // attempt's grid comes first, so a kept plan never stands in for a wider one found now; one
  // kept below the strictest is not `kept` for the node, which still tries the lower speeds for
  // the paper's safe CPA.
  if (!rq.warm.empty()) {
    std::vector<Vec2> kept{pb.start};
    for (const Vec2& w : warm_tail(rq.warm, pb.start))
      if (norm(w - kept.back()) > 1.0) kept.push_back(w);
    if (kept.size() >= 2 && norm(kept.back() - pb.goal.p) < 1.0 &&
        check.check_path(kept, lv).empty()) {
      Result r = finish(pb, kept, !a.strictest, check, objective);
      r.reason = "previous plan clear at safe CPA " + fmt(c.safety_distance) + " m: kept (§3 Step 1, rule 8(b))";
      r.stats.edge_checks = tally.checks + kept.size() - 1;
      r.stats.nodes = static_cast<int>(kept.size());
      r.stats.warm_started = true;
      r.kept = a.strictest && a.keep;
      return r;
    }
  }

  // Steps 2-6 on both grids.
  const SideResult stb = search.run(+1, lv), port = search.run(-1, lv);
  tally.expanded += stb.expanded + port.expanded;
  tally.checks += stb.checks + port.checks;
  tally.colreg_rejects += stb.colreg_rejects + port.colreg_rejects;
  if (!stb.ok && !port.ok) {
    tally.notes += (tally.notes.empty() ? "" : "; ") + at + level_name(lv) + ": starboard: " + stb.why + "; port: " + port.why;
    return std::nullopt;
  }
  // Starboard first; the port alternative only when it costs less (§3, after eq. 5).
  const bool take_port = !stb.ok || (port.ok && port.cost < stb.cost);
  const SideResult& s = take_port ? port : stb;
  // Every leg was checked by the same checker at the same times: a failure here is a bug.
  if (const std::string v = check.check_path(s.pts, false); !v.empty()) {
    Result bad;
    bad.status = Status::kNoPath;
    bad.reason = "dijkstra-sv path failed the checker: " + v;
    return bad;
  }
  Result r = finish(pb, s.pts, !a.strictest, check, objective);
  r.stats.iterations = r.stats.iterations_compliant = tally.expanded;
  r.stats.nodes = static_cast<int>(s.pts.size());
  r.stats.first_solution_iteration = tally.expanded;
  r.stats.edge_checks = tally.checks;
  r.reason = std::string(take_port ? "port" : "starboard") + " grid " + at + "cost " + fmt(s.cost) + " (other side: " +
             (take_port ? (stb.ok ? "cost " + fmt(stb.cost) : stb.why) : (port.ok ? "cost " + fmt(port.cost) : port.why)) + ")";
  return r;
}

}  // namespace mpgc::opp
