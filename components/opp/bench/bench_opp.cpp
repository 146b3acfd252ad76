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
#include <memory>
#include <string>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
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

RunOut run_ompl(const opp::Scenario& s, int max_iter, double wall, const std::vector<int>& checkpoints) {
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
  auto p = std::make_shared<og::RRTstar>(si);
  p->setRange(s.params.step);
  p->setGoalBias(s.params.goal_bias);
  p->setRewireFactor(s.params.rewire_factor);
  p->setKNearest(s.params.k_nearest);
  p->setDelayCC(true);
  p->setProblemDefinition(pdef);
  p->setup();
  RunOut out;
  size_t next_cp = 0;
  const auto t0 = Clock::now();
  ob::PlannerTerminationCondition ptc([&] {
    const int n = static_cast<int>(p->numIterations());
    const double c = p->bestCost().value();
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
  p->solve(ptc);
  out.time = since(t0);
  out.iterations = static_cast<int>(p->numIterations());
  out.cost = p->bestCost().value();
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
  out.first_time = r.stats.first_solution_time;
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

struct Versus {
  double iter_ratio = NAN, cost_equal_time = NAN, cost_equal_iter = NAN;
};

Versus versus(const opp::Scenario& s, int seeds, const std::vector<double>& walls) {
  const std::vector<int> cps = {1000, 5000, 20000};
  const double bound = opp::norm(s.problem.goal.p - s.problem.start);
  std::printf("\n== %s: ours vs OMPL RRTstar (range %.4g, goal bias %.2f, rewire factor %.2f, k-nearest, %d seeds; "
              "straight-line bound %.2f) ==\n",
              s.name.c_str(), s.params.step, s.params.goal_bias, s.params.rewire_factor, seeds, bound);
  std::vector<RunOut> ours, ompl;
  for (int i = 0; i < seeds; ++i) {
    ours.push_back(run_ours(s, 1000 + i, 20000, 0, cps));
    ompl.push_back(run_ompl(s, 20000, 0, cps));
  }
  std::printf("%-34s %14s %14s %10s\n", "median over seeds", "ours", "OMPL", "ours/OMPL");
  auto row = [](const char* name, double a, double b) { std::printf("%-34s %14.5g %14.5g %10.3f\n", name, a, b, a / b); };
  Versus v;
  for (size_t k = 0; k < cps.size(); ++k) {
    const double a = median(col(ours, [&](const RunOut& r) { return r.at_iter[k]; }));
    const double b = median(col(ompl, [&](const RunOut& r) { return r.at_iter[k]; }));
    row(("cost at " + std::to_string(cps[k]) + " iterations").c_str(), a, b);
    if (k == cps.size() - 1) v.cost_equal_iter = a / b;
  }
  const double ti_a = median(col(ours, [](const RunOut& r) { return 1e6 * r.time / r.iterations; }));
  const double ti_b = median(col(ompl, [](const RunOut& r) { return 1e6 * r.time / r.iterations; }));
  row("time per iteration [us] (20k run)", ti_a, ti_b);
  v.iter_ratio = ti_b / ti_a;
  row("iterations per second", 1e6 / ti_a, 1e6 / ti_b);
  row("time to first solution [ms]", 1e3 * median(col(ours, [](const RunOut& r) { return r.first_time; })),
      1e3 * median(col(ompl, [](const RunOut& r) { return r.first_time; })));
  row("iterations to first solution", median(col(ours, [](const RunOut& r) { return double(r.first_iter); })),
      median(col(ompl, [](const RunOut& r) { return double(r.first_iter); })));
  row("edge checks (20k run)", median(col(ours, [](const RunOut& r) { return double(r.checks); })),
      median(col(ompl, [](const RunOut& r) { return double(r.checks); })));
  for (double w : walls) {
    std::vector<RunOut> a, b;
    for (int i = 0; i < seeds; ++i) {
      a.push_back(run_ours(s, 2000 + i, 2'000'000, w, {}));
      b.push_back(run_ompl(s, 100'000'000, w, {}));
    }
    char name[64];
    std::snprintf(name, sizeof name, "cost at %.0f ms wall", 1e3 * w);
    const double ca = median(col(a, [](const RunOut& r) { return r.cost; }));
    const double cb = median(col(b, [](const RunOut& r) { return r.cost; }));
    row(name, ca, cb);
    std::snprintf(name, sizeof name, "  (cost - bound) at %.0f ms", 1e3 * w);
    row(name, ca - bound, cb - bound);
    std::snprintf(name, sizeof name, "  iterations in %.0f ms", 1e3 * w);
    row(name, median(col(a, [](const RunOut& r) { return double(r.iterations); })),
        median(col(b, [](const RunOut& r) { return double(r.iterations); })));
    v.cost_equal_time = ca / cb;
  }
  return v;
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

// Plans each case `seeds` times (plan seeds 1..seeds) and prints the planning times and a hash of
// every path and cost (equal hashes: the same plans bit for bit).
void chart_section(int seeds) {
  const char* env = std::getenv("MPGC_SHARED_DATA");
  const std::string data = env ? env : "../shared/data";
  std::printf("\n== the component's planner on charts (%d plans each, defaults + the scenario's parameters) ==\n", seeds);
  std::printf("%-12s %10s %10s %10s %10s %12s %18s\n", "case", "median ms", "p95 ms", "max ms", "iter", "edge checks",
              "path hash");
  for (const ChartCase& c : chart_cases(data)) {
    mpgc::rt::ParamSet ps;
    opp::NodeParams np;
    std::vector<std::unique_ptr<opp::Planner>> planners;
    opp::declare(ps, np, planners);
    for (const auto& o : c.overrides) ps.set_override(o);
    ps.validate_and_apply();
    std::vector<double> ms;
    uint64_t hash = 1469598103934665603ULL, checks = 0, iters = 0;
    auto mix = [&](double v) {
      uint64_t u;
      std::memcpy(&u, &v, sizeof u);
      hash = (hash ^ u) * 1099511628211ULL;
    };
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
    std::printf("%-12s %10.2f %10.2f %10.2f %10.0f %12.0f %18llx\n", c.name.c_str(), median(ms), quantile(ms, 0.95),
                *std::max_element(ms.begin(), ms.end()), double(iters) / seeds, double(checks) / seeds,
                static_cast<unsigned long long>(hash));
  }
}

int main(int argc, char** argv) {
  int seeds = 20;
  bool charts_only = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seeds") && i + 1 < argc) seeds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--quick")) seeds = 5;
    else if (!std::strcmp(argv[i], "--charts")) charts_only = true;
    else {
      std::fprintf(stderr, "usage: mpgc_bench_opp [--seeds N] [--quick] [--charts]\n");
      return 2;
    }
  }
  if (charts_only) {
    chart_section(seeds);
    return 0;
  }
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  ompl::RNG::setSeed(1);  // once per process: OMPL's planners then draw a fixed sequence of seeds
  const auto t_all = Clock::now();
  std::printf("mpgc bench opp: %d seeds per figure\n", seeds);

  const Versus disc = versus(opp::disc_world(), seeds, {0.05, 0.25});
  const Versus frozen = versus(opp::paper_scenario1_frozen(), seeds, {0.05, 0.25});

  // ---- Full COLREG planner on the paper scenarios (moving targets, eq. 5-9 cost, §5). ----
  std::printf("\n== full COLREG planner, seed 000 scenarios 1-3 (%d seeds; paper: about 500 ms per plan) ==\n", seeds);
  std::printf("%-22s %10s %10s %10s %10s %10s %10s %10s %12s %8s\n", "scenario", "first ms", "first p95", "5k ms",
              "5k p95", "20k ms", "cost5k/20k", "plain/rst", "status", "us/iter");
  std::vector<double> paper_ms;
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
  const double paper_med = median(paper_ms);
  std::printf("(cost5k/20k: 5k-iteration plan over 20k; plain/rst: 20k one tree over 20k with restarts every 1000 "
              "stale iterations)\n");
  std::printf("5k-iteration plan over all scenarios: median %.2f ms, p95 %.2f ms = %.1f%% of the paper's 500 ms\n",
              paper_med, quantile(paper_ms, 0.95), paper_med / 5.0);

  // ---- Warm start: re-plan 15 s later (the paper's rate) with and without the previous plan. ----
  std::printf("\n== warm start: re-plan after 15 s with the previous path (%d seeds) ==\n", seeds);
  std::printf("%-22s %14s %14s %14s %14s\n", "scenario", "cold cost@300", "warm cost@300", "cold 1st iter", "warm 1st iter");
  double warm_gain = 0;
  int warm_n = 0;
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
  for (int nt : {2, 10, 50}) {
    auto s = opp::paper_scenario(1);
    if (nt > 2) {
      auto extra = opp::random_targets(s.problem, 4 * nt, s.problem.speed, 77);
      for (const auto& t : extra) {
        if (static_cast<int>(s.problem.targets.size()) >= nt) break;
        if (opp::norm(t.p - s.problem.start) > 2 * s.params.safety_distance) s.problem.targets.push_back(t);
      }
    }
    std::vector<double> ms, us;
    std::string st;
    for (int i = 0; i < gs; ++i) {
      opp::Result r;
      const RunOut a = run_ours(s, 6000 + i, 5000, 0, {}, &r);
      ms.push_back(1e3 * a.time);
      us.push_back(1e6 * a.time / a.iterations);
      st = opp::to_string(r.status);
    }
    char name[64];
    std::snprintf(name, sizeof name, "%zu targets (%s)", s.problem.targets.size(), st.c_str());
    std::printf("%-28s %12.2f %12.3f %12s\n", name, median(ms), median(us), "-");
  }
  for (int np : {1000, 100000, 1000000}) {
    auto s = opp::paper_scenario(1);
    const auto tb = Clock::now();
    auto pts = opp::random_points(s.problem, np, 2.0 * s.params.safety_distance, 99);
    auto fixed = opp::point_obstacles(std::move(pts));
    const double build = 1e3 * since(tb);
    s.fixed = fixed;
    s.problem.fixed = fixed.get();
    std::vector<double> ms, us;
    std::string st;
    for (int i = 0; i < gs; ++i) {
      opp::Result r;
      const RunOut a = run_ours(s, 7000 + i, 5000, 0, {}, &r);
      ms.push_back(1e3 * a.time);
      us.push_back(1e6 * a.time / a.iterations);
      st = opp::to_string(r.status);
    }
    char name[64];
    std::snprintf(name, sizeof name, "%d fixed points (%s)", np, st.c_str());
    std::printf("%-28s %12.2f %12.3f %12.1f\n", name, median(ms), median(us), build);
  }

  std::printf("\ntotal bench time %.1f s\n", since(t_all));
  mpgc::json::Json summary;  // the figures a CI log or a tracking script reads
  summary["iter_per_s_ratio_vs_ompl"] = mpgc::json::number(disc.iter_ratio);
  summary["cost_ratio_vs_ompl_equal_time"] = mpgc::json::number(disc.cost_equal_time);
  summary["cost_ratio_vs_ompl_20k_iter"] = mpgc::json::number(disc.cost_equal_iter);
  summary["iter_per_s_ratio_vs_ompl_scenario1_frozen"] = mpgc::json::number(frozen.iter_ratio);
  summary["cost_ratio_vs_ompl_equal_time_scenario1_frozen"] = mpgc::json::number(frozen.cost_equal_time);
  summary["paper_plan_ms_median"] = mpgc::json::number(paper_med);
  summary["paper_plan_ms_p95"] = mpgc::json::number(quantile(paper_ms, 0.95));
  summary["paper_plan_iterations"] = 5000;
  summary["warm_over_cold_cost_300_iter"] = mpgc::json::number(warm_n ? warm_gain / warm_n : NAN);
  summary["seeds"] = seeds;
  std::printf("%s\n", summary.dump().c_str());
  return 0;
}
