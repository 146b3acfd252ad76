// ./mpgc bench opp — our RRT* side by side with OMPL's RRTstar on the same 2-D problems with the
// same validity checker, range, goal bias and rewire settings; then the full COLREG planner on
// the seed 000 scenarios, the warm start, and growth with targets and fixed points.
// The last line is one JSON object. Wall time is read here (a benchmark), never in the library.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "mpgc/geo/geodesy.hpp"
#include "mpgc/json/json.hpp"
#include "mpgc/obstacle_manager/chart.hpp"
#include "mpgc/opp/chart_obstacles.hpp"
#include "mpgc/opp/node.hpp"
#include "mpgc/opp/registry.hpp"
#include "mpgc/runtime/params.hpp"
#include "mpgc/opp/rrtstar.hpp"
#include "mpgc/opp/scenarios.hpp"

namespace opp = mpgc::opp;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double quantile(std::vector<double> v, double q) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double f = pos - i;
  return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}
double median(const std::vector<double>& v) { return quantile(v, 0.5); }

// ---- OMPL side: the same geometry through OMPL's validator interfaces. ----
struct Counter {
  uint64_t checks = 0;
};

class Validity : public ob::StateValidityChecker {
 public:
  Validity(const ob::SpaceInformationPtr& si, const opp::FixedObstacles* f, double d, Counter* c)
      : ob::StateValidityChecker(si), f_(f), d_(d), c_(c) {}
  bool isValid(const ob::State* s) const override {
    ++c_->checks;
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    const opp::Vec2 p{v->values[0], v->values[1]};
    return f_->segment_clear(p, p, d_);
  }

 private:
  const opp::FixedObstacles* f_;
  double d_;
  Counter* c_;
};

class Motion : public ob::MotionValidator {
 public:
  Motion(const ob::SpaceInformationPtr& si, const opp::FixedObstacles* f, double d, Counter* c)
      : ob::MotionValidator(si), f_(f), d_(d), c_(c) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    ++c_->checks;
    return f_->segment_clear(pt(a), pt(b), d_);
  }
  bool checkMotion(const ob::State* a, const ob::State* b, std::pair<ob::State*, double>& last) const override {
    const bool ok = checkMotion(a, b);
    if (!ok) {
      si_->copyState(last.first, a);
      last.second = 0.0;
    }
    return ok;
  }

 private:
  static opp::Vec2 pt(const ob::State* s) {
    const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
    return {v->values[0], v->values[1]};
  }
  const opp::FixedObstacles* f_;
  double d_;
  Counter* c_;
};

struct RunOut {
  double cost = NAN;             // final
  std::vector<double> at_iter;   // cost at the checkpoints
  double first_time = NAN;       // [s]
  int first_iter = -1;
  double time = 0;               // [s]
  int iterations = 0;
  uint64_t checks = 0;
};

// OMPL's asymptotically optimal planners of the race. RRTstar and InformedRRTstar get our range,
// goal bias, rewire factor and k-nearest (and delayCC); BITstar has no range nor goal bias (it
// holds the goal as a vertex and batches of samples): our rewire factor and k-nearest, its
// defaults otherwise (100 samples per batch, pruning on).
enum class Ompl { kRRTstar, kInformedRRTstar, kBITstar };
const char* ompl_name(Ompl k) {
  switch (k) {
    case Ompl::kRRTstar: return "RRTstar";
    case Ompl::kInformedRRTstar: return "InformedRRTstar";
    case Ompl::kBITstar: return "BITstar";
  }
  return "?";
}

RunOut run_ompl(const opp::Scenario& s, int max_iter, double wall, const std::vector<int>& checkpoints,
                Ompl kind = Ompl::kRRTstar) {
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds b(2);
  b.setLow(0, s.problem.bounds.min_x);
  b.setHigh(0, s.problem.bounds.max_x);
  b.setLow(1, s.problem.bounds.min_y);
  b.setHigh(1, s.problem.bounds.max_y);
  space->setBounds(b);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  Counter cnt;
  si->setStateValidityChecker(std::make_shared<Validity>(si, s.problem.fixed, s.params.safety_distance, &cnt));
  si->setMotionValidator(std::make_shared<Motion>(si, s.problem.fixed, s.params.safety_distance, &cnt));
  si->setup();
  ob::ScopedState<> start(space), goal(space);
  start[0] = s.problem.start.x;
  start[1] = s.problem.start.y;
  goal[0] = s.problem.goal.p.x;
  goal[1] = s.problem.goal.p.y;
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 1e-9);
  pdef->setOptimizationObjective(std::make_shared<ob::PathLengthOptimizationObjective>(si));
  ob::PlannerPtr planner;
  std::function<unsigned()> iterations;
  std::function<double()> best;
  if (kind == Ompl::kBITstar) {
    auto p = std::make_shared<og::BITstar>(si);
    p->setRewireFactor(s.params.rewire_factor);
    p->setUseKNearest(s.params.k_nearest);
    iterations = [p = p.get()] { return p->numIterations(); };
    best = [p = p.get()] { return p->bestCost().value(); };
    planner = p;
  } else {
    std::shared_ptr<og::RRTstar> p;
    if (kind == Ompl::kInformedRRTstar) p = std::make_shared<og::InformedRRTstar>(si);
    else p = std::make_shared<og::RRTstar>(si);
    p->setRange(s.params.step);
    p->setGoalBias(s.params.goal_bias);
    p->setRewireFactor(s.params.rewire_factor);
    p->setKNearest(s.params.k_nearest);
    p->setDelayCC(true);
    iterations = [p = p.get()] { return p->numIterations(); };
    best = [p = p.get()] { return p->bestCost().value(); };
    planner = p;
  }
  planner->setProblemDefinition(pdef);
  planner->setup();
  RunOut out;
  size_t next_cp = 0;
  const auto t0 = Clock::now();
  ob::PlannerTerminationCondition ptc([&] {
    const int n = static_cast<int>(iterations());
    const double c = best();
    if (out.first_iter < 0 && std::isfinite(c)) {
      out.first_iter = n;
      out.first_time = since(t0);
    }
    while (next_cp < checkpoints.size() && n >= checkpoints[next_cp]) {
      out.at_iter.push_back(c);
      ++next_cp;
    }
    return n >= max_iter || (wall > 0 && since(t0) >= wall);
  });
  planner->solve(ptc);
  out.time = since(t0);
  out.iterations = static_cast<int>(iterations());
  out.cost = best();
  if (!std::isfinite(out.first_time)) out.first_time = INFINITY;
  while (next_cp < checkpoints.size()) {  // stopped early: the last cost stands for the rest
    out.at_iter.push_back(out.cost);
    ++next_cp;
  }
  out.checks = cnt.checks;
  return out;
}

RunOut run_ours(const opp::Scenario& s, uint64_t seed, int max_iter, double wall, const std::vector<int>& checkpoints,
                opp::Result* res_out = nullptr, const std::vector<opp::Vec2>& warm = {}) {
  opp::Params p = s.params;
  p.seed = seed;
  p.max_iterations = max_iter;
  p.time_budget = wall > 0 ? wall : 1e9;
  RunOut out;
  size_t next_cp = 0;
  opp::Hooks h;
  const auto t0 = Clock::now();
  h.elapsed = [&] { return since(t0); };
  h.progress = [&](int n, double c) {
    while (next_cp < checkpoints.size() && n >= checkpoints[next_cp]) {
      out.at_iter.push_back(c);
      ++next_cp;
    }
  };
  opp::Result r = opp::plan(s.problem, p, h, warm);
  out.time = since(t0);
  out.iterations = r.stats.iterations;
  out.cost = r.path.empty() ? INFINITY : r.cost.total;
  out.first_iter = r.stats.first_solution_iteration;
  out.first_time = r.stats.first_solution_time >= 0 ? r.stats.first_solution_time : INFINITY;
  out.checks = r.stats.edge_checks;
  if (res_out) *res_out = std::move(r);
  return out;
}

template <class F>
std::vector<double> col(const std::vector<RunOut>& v, F f) {
  std::vector<double> o;
  for (const auto& r : v) o.push_back(f(r));
  return o;
}

// Quantile that keeps the failures: a run without a solution counts as +inf (sorted last), so a
// median or p95 over runs that mostly fail is inf, not the cost of the few that succeeded.
double quantile_inf(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  for (double& x : v)
    if (std::isnan(x)) x = INFINITY;
  std::sort(v.begin(), v.end());
  const double pos = q * (v.size() - 1);
  const size_t i = static_cast<size_t>(pos);
  const double f = pos - i;
  if (i + 1 >= v.size() || f == 0) return v[i];
  if (!std::isfinite(v[i + 1])) return INFINITY;
  return v[i] * (1 - f) + v[i + 1] * f;
}

// The scenario with our planner's goal treatment set: connect_goal false (like OMPL's RRTstar: only
// a goal sample connects to the goal) or true (a goal edge tried from every new node within step).
opp::Scenario with_goal_edges(opp::Scenario s, bool on) {
  s.params.connect_goal = on;
  return s;
}

// Our rows of the race, before OMPL's: ours (informed sampling, goal edges from goal samples only:
// like for like with OMPL's InformedRRTstar), the same without informed sampling, and with our
// default goal edges from every new node.
constexpr size_t kOurs = 3;
opp::Scenario ours_race(const opp::Scenario& s, bool informed, bool goal_edges) {
  opp::Scenario o = with_goal_edges(s, goal_edges);
  o.params.informed = informed;
  return o;
}

struct Versus {
  double iter_ratio = NAN, cost_equal_iter = NAN;
};

// Equal iterations: ours (connect_goal off, like for like; and on, to show what the goal edges
// change) against OMPL's RRTstar with the same range, goal bias, rewire factor and k-nearest.
Versus versus(const opp::Scenario& s0, int seeds, const std::vector<int>& cps) {
  const opp::Scenario off = with_goal_edges(s0, false), on = with_goal_edges(s0, true);
  const opp::Scenario& s = off;
  const double bound = opp::norm(s.problem.goal.p - s.problem.start);
  std::printf("\n== %s: ours vs OMPL RRTstar at equal iterations (range %.4g, goal bias %.2f, rewire factor %.2f, "
              "k-nearest, %d seeds; straight-line bound %.2f) ==\n",
              s.name.c_str(), s.params.step, s.params.goal_bias, s.params.rewire_factor, seeds, bound);
  const int max_iter = cps.back();
  std::vector<RunOut> ours, ours_ge, ompl;
  for (int i = 0; i < seeds; ++i) {
    ours.push_back(run_ours(off, 1000 + i, max_iter, 0, cps));
    ours_ge.push_back(run_ours(on, 1000 + i, max_iter, 0, cps));
    ompl.push_back(run_ompl(s, max_iter, 0, cps));
  }
  std::printf("%-34s %14s %14s %14s %10s\n", "median over seeds", "ours", "ours+goal edges", "OMPL RRTstar",
              "ours/OMPL");
  auto row = [](const std::string& name, double a, double g, double b) {
    std::printf("%-34s %14.5g %14.5g %14.5g %10.3f\n", name.c_str(), a, g, b, a / b);
  };
  auto med = [](const std::vector<RunOut>& v, auto f) { return quantile_inf(col(v, f), 0.5); };
  Versus v;
  for (size_t k = 0; k < cps.size(); ++k) {
    auto f = [&](const RunOut& r) { return r.at_iter[k]; };
    const double a = med(ours, f), g = med(ours_ge, f), b = med(ompl, f);
    row("cost at " + std::to_string(cps[k]) + " iterations", a, g, b);
    if (k == cps.size() - 1) v.cost_equal_iter = a / b;
  }
  auto us = [](const RunOut& r) { return 1e6 * r.time / r.iterations; };
  const double ti_a = med(ours, us), ti_g = med(ours_ge, us), ti_b = med(ompl, us);
  row("time per iteration [us] (" + std::to_string(max_iter / 1000) + "k run)", ti_a, ti_g, ti_b);
  v.iter_ratio = ti_b / ti_a;
  row("iterations per second", 1e6 / ti_a, 1e6 / ti_g, 1e6 / ti_b);
  auto ft = [](const RunOut& r) { return 1e3 * r.first_time; };
  row("time to first solution [ms]", med(ours, ft), med(ours_ge, ft), med(ompl, ft));
  auto fi = [](const RunOut& r) { return r.first_iter < 0 ? INFINITY : double(r.first_iter); };
  row("iterations to first solution", med(ours, fi), med(ours_ge, fi), med(ompl, fi));
  auto ch = [](const RunOut& r) { return double(r.checks); };
  row("edge checks (" + std::to_string(max_iter / 1000) + "k run)", med(ours, ch), med(ours_ge, ch), med(ompl, ch));
  // What connect_goal changes: the goal is no tree node, so with the same seed both grow the same
  // tree; with it on, a goal edge is found when its node is made, with it off only at the next goal
  // sample (1 / goal_bias iterations on average) -- the first solution and the cost between samples.
  int differ = 0, earlier = 0;
  for (int i = 0; i < seeds; ++i) {
    differ += ours[i].first_iter != ours_ge[i].first_iter || ours[i].at_iter != ours_ge[i].at_iter;
    earlier += ours_ge[i].first_iter >= 0 && (ours[i].first_iter < 0 || ours_ge[i].first_iter < ours[i].first_iter);
  }
  std::printf("connect_goal on vs off: %d of %d seeds differ (first solution or a checkpoint cost), %d find the "
              "first solution earlier with it on\n",
              differ, seeds, earlier);
  return v;
}

// ---- The race: our RRT* against OMPL's asymptotically optimal planners at equal wall time. ----
struct Cell {
  double med = NAN, p95 = NAN, success = NAN, it_per_s = NAN, first_ms = NAN;
};
struct Race {
  std::string key;                    // JSON key of the problem
  double bound = NAN;                 // straight-line lower bound
  std::vector<double> walls;          // [s]
  std::vector<std::string> planners;  // ours, ours+goal edges, then OMPL's
  std::vector<std::vector<Cell>> cell;  // [planner][wall]
};

const std::vector<Ompl> kOmpl = {Ompl::kRRTstar, Ompl::kInformedRRTstar, Ompl::kBITstar};

// Every seed runs every planner back to back (load on the shared machine falls on all alike).
Race race(const std::string& key, const opp::Scenario& s0, int seeds, const std::vector<double>& walls) {
  const opp::Scenario ours[kOurs] = {ours_race(s0, true, false), ours_race(s0, false, false), ours_race(s0, true, true)};
  Race rc;
  rc.key = key;
  rc.bound = opp::norm(s0.problem.goal.p - s0.problem.start);
  rc.walls = walls;
  rc.planners = {"ours", "ours uninformed", "ours+goal edges"};
  for (Ompl k : kOmpl) rc.planners.push_back(std::string("OMPL ") + ompl_name(k));
  const size_t np = rc.planners.size();
  rc.cell.assign(np, std::vector<Cell>(walls.size()));
  for (size_t w = 0; w < walls.size(); ++w) {
    std::vector<std::vector<RunOut>> runs(np);
    for (int i = 0; i < seeds; ++i) {
      for (size_t k = 0; k < kOurs; ++k) runs[k].push_back(run_ours(ours[k], 2000 + i, 2'000'000, walls[w], {}));
      for (size_t k = 0; k < kOmpl.size(); ++k) runs[kOurs + k].push_back(run_ompl(s0, 2'000'000'000, walls[w], {}, kOmpl[k]));
    }
    for (size_t p = 0; p < np; ++p) {
      const auto cost = col(runs[p], [](const RunOut& r) { return r.cost; });
      Cell& c = rc.cell[p][w];
      c.med = quantile_inf(cost, 0.5);
      c.p95 = quantile_inf(cost, 0.95);
      c.success = std::count_if(cost.begin(), cost.end(), [](double x) { return std::isfinite(x); }) / double(seeds);
      c.it_per_s = quantile_inf(col(runs[p], [](const RunOut& r) { return r.iterations / r.time; }), 0.5);
      c.first_ms = quantile_inf(col(runs[p], [](const RunOut& r) { return 1e3 * r.first_time; }), 0.5);
    }
  }
  return rc;
}

// Index into Race::planners of the best OMPL planner at wall w: the lowest median cost (ties: the
// lower p95, then the first listed).
size_t best_ompl(const Race& rc, size_t w) {
  size_t b = kOurs;
  for (size_t p = kOurs + 1; p < rc.planners.size(); ++p) {
    const Cell &c = rc.cell[p][w], &d = rc.cell[b][w];
    if (c.med < d.med || (c.med == d.med && c.p95 < d.p95)) b = p;
  }
  return b;
}

void print_races(const std::vector<Race>& races, int seeds) {
  std::printf("\n== the race: equal wall time, %d seeds per cell, path length, the same validity checker ==\n", seeds);
  std::printf("ours = our RRT* with informed sampling (plan.informed) and connect_goal off (a goal edge only from a "
              "goal sample, as OMPL's: like for like with InformedRRTstar);\nours uninformed = the same sampling the "
              "whole box (as OMPL's RRTstar); ours+goal edges = informed, connect_goal on (an edge to the goal\ntried "
              "from every new node within one step).\nRRTstar/InformedRRTstar: our range, goal bias, rewire factor, k-nearest, "
              "delayCC; BITstar: our rewire factor, k-nearest, defaults otherwise\n(it holds the goal as a vertex: "
              "its own goal treatment). A run without a solution counts as +inf cost.\n");
  std::printf("%-18s %-22s %7s %11s %11s %9s %8s %12s %10s %10s\n", "problem", "planner", "wall ms", "med cost",
              "p95 cost", "med/bound", "success", "iter/s", "first ms", "ours/this");
  for (const Race& rc : races) {
    for (size_t w = 0; w < rc.walls.size(); ++w) {
      const size_t b = best_ompl(rc, w);
      for (size_t p = 0; p < rc.planners.size(); ++p) {
        const Cell& c = rc.cell[p][w];
        char ratio[16] = "";
        if (p >= 1) std::snprintf(ratio, sizeof ratio, "%.4f", rc.cell[0][w].med / c.med);
        std::printf("%-18s %-22s %7.0f %11.5g %11.5g %9.4f %7.0f%% %12.0f %10.3f %10s%s\n", rc.key.c_str(),
                    (rc.planners[p] + (p == b ? " *" : "")).c_str(), 1e3 * rc.walls[w], c.med, c.p95, c.med / rc.bound,
                    100 * c.success, c.it_per_s, c.first_ms, ratio, "");
      }
    }
  }
  std::printf("(* the best OMPL planner at that wall time: the lowest median cost; ours/this: median cost of ours "
              "over this planner's; iter/s: BITstar's\n iterations are edges taken from its queue, not samples; first "
              "ms: median time to the first solution, inf when most runs found none)\n");
  // The verdict at the longest wall, plainly.
  for (const Race& rc : races) {
    const size_t w = rc.walls.size() - 1, b = best_ompl(rc, w);
    const double r = rc.cell[0][w].med / rc.cell[b][w].med;
    std::printf("%-18s at %.0f ms: ours/%s median cost %.4f -> %s\n", rc.key.c_str(), 1e3 * rc.walls[w],
                rc.planners[b].c_str() + 5, r,
                r <= 1.0 ? "ours is as good or better" : "OURS LOSES: a higher median cost than the best OMPL planner");
  }
}

}  // namespace

// ---- The component's planner on charts: the Annapolis crop (scenarios/chart/annapolis.yaml) and
// the canal of seed 000 scenario 3 (scenarios/paper/s3_colreg.yaml), built as the obstacle manager
// builds them, planned with the component's defaults and the scenario's parameters from its first
// position. Each plan's path is hashed, so two builds can be compared for identical plans.
struct ChartCase {
  std::string name;
  std::shared_ptr<opp::ChartObstacles> chart;
  opp::Bounds region;
  opp::OwnReport own;
  opp::GoalSpec goal;
  std::vector<opp::TrackReport> tracks;
  std::vector<std::string> overrides;
};

namespace om = mpgc::obstacle_manager;

std::shared_ptr<opp::ChartObstacles> chart_from(om::ChartBuilder& b, const mpgc::geom::BoxNE& box) {
  om::ObstacleSet set = om::crop(b.take(), box);
  return std::make_shared<opp::ChartObstacles>(
      std::make_shared<const mpgc::geom::FixedObstacleMap>(std::move(set.points), std::move(set.polygons)));
}

std::vector<ChartCase> chart_cases(const std::string& data) {
  std::vector<ChartCase> out;
  constexpr double kKn = 1852.0 / 3600.0, kDeg = 3.14159265358979323846 / 180.0;
  auto vel = [&](double course_deg, double kn) {
    return opp::Vec2{kn * kKn * std::cos(course_deg * kDeg), kn * kKn * std::sin(course_deg * kDeg)};
  };
  {
    om::ChartParams cp;
    cp.draught = 3.0;
    om::ChartBuilder b(mpgc::geo::LocalNed({38.965 * kDeg, -76.45 * kDeg}), cp);
    for (const char* f : {"LNDARE", "OBSTRN", "DEPARE"}) b.load_file(data + "/chart/crop_annapolis_" + f + ".geojson");
    ChartCase c;
    c.name = "annapolis";
    c.own = {{-3850, 100}, 80 * kDeg, 9 * kKn, 80 * kDeg, 0};
    const mpgc::geom::BoxNE box{c.own.p.x - 10000, c.own.p.y - 10000, c.own.p.x + 10000, c.own.p.y + 10000};
    c.chart = chart_from(b, box);
    c.region = {box.min_x, box.min_y, box.max_x, box.max_y};
    c.goal.p = {-300, -400};
    c.goal.heading = NAN;
    c.goal.safety_distance = 100;
    c.tracks = {{1, {-190, -490}, {0, 0}, 0}, {2, {-4480, 1151}, vel(20, 6), 0}};
    c.overrides = {"plan.colreg_distance=926", "plan.step=250", "plan.max_iterations=10000", "plan.time_budget=30"};
    out.push_back(std::move(c));
  }
  {
    const double L = 320;
    om::ChartBuilder b(mpgc::geo::LocalNed({38.80 * kDeg, -76.30 * kDeg}), om::ChartParams{});
    b.add_line({{7.68 * L, -27.68 * L}, {127.68 * L, 92.32 * L}}, "wall1");
    b.add_line({{-27.68 * L, 7.68 * L}, {92.32 * L, 127.68 * L}}, "wall2");
    ChartCase c;
    c.name = "s3_canal";
    c.own = {{0, 0}, 45 * kDeg, 15.5 * kKn, 45 * kDeg, 0};
    const mpgc::geom::BoxNE box{-10000, -10000, 42000, 42000};
    c.chart = chart_from(b, box);
    c.region = {box.min_x, box.min_y, box.max_x, box.max_y};
    c.goal.p = {100 * L, 100 * L};
    c.goal.heading = NAN;
    c.goal.safety_distance = 10 * L;
    c.tracks = {{1, {100 * L, 100 * L}, vel(225, 15.5), 0}};
    c.overrides = {"plan.colreg_distance=9600", "plan.time_budget=30"};
    out.push_back(std::move(c));
  }
  return out;
}

// The race's third problem: the Annapolis crop's fixed obstacles (land, obstructions, water
// shallower than the 3 m draught; scenarios/chart/annapolis.yaml) as a static path-length problem:
// the scenario's start and goal (5 km round the shoal; the straight line crosses the shoal and
// the land behind it), d_safety 100 m from every obstacle, step 250 m, the node's sampling box
// (start and goal with plan.bounds_margin 3000 m), no targets, no turn limit, no COLREG.
opp::Scenario chart_problem(const std::string& data) {
  constexpr double kDeg = 3.14159265358979323846 / 180.0;
  om::ChartParams cp;
  cp.draught = 3.0;
  om::ChartBuilder b(mpgc::geo::LocalNed({38.965 * kDeg, -76.45 * kDeg}), cp);
  for (const char* f : {"LNDARE", "OBSTRN", "DEPARE"}) b.load_file(data + "/chart/crop_annapolis_" + f + ".geojson");
  const opp::Vec2 start{-3850, 100}, goal{-300, -400};
  const mpgc::geom::BoxNE box{start.x - 10000, start.y - 10000, start.x + 10000, start.y + 10000};
  opp::Scenario s;
  s.name = "annapolis-chart";
  s.fixed = chart_from(b, box);
  opp::Problem& pb = s.problem;
  pb.start = start;
  pb.heading = 80 * kDeg;
  pb.speed = 9 * 1852.0 / 3600.0;
  pb.goal.p = goal;
  const double m = 3000;
  pb.bounds = {std::min(start.x, goal.x) - m, std::min(start.y, goal.y) - m, std::max(start.x, goal.x) + m,
               std::max(start.y, goal.y) + m};
  pb.fixed = s.fixed.get();
  pb.colreg = false;
  opp::Params& p = s.params;
  p.safety_distance = 100.0;
  p.colreg_distance = 926.0;
  p.max_turn = 3.14159265358979323846;
  p.gamma_s = p.gamma_f = p.gamma_m = 0.0;
  p.gamma_l = 1.0;
  p.step = 250.0;
  p.goal_bias = 0.05;
  p.rewire_factor = 1.1;
  p.restart_after = 0;  // plain RRT*, as OMPL's
  return s;
}

std::string shared_data() {
  const char* env = std::getenv("MPGC_SHARED_DATA");
  return env ? env : "../shared/data";
}

// FNV-1a over the bits of a double: equal hashes, the same plans bit for bit.
uint64_t mix_hash(uint64_t h, double v) {
  uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return (h ^ u) * 1099511628211ULL;
}

void print_hashed(const std::string& name, const std::vector<double>& ms, uint64_t iters, uint64_t checks, int seeds,
                  uint64_t hash) {
  std::printf("%-12s %10.2f %10.2f %10.2f %10.0f %12.0f %18llx\n", name.c_str(), median(ms), quantile(ms, 0.95),
              *std::max_element(ms.begin(), ms.end()), double(iters) / seeds, double(checks) / seeds,
              static_cast<unsigned long long>(hash));
}

// Plans each case `seeds` times (plan seeds 1..seeds), then seed 000's scenarios 1-3, and prints the planning times and a hash of
// every path and cost (equal hashes: the same plans bit for bit).
void chart_section(int seeds, const std::string& only) {
  const std::string data = shared_data();
  std::printf("\n== the component's planner on charts (defaults + the scenario's parameters) and seed 000 scenarios 1-3 (%d plans each) ==\n", seeds);
  std::printf("%-12s %10s %10s %10s %10s %12s %18s\n", "case", "median ms", "p95 ms", "max ms", "iter", "edge checks",
              "path hash");
  for (const ChartCase& c : chart_cases(data)) {
    if (!only.empty() && c.name != only) continue;
    mpgc::rt::ParamSet ps;
    opp::NodeParams np;
    std::vector<std::unique_ptr<opp::Planner>> planners;
    opp::declare(ps, np, planners);
    for (const auto& o : c.overrides) ps.set_override(o);
    ps.validate_and_apply();
    std::vector<double> ms;
    uint64_t hash = 1469598103934665603ULL, checks = 0, iters = 0;
    auto mix = [&](double v) { hash = mix_hash(hash, v); };
    for (int k = 0; k < seeds; ++k) {
      const opp::Setup s = opp::build_setup(np, c.own, c.goal, opp::targets_at(c.tracks, 0, np.target_sigmas),
                                            opp::ChartView{c.chart.get(), c.region}, static_cast<uint32_t>(k));
      opp::Hooks hooks;
      const auto t0 = Clock::now();
      hooks.elapsed = [t0] { return since(t0); };
      const opp::Result r = planners.front()->solve(s.request(np.objective, {}), hooks);
      ms.push_back(1e3 * since(t0));
      checks += r.stats.edge_checks;
      iters += r.stats.iterations;
      mix(r.cost.total);
      for (const auto& w : r.path) {
        mix(w.p.x);
        mix(w.p.y);
      }
    }
    print_hashed(c.name, ms, iters, checks, seeds, hash);
  }
  // Open water with moving targets and COLREG: seed 000 scenarios 1-3 at the default 20 000
  // iterations (the budget of every closed-loop plan).
  for (int n = 1; n <= 3; ++n) {
    if (!only.empty() && "paper_s" + std::to_string(n) != only) continue;
    const opp::Scenario sc = opp::paper_scenario(n);
    std::vector<double> ms;
    uint64_t hash = 1469598103934665603ULL, checks = 0, iters = 0;
    for (int k = 0; k < seeds; ++k) {
      opp::Result r;
      const RunOut o = run_ours(sc, static_cast<uint64_t>(k), 20000, 0, {}, &r);
      ms.push_back(1e3 * o.time);
      checks += o.checks;
      iters += static_cast<uint64_t>(o.iterations);
      hash = mix_hash(hash, r.cost.total);
      for (const auto& w : r.path) hash = mix_hash(mix_hash(hash, w.p.x), w.p.y);
    }
    print_hashed("paper_s" + std::to_string(n), ms, iters, checks, seeds, hash);
  }
}

std::vector<double> parse_walls(const char* arg) {
  std::vector<double> w;
  for (const char* c = arg; *c;) {
    char* end = nullptr;
    const double v = std::strtod(c, &end);
    if (end == c || !(v > 0)) return {};
    w.push_back(v / 1e3);
    c = *end == ',' ? end + 1 : end;
    if (*end && *end != ',') return {};
  }
  std::sort(w.begin(), w.end());
  return w;
}

int main(int argc, char** argv) {
  int seeds = 20;
  bool charts_only = false, race_only = false;
  std::string only_case;
  std::vector<double> walls = {0.05, 0.25};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--quick")) seeds = 5;
    else if (!std::strcmp(argv[i], "--charts")) charts_only = true;
    else if (!std::strcmp(argv[i], "--race")) race_only = true;
    else if (!std::strcmp(argv[i], "--case") && i + 1 < argc) charts_only = true, only_case = argv[++i];
    else if (!std::strcmp(argv[i], "--walls") && i + 1 < argc && !(walls = parse_walls(argv[++i])).empty()) {
    } else {
      std::fprintf(stderr,
                   "usage: mpgc_bench_opp [--seeds N] [--quick] [--charts] [--case NAME] [--race] [--walls MS[,MS...]]\n"
                   "  --quick: 5 seeds; --charts: only the component's planner on the charts (--case: one of its rows,\n"
                   "  e.g. s3_canal, for a profile); --race: only the\n"
                   "  equal-iteration and equal-time comparisons with OMPL; --walls: the equal wall times in ms\n"
                   "  (default 50,250; the longest is the one the JSON's equal-time ratios use)\n");
      return 2;
    }
  }
  if (charts_only) {
    chart_section(seeds, only_case);
    return 0;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  ompl::RNG::setSeed(1);  // once per process: OMPL's planners then draw a fixed sequence of seeds
  const auto t_all = Clock::now();
  std::printf("mpgc bench opp: %d seeds per figure\n", seeds);

  const opp::Scenario disc_s = opp::disc_world(), frozen_s = opp::paper_scenario1_frozen(),
                      chart_s = chart_problem(shared_data());
  const Versus disc = versus(disc_s, seeds, {1000, 5000, 20000});
  const Versus frozen = versus(frozen_s, seeds, {1000, 5000, 20000});
  const Versus chartv = versus(chart_s, seeds, {1000, 5000, 20000});
  const auto t_race = Clock::now();
  const std::vector<Race> races = {race("disc", disc_s, seeds, walls), race("scenario1_frozen", frozen_s, seeds, walls),
                                   race("chart", chart_s, seeds, walls)};
  print_races(races, seeds);
  std::printf("(the race took %.1f s)\n", since(t_race));

  // The JSON of the comparison: per problem at the longest wall, and the worst problem overall.
  mpgc::json::Json problems;
  double worst = -INFINITY;
  std::string worst_best;
  const Versus* vs[] = {&disc, &frozen, &chartv};
  for (size_t k = 0; k < races.size(); ++k) {
    const Race& rc = races[k];
    const size_t w = rc.walls.size() - 1, b = best_ompl(rc, w);
    const double r = rc.cell[0][w].med / rc.cell[b][w].med;
    mpgc::json::Json j;
    j["best_ompl_planner"] = rc.planners[b].substr(5);
    j["cost_ratio_vs_best_ompl_equal_time"] = mpgc::json::number(r);
    j["cost_p95_ratio_vs_best_ompl_equal_time"] = mpgc::json::number(rc.cell[0][w].p95 / rc.cell[b][w].p95);
    for (size_t p = kOurs; p < rc.planners.size(); ++p) {
      const std::string n = rc.planners[p].substr(5);
      j["cost_ratio_vs_" + n + "_equal_time"] = mpgc::json::number(rc.cell[0][w].med / rc.cell[p][w].med);
      j["iter_per_s_ratio_vs_" + n + "_equal_time"] = mpgc::json::number(rc.cell[0][w].it_per_s / rc.cell[p][w].it_per_s);
      j["first_solution_ms_" + n] = mpgc::json::number(rc.cell[p][w].first_ms);
      j["success_" + n] = mpgc::json::number(rc.cell[p][w].success);
    }
    j["cost_median_ours"] = mpgc::json::number(rc.cell[0][w].med);
    j["first_solution_ms_ours"] = mpgc::json::number(rc.cell[0][w].first_ms);
    j["success_ours"] = mpgc::json::number(rc.cell[0][w].success);
    j["cost_ratio_goal_edges_on_vs_off_equal_time"] = mpgc::json::number(rc.cell[2][w].med / rc.cell[0][w].med);
    j["cost_ratio_informed_vs_uninformed_equal_time"] = mpgc::json::number(rc.cell[0][w].med / rc.cell[1][w].med);
    j["iter_per_s_ratio_vs_ompl_rrtstar_20k_iter"] = mpgc::json::number(vs[k]->iter_ratio);
    j["cost_ratio_vs_ompl_rrtstar_20k_iter"] = mpgc::json::number(vs[k]->cost_equal_iter);
    j["loses"] = !(r <= 1.0);
    problems[rc.key] = j;
    if (!(r <= worst)) {
      worst = r;
      worst_best = rc.planners[b].substr(5);
    }
  }
  auto vs_rrtstar = [&](size_t k) {
    const Race& rc = races[k];
    const size_t w = rc.walls.size() - 1;
    return rc.cell[0][w].med / rc.cell[kOurs][w].med;
  };

  std::vector<double> paper_ms;
  double paper_med = NAN, warm_gain = 0;
  int warm_n = 0;
  if (!race_only) {
    // ---- Full COLREG planner on the paper scenarios (moving targets, eq. 5-9 cost, §5). ----
    std::printf("\n== full COLREG planner, seed 000 scenarios 1-3 (%d seeds; paper: about 500 ms per plan) ==\n", seeds);
    std::printf("%-22s %10s %10s %10s %10s %10s %10s %10s %12s %8s\n", "scenario", "first ms", "first p95", "5k ms",
                "5k p95", "20k ms", "cost5k/20k", "plain/rst", "status", "us/iter");
    for (int n = 1; n <= 3; ++n) {
      const auto s = opp::paper_scenario(n);
      std::vector<double> first, t5, t20, ratio, usit, plain;
      int ok = 0, relaxed = 0;
      for (int i = 0; i < seeds; ++i) {
        opp::Result r5;
        const RunOut a = run_ours(s, 3000 + i, 5000, 0, {}, &r5);
        const RunOut b = run_ours(s, 3000 + i, 20000, 0, {});
        opp::Scenario sp = s;
        sp.params.restart_after = 0;  // one tree, no restarts
        const RunOut c = run_ours(sp, 3000 + i, 20000, 0, {});
        plain.push_back(c.cost / b.cost);
        first.push_back(1e3 * a.first_time);
        t5.push_back(1e3 * a.time);
        t20.push_back(1e3 * b.time);
        ratio.push_back(a.cost / b.cost);
        usit.push_back(1e6 * a.time / a.iterations);
        ok += r5.status == opp::Status::kOk;
        relaxed += r5.status == opp::Status::kRelaxed;
        paper_ms.push_back(1e3 * a.time);
      }
      char st[32];
      std::snprintf(st, sizeof st, "%d ok/%d rel", ok, relaxed);
      std::printf("%-22s %10.2f %10.2f %10.2f %10.2f %10.2f %10.4f %10.4f %12s %8.2f\n", s.name.c_str(), median(first),
                  quantile(first, 0.95), median(t5), quantile(t5, 0.95), median(t20), median(ratio), median(plain), st,
                  median(usit));
    }
    paper_med = median(paper_ms);
    std::printf("(cost5k/20k: 5k-iteration plan over 20k; plain/rst: 20k one tree over 20k with restarts every 1000 "
                "stale iterations)\n");
    std::printf("5k-iteration plan over all scenarios: median %.2f ms, p95 %.2f ms = %.1f%% of the paper's 500 ms\n",
                paper_med, quantile(paper_ms, 0.95), paper_med / 5.0);

    // ---- Warm start: re-plan 15 s later (the paper's rate) with and without the previous plan. ----
    std::printf("\n== warm start: re-plan after 15 s with the previous path (%d seeds) ==\n", seeds);
    std::printf("%-22s %14s %14s %14s %14s\n", "scenario", "cold cost@300", "warm cost@300", "cold 1st iter", "warm 1st iter");
    for (int n = 1; n <= 3; ++n) {
      const auto s = opp::paper_scenario(n);
      std::vector<double> cc, wc, cf, wf;
      for (int i = 0; i < seeds; ++i) {
        opp::Result r1;
        run_ours(s, 4000 + i, 5000, 0, {}, &r1);
        if (r1.path.size() < 2) continue;
        opp::Scenario s2 = s;
        const double dt = 15.0;
        // Where the ship is after 15 s along the plan.
        opp::Vec2 pos = r1.path.back().p, dir{1, 0};
        for (size_t k = 0; k + 1 < r1.path.size(); ++k)
          if (dt <= r1.path[k + 1].t) {
            const double f = (dt - r1.path[k].t) / (r1.path[k + 1].t - r1.path[k].t);
            pos = r1.path[k].p + f * (r1.path[k + 1].p - r1.path[k].p);
            dir = r1.path[k + 1].p - r1.path[k].p;
            break;
          }
        s2.problem.start = pos;
        s2.problem.heading = std::atan2(dir.y, dir.x);
        for (auto& t : s2.problem.targets) t.p = t.p + dt * t.v;
        std::vector<opp::Vec2> prev;
        for (const auto& w : r1.path) prev.push_back(w.p);
        const RunOut c = run_ours(s2, 5000 + i, 300, 0, {});
        const RunOut w = run_ours(s2, 5000 + i, 300, 0, {}, nullptr, prev);
        cc.push_back(c.cost);
        wc.push_back(w.cost);
        cf.push_back(c.first_iter);
        wf.push_back(w.first_iter);
      }
      std::printf("%-22s %14.1f %14.1f %14.1f %14.1f\n", s.name.c_str(), median(cc), median(wc), median(cf), median(wf));
      if (std::isfinite(median(cc)) && std::isfinite(median(wc))) {
        warm_gain += median(wc) / median(cc);
        ++warm_n;
      }
    }

    // ---- Growth with targets and fixed points (scenario 1, 5000 iterations). ----
    std::printf("\n== growth: scenario 1, 5000 iterations, median of %d seeds ==\n", std::max(3, seeds / 4));
    std::printf("%-28s %12s %12s %12s\n", "case", "plan ms", "us/iter", "build ms");
    const int gs = std::max(3, seeds / 4);
    struct Timed {
      double ms, us_per_iteration;
      std::string status;  // of the last seed's plan
    };
    // gs seeds of 5000 iterations from seed0: the median plan time and time per iteration.
    auto timed = [&](const auto& s, int seed0) {
      std::vector<double> ms, us;
      std::string st;
      for (int i = 0; i < gs; ++i) {
        opp::Result r;
        const RunOut a = run_ours(s, seed0 + i, 5000, 0, {}, &r);
        ms.push_back(1e3 * a.time);
        us.push_back(1e6 * a.time / a.iterations);
        st = opp::to_string(r.status);
      }
      return Timed{median(ms), median(us), st};
    };
    for (int nt : {2, 10, 50}) {
      auto s = opp::paper_scenario(1);
      if (nt > 2) {
        auto extra = opp::random_targets(s.problem, 4 * nt, s.problem.speed, 77);
        for (const auto& t : extra) {
          if (static_cast<int>(s.problem.targets.size()) >= nt) break;
          if (opp::norm(t.p - s.problem.start) > 2 * s.params.safety_distance) s.problem.targets.push_back(t);
        }
      }
      const Timed tm = timed(s, 6000);
      char name[64];
      std::snprintf(name, sizeof name, "%zu targets (%s)", s.problem.targets.size(), tm.status.c_str());
      std::printf("%-28s %12.2f %12.3f %12s\n", name, tm.ms, tm.us_per_iteration, "-");
    }
    for (int np : {1000, 100000, 1000000}) {
      auto s = opp::paper_scenario(1);
      const auto tb = Clock::now();
      auto pts = opp::random_points(s.problem, np, 2.0 * s.params.safety_distance, 99);
      auto fixed = opp::point_obstacles(std::move(pts));
      const double build = 1e3 * since(tb);
      s.fixed = fixed;
      s.problem.fixed = fixed.get();
      const Timed tm = timed(s, 7000);
      char name[64];
      std::snprintf(name, sizeof name, "%d fixed points (%s)", np, tm.status.c_str());
      std::printf("%-28s %12.2f %12.3f %12.1f\n", name, tm.ms, tm.us_per_iteration, build);
    }
  }

  std::printf("\ntotal bench time %.1f s\n", since(t_all));
  mpgc::json::Json summary;  // the figures a CI log or a tracking script reads
  // vs OMPL = vs OMPL's RRTstar, ours with connect_goal off (like for like); equal time = the longest wall.
  summary["iter_per_s_ratio_vs_ompl"] = mpgc::json::number(disc.iter_ratio);
  summary["cost_ratio_vs_ompl_equal_time"] = mpgc::json::number(vs_rrtstar(0));
  summary["cost_ratio_vs_ompl_20k_iter"] = mpgc::json::number(disc.cost_equal_iter);
  summary["iter_per_s_ratio_vs_ompl_scenario1_frozen"] = mpgc::json::number(frozen.iter_ratio);
  summary["cost_ratio_vs_ompl_equal_time_scenario1_frozen"] = mpgc::json::number(vs_rrtstar(1));
  summary["paper_plan_ms_median"] = mpgc::json::number(paper_med);
  summary["paper_plan_ms_p95"] = mpgc::json::number(quantile(paper_ms, 0.95));
  summary["paper_plan_iterations"] = 5000;
  summary["warm_over_cold_cost_300_iter"] = mpgc::json::number(warm_n ? warm_gain / warm_n : NAN);
  summary["seeds"] = seeds;
  summary["goal_treatment"] = "ours connect_goal off (goal samples only, as OMPL RRTstar), informed sampling on (plan.informed)";
  summary["equal_time_s"] = walls.back();
  summary["cost_ratio_vs_best_ompl_equal_time"] = mpgc::json::number(worst);
  summary["best_ompl_planner"] = worst_best;
  summary["problems"] = problems;
  std::printf("%s\n", summary.dump().c_str());
  return 0;
}
