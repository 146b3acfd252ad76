// The two figures of the report, as hand-written SVG 1.1 (renders in browsers, Inkscape and
// rsvg-convert). Layout: plot area with a frame and light grid, axis labels, legend to the right
// of the plot so that it never covers data.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "mpgc/scenario_runner/report.hpp"

namespace mpgc::scenario_runner {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
const char* const kOwnColour = "#1f4e9c";
const char* const kTargetColours[] = {"#d62728", "#2ca02c", "#9467bd", "#ff7f0e",
                                      "#8c564b", "#e377c2", "#17becf", "#7f7f00"};
const char* const kFixedColour = "#8c6d31";
const char* const kObstacleFill = "#e8dcb5";
const char* const kPlanColour = "#9a9a9a";
const char* const kFont = "font-family=\"DejaVu Sans, Arial, Helvetica, sans-serif\"";

const char* target_colour(std::size_t k) { return kTargetColours[k % (sizeof kTargetColours / sizeof *kTargetColours)]; }

std::string f1(double v, int decimals = 1) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string esc(const std::string& s) {
  std::string r;
  for (const char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

// Tick step giving about `target` ticks over `range`: 1, 2 or 5 times a power of ten.
double nice_step(double range, int target) {
  if (!(range > 0.0)) return 1.0;
  const double raw = range / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  const double m = raw / p;  // in [1, 10): round to the nearest of 1, 2, 5, 10
  return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

int decimals_for(double step) { return step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9)); }

// Linear map of data to pixels.
struct Scale {
  double d0, d1, p0, p1;
  double operator()(double v) const { return p0 + (v - d0) / (d1 - d0) * (p1 - p0); }
};

struct Frame {
  double left, top, width, height;
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

void text(std::ostream& o, double x, double y, const std::string& s, int size = 12, const char* anchor = "start",
          const std::string& extra = "") {
  o << "<text x=\"" << f1(x) << "\" y=\"" << f1(y) << "\" font-size=\"" << size << "\" text-anchor=\"" << anchor
    << "\" " << kFont << " " << extra << ">" << esc(s) << "</text>\n";
}

// Text with a white halo so that it stays readable over lines.
void label(std::ostream& o, double x, double y, const std::string& s, int size, const char* anchor, const char* colour) {
  text(o, x, y, s, size, anchor,
       std::string("fill=\"") + colour +
           "\" stroke=\"white\" stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\"");
}

// Frame, grid, ticks and tick labels; `xs`/`ys` map data to pixels, values shown divided by `unit`.
void axes(std::ostream& o, const Frame& f, const Scale& xs, const Scale& ys, double xstep, double ystep, double unit_x,
          double unit_y, const std::string& xlabel, const std::string& ylabel) {
  const int xd = decimals_for(xstep / unit_x), yd = decimals_for(ystep / unit_y);
  o << "<g stroke=\"#e3e3e3\" stroke-width=\"1\">\n";
  const double x_first = std::ceil(std::min(xs.d0, xs.d1) / xstep - 1e-9) * xstep;
  const double y_first = std::ceil(std::min(ys.d0, ys.d1) / ystep - 1e-9) * ystep;
  for (double v = x_first; v <= std::max(xs.d0, xs.d1) + 1e-9 * xstep; v += xstep)
    o << "<line x1=\"" << f1(xs(v)) << "\" y1=\"" << f1(f.top) << "\" x2=\"" << f1(xs(v)) << "\" y2=\"" << f1(f.bottom())
      << "\"/>\n";
  for (double v = y_first; v <= std::max(ys.d0, ys.d1) + 1e-9 * ystep; v += ystep)
    o << "<line x1=\"" << f1(f.left) << "\" y1=\"" << f1(ys(v)) << "\" x2=\"" << f1(f.right()) << "\" y2=\"" << f1(ys(v))
      << "\"/>\n";
  o << "</g>\n";
  for (double v = x_first; v <= std::max(xs.d0, xs.d1) + 1e-9 * xstep; v += xstep) {
    o << "<line x1=\"" << f1(xs(v)) << "\" y1=\"" << f1(f.bottom()) << "\" x2=\"" << f1(xs(v)) << "\" y2=\""
      << f1(f.bottom() + 5) << "\" stroke=\"black\"/>\n";
    text(o, xs(v), f.bottom() + 19, f1(std::fabs(v) < 1e-9 * xstep ? 0.0 : v / unit_x, xd), 12, "middle");
  }
  for (double v = y_first; v <= std::max(ys.d0, ys.d1) + 1e-9 * ystep; v += ystep) {
    o << "<line x1=\"" << f1(f.left - 5) << "\" y1=\"" << f1(ys(v)) << "\" x2=\"" << f1(f.left) << "\" y2=\""
      << f1(ys(v)) << "\" stroke=\"black\"/>\n";
    text(o, f.left - 8, ys(v) + 4, f1(std::fabs(v) < 1e-9 * ystep ? 0.0 : v / unit_y, yd), 12, "end");
  }
  o << "<rect x=\"" << f1(f.left) << "\" y=\"" << f1(f.top) << "\" width=\"" << f1(f.width) << "\" height=\""
    << f1(f.height) << "\" fill=\"none\" stroke=\"black\" stroke-width=\"1\"/>\n";
  text(o, f.left + f.width / 2, f.bottom() + 42, xlabel, 14, "middle");
  const double ly = f.top + f.height / 2, lx = f.left - 52;
  text(o, lx, ly, ylabel, 14, "middle", "transform=\"rotate(-90 " + f1(lx) + " " + f1(ly) + ")\"");
}

// Legend rows to the right of the plot.
struct Legend {
  std::ostream& o;
  double x, y;
  void row(const std::string& symbol, const std::string& name) {
    o << "<g transform=\"translate(" << f1(x) << " " << f1(y) << ")\">" << symbol << "</g>\n";
    text(o, x + 34, y + 4, name, 12);
    y += 20;
  }
  void line(const char* colour, double width, const std::string& name, const char* dash = nullptr) {
    row(std::string("<line x1=\"0\" y1=\"0\" x2=\"26\" y2=\"0\" stroke=\"") + colour + "\" stroke-width=\"" +
            f1(width) + "\"" + (dash ? std::string(" stroke-dasharray=\"") + dash + "\"" : "") + "/>",
        name);
  }
  void note(const std::string& s, const char* colour = "#333333") {
    text(o, x, y + 4, s, 12, "start", std::string("fill=\"") + colour + "\"");
    y += 18;
  }
};

std::string time_text(double s) {
  if (std::fabs(s) >= 1200.0) return f1(s / 60.0, 0) + " min";
  return f1(s, 0) + " s";
}

// Up to `max_points` samples in order, keeping each bucket's minimum and maximum (for distances:
// the minima matter).
std::vector<std::size_t> decimate(const std::vector<double>& v, std::size_t max_points) {
  std::vector<std::size_t> idx;
  if (v.size() <= max_points) {
    for (std::size_t i = 0; i < v.size(); ++i) idx.push_back(i);
    return idx;
  }
  const std::size_t buckets = max_points / 2;
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t a = b * v.size() / buckets, e = (b + 1) * v.size() / buckets;
    std::size_t lo = a, hi = a;
    for (std::size_t i = a; i < e; ++i) {
      if (v[i] < v[lo]) lo = i;
      if (v[i] > v[hi]) hi = i;
    }
    idx.push_back(std::min(lo, hi));
    if (lo != hi) idx.push_back(std::max(lo, hi));
  }
  if (idx.back() != v.size() - 1) idx.push_back(v.size() - 1);
  return idx;
}

std::size_t nearest_sample(const std::vector<double>& t, double when) {
  const auto it = std::lower_bound(t.begin(), t.end(), when);
  if (it == t.end()) return t.size() - 1;
  const auto i = static_cast<std::size_t>(it - t.begin());
  return (i > 0 && when - t[i - 1] < t[i] - when) ? i - 1 : i;
}

void header(std::ostream& o, double w, double h, const std::string& title) {
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f1(w, 0) << "\" height=\"" << f1(h, 0)
    << "\" viewBox=\"0 0 " << f1(w, 0) << " " << f1(h, 0) << "\">\n"
    << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  text(o, w / 2, 24, title, 15, "middle", "font-weight=\"bold\"");
}

}  // namespace

void write_trajectory_svg(std::ostream& o, const RunRecord& run, const Metrics& m, const ReportOptions& opt) {
  run.validate();
  opt.validate();
  const double unit = opt.length_unit;
  const std::size_t n = run.t.size();

  // Data bounds (north x, east y): ships, goal circle, plans; fixed obstacles are clipped.
  double n0 = kInf, n1 = -kInf, e0 = kInf, e1 = -kInf;
  auto grow = [&](double x, double y, double r = 0.0) {
    n0 = std::min(n0, x - r), n1 = std::max(n1, x + r), e0 = std::min(e0, y - r), e1 = std::max(e1, y + r);
  };
  for (const auto& s : run.own.states) grow(s.x, s.y);
  for (const auto& tg : run.targets)
    for (const auto& s : tg.states) grow(s.x, s.y);
  grow(run.goal.x, run.goal.y, run.goal.radius);
  if (opt.show_plans)
    for (const auto& p : run.plans)
      for (const auto& w : p.waypoints) grow(w.x, w.y);
  // Margin, and a minimum extent so that a short run still gives a readable map.
  const double span = std::max({n1 - n0, e1 - e0, 10.0 * unit, 1.0});
  const double pad = 0.06 * span;
  n0 -= pad, n1 += pad, e0 -= pad, e1 += pad;
  // Equal scale, plot area at most 620 x 620 px and at least 320 px on each side.
  const double max_px = 620.0, min_px = 320.0;
  const double k = std::min(max_px / (e1 - e0), max_px / (n1 - n0));
  double w = (e1 - e0) * k, h = (n1 - n0) * k;
  if (w < min_px) {
    const double extra = (min_px / k - (e1 - e0)) / 2;
    e0 -= extra, e1 += extra, w = min_px;
  }
  if (h < min_px) {
    const double extra = (min_px / k - (n1 - n0)) / 2;
    n0 -= extra, n1 += extra, h = min_px;
  }
  const Frame f{78, 44, w, h};
  const Scale xs{e0, e1, f.left, f.right()};
  const Scale ys{n0, n1, f.bottom(), f.top};
  const double legend_w = 270;
  const double W = f.right() + 24 + legend_w, H = f.bottom() + 58;
  header(o, W, std::max(H, 420.0), (opt.scenario.empty() ? std::string("Run") : opt.scenario) + " \u2014 trajectories");

  const double step = nice_step(std::max(e1 - e0, n1 - n0) / unit, 6) * unit;  // nice in shown units
  axes(o, f, xs, ys, step, step, unit, unit, "East [" + opt.length_unit_name + "]",
       "North [" + opt.length_unit_name + "]");

  o << "<defs><clipPath id=\"plot\"><rect x=\"" << f1(f.left) << "\" y=\"" << f1(f.top) << "\" width=\"" << f1(f.width)
    << "\" height=\"" << f1(f.height) << "\"/></clipPath></defs>\n<g clip-path=\"url(#plot)\">\n";
  auto px = [&](double x, double y) { return f1(xs(y)) + "," + f1(ys(x)); };

  // Fixed obstacles.
  for (const auto& poly : run.obstacles.polygons) {
    o << "<polygon points=\"";
    for (const auto& v : poly.vertices) o << px(v.x, v.y) << " ";
    o << "\" fill=\"" << kObstacleFill << "\" stroke=\"" << kFixedColour << "\" stroke-width=\"1\"/>\n";
  }
  for (const auto& c : run.obstacles.circles)
    o << "<circle cx=\"" << f1(xs(c.centre.y)) << "\" cy=\"" << f1(ys(c.centre.x)) << "\" r=\""
      << f1(std::max(c.radius * k, 1.5)) << "\" fill=\"" << kObstacleFill << "\" stroke=\"" << kFixedColour
      << "\" stroke-width=\"1\"/>\n";

  // Planned paths at the re-plan instants.
  if (opt.show_plans)
    for (const auto& p : run.plans) {
      if (p.status == PlanStatus::kNoPath || p.waypoints.size() < 2) continue;
      o << "<polyline points=\"";
      for (const auto& wp : p.waypoints) o << px(wp.x, wp.y) << " ";
      o << "\" fill=\"none\" stroke=\"" << kPlanColour << "\" stroke-width=\"0.8\""
        << (p.status == PlanStatus::kRelaxed ? " stroke-dasharray=\"4 3\"" : "") << "/>\n";
    }

  // Goal with its arrival circle.
  o << "<circle cx=\"" << f1(xs(run.goal.y)) << "\" cy=\"" << f1(ys(run.goal.x)) << "\" r=\""
    << f1(std::max(run.goal.radius * k, 3.0)) << "\" fill=\"#2ca02c\" fill-opacity=\"0.12\" stroke=\"#1a7a1a\""
    << " stroke-dasharray=\"3 2\"/>\n";

  // Snapshot instants: evenly spaced up to the arrival (or the end).
  const double t_last = m.goal_reached && std::isfinite(m.t_goal) ? m.t_goal : run.t.back();
  std::vector<std::size_t> snaps;
  for (int i = 1; i <= opt.snapshot_instants; ++i) {
    const double when = run.t.front() + (t_last - run.t.front()) * i / (opt.snapshot_instants + 1.0);
    snaps.push_back(nearest_sample(run.t, when));
  }
  const double r_safe = run.safety_distance * k;
  for (std::size_t j = 0; j < run.targets.size(); ++j)
    for (std::size_t i : snaps) {
      const auto& s = run.targets[j].states[i];
      o << "<circle cx=\"" << f1(xs(s.y)) << "\" cy=\"" << f1(ys(s.x)) << "\" r=\"" << f1(r_safe) << "\" fill=\""
        << target_colour(j) << "\" fill-opacity=\"0.05\" stroke=\"" << target_colour(j)
        << "\" stroke-width=\"0.8\" stroke-dasharray=\"5 3\"/>\n";
    }
  // At each target's closest approach: its d_safety circle (solid) and the line of closest approach.
  for (std::size_t j = 0; j < run.targets.size() && j < m.min_distance_targets.size(); ++j) {
    const std::size_t i = nearest_sample(run.t, m.min_distance_targets[j].t_min);
    const auto& s = run.targets[j].states[i];
    const auto& os = run.own.states[i];
    o << "<circle cx=\"" << f1(xs(s.y)) << "\" cy=\"" << f1(ys(s.x)) << "\" r=\"" << f1(r_safe) << "\" fill=\""
      << target_colour(j) << "\" fill-opacity=\"0.08\" stroke=\"" << target_colour(j) << "\" stroke-width=\"1.2\"/>\n";
    o << "<line x1=\"" << f1(xs(os.y)) << "\" y1=\"" << f1(ys(os.x)) << "\" x2=\"" << f1(xs(s.y)) << "\" y2=\""
      << f1(ys(s.x)) << "\" stroke=\"" << target_colour(j) << "\" stroke-width=\"1\" stroke-dasharray=\"2 2\"/>\n";
  }

  // Tracks (at most ~3000 points each; positions are smooth, so a stride is enough).
  const std::size_t stride = std::max<std::size_t>(1, n / 3000);
  auto track = [&](const ShipTrack& tr, const char* colour, double width) {
    o << "<polyline points=\"";
    for (std::size_t i = 0; i < n; i += stride) o << px(tr.states[i].x, tr.states[i].y) << " ";
    o << px(tr.states[n - 1].x, tr.states[n - 1].y) << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\""
      << f1(width) << "\" stroke-linejoin=\"round\"/>\n";
  };
  for (std::size_t j = 0; j < run.targets.size(); ++j) track(run.targets[j], target_colour(j), 1.6);
  track(run.own, kOwnColour, 2.2);

  // Ship symbols: a triangle pointing along the heading at the end of each track.
  auto ship = [&](const ShipState& s, const char* colour) {
    const double sx = xs(s.y), sy = ys(s.x), a = s.heading;
    auto pt = [&](double fwd, double stb) {  // body frame to screen (north up, east right)
      return f1(sx + fwd * std::sin(a) + stb * std::cos(a)) + "," + f1(sy - fwd * std::cos(a) + stb * std::sin(a));
    };
    o << "<polygon points=\"" << pt(9, 0) << " " << pt(-6, 5) << " " << pt(-6, -5) << "\" fill=\"" << colour
      << "\" stroke=\"white\" stroke-width=\"0.8\"/>\n";
  };
  for (std::size_t j = 0; j < run.targets.size(); ++j) {
    const auto& s0 = run.targets[j].states.front();
    o << "<circle cx=\"" << f1(xs(s0.y)) << "\" cy=\"" << f1(ys(s0.x)) << "\" r=\"4\" fill=\"white\" stroke=\""
      << target_colour(j) << "\" stroke-width=\"1.5\"/>\n";
    ship(run.targets[j].states.back(), target_colour(j));
  }
  ship(run.own.states.back(), kOwnColour);
  const auto& own0 = run.own.states.front();
  o << "<rect x=\"" << f1(xs(own0.y) - 5) << "\" y=\"" << f1(ys(own0.x) - 5) << "\" width=\"10\" height=\"10\" fill=\""
    << kOwnColour << "\"/>\n";
  o << "<path d=\"M" << f1(xs(run.goal.y) - 6) << "," << f1(ys(run.goal.x)) << " h12 M" << f1(xs(run.goal.y)) << ","
    << f1(ys(run.goal.x) - 6) << " v12\" stroke=\"#1a7a1a\" stroke-width=\"2.5\"/>\n";

  // Snapshot markers, the own ship's labelled with the time.
  for (std::size_t i : snaps) {
    for (std::size_t j = 0; j < run.targets.size(); ++j) {
      const auto& s = run.targets[j].states[i];
      o << "<circle cx=\"" << f1(xs(s.y)) << "\" cy=\"" << f1(ys(s.x)) << "\" r=\"3\" fill=\"" << target_colour(j)
        << "\"/>\n";
    }
    const auto& s = run.own.states[i];
    o << "<circle cx=\"" << f1(xs(s.y)) << "\" cy=\"" << f1(ys(s.x)) << "\" r=\"3\" fill=\"" << kOwnColour << "\"/>\n";
    // Label on the side away from the track's direction of travel (left of the course).
    const double c = s.cog, lx = xs(s.y) - 8 * std::cos(c), ly = ys(s.x) - 8 * std::sin(c) + 4;
    label(o, lx, ly, time_text(run.t[i] - run.t.front()), 11, std::cos(c) >= 0 ? "end" : "start", kOwnColour);
  }
  o << "</g>\n";

  // Legend.
  Legend L{o, f.right() + 24, f.top + 8};
  L.line(kOwnColour, 2.2, "Own ship");
  for (std::size_t j = 0; j < run.targets.size(); ++j)
    L.line(target_colour(j), 1.6, "Target " + std::to_string(run.targets[j].id));
  if (opt.show_plans && !run.plans.empty()) {
    L.line(kPlanColour, 0.8, "Planned paths");
    if (m.relaxed_plans > 0) L.line(kPlanColour, 0.8, "Relaxed (no COLREG)", "4 3");
  }
  if (!run.obstacles.empty())
    L.row(std::string("<rect x=\"0\" y=\"-6\" width=\"26\" height=\"12\" fill=\"") + kObstacleFill + "\" stroke=\"" +
              kFixedColour + "\"/>",
          "Fixed obstacles");
  if (!run.targets.empty()) {
    L.row("<circle cx=\"13\" cy=\"0\" r=\"7\" fill=\"none\" stroke=\"#555\" stroke-dasharray=\"3 2\"/>",
          "d_safety around targets");
    L.row("<circle cx=\"13\" cy=\"0\" r=\"7\" fill=\"none\" stroke=\"#555\" stroke-width=\"1.2\"/>"
          "<line x1=\"0\" y1=\"0\" x2=\"13\" y2=\"0\" stroke=\"#555\" stroke-dasharray=\"2 2\"/>",
          "d_safety at closest approach");
    L.row("<circle cx=\"13\" cy=\"0\" r=\"4\" fill=\"white\" stroke=\"#555\" stroke-width=\"1.5\"/>", "Target start");
  }
  L.row(std::string("<rect x=\"8\" y=\"-5\" width=\"10\" height=\"10\" fill=\"") + kOwnColour + "\"/>", "Start");
  L.row("<path d=\"M7,0 h12 M13,-6 v12\" stroke=\"#1a7a1a\" stroke-width=\"2.5\"/>", "Goal (arrival circle)");
  L.row(std::string("<circle cx=\"13\" cy=\"0\" r=\"3\" fill=\"") + kOwnColour + "\"/>", "Positions at labelled times");
  L.row("<polygon points=\"22,0 7,5 7,-5\" fill=\"#555\"/>", "Final position");
  L.y += 10;
  const double u = opt.length_unit;
  const std::string un = " " + opt.length_unit_name;
  L.note(std::string(m.passed ? "PASSED" : "FAILED"), m.passed ? "#1a7a1a" : "#b00000");
  L.note("d_safety " + f1(run.safety_distance / u, 1) + un);
  if (std::isfinite(m.min_distance)) L.note("min distance " + f1(m.min_distance / u, 2) + un);
  L.note("goal " + std::string(m.goal_reached ? "reached at " + time_text(m.t_goal - run.t.front()) : "not reached"));
  for (const auto& e : m.encounters)
    if (e.encountered && e.situation != colreg::EncounterType::kNone)
      L.note("T" + std::to_string(e.target_id) + " " + colreg::to_string(e.situation) + ": " +
             (e.compliant ? "compliant" : "non-compliant"));
  o << "</svg>\n";
}

void write_dtc_svg(std::ostream& o, const RunRecord& run, const Metrics& m, const ReportOptions& opt) {
  run.validate();
  opt.validate();
  const DistanceSeries ds = distance_series(run);
  const double t0 = run.t.front(), t1 = std::max(run.t.back(), t0 + 1e-3);
  const bool minutes = (t1 - t0) >= 1200.0;
  const double tu = minutes ? 60.0 : 1.0;

  double ymax = run.safety_distance * 1.25;
  for (const auto& v : ds.target)
    for (double d : v) ymax = std::max(ymax, d);
  for (double d : ds.fixed)
    if (std::isfinite(d)) ymax = std::max(ymax, d);
  const double ystep = nice_step(ymax / opt.length_unit, 6) * opt.length_unit;
  ymax = std::ceil(ymax / ystep - 1e-9) * ystep;

  const Frame f{78, 44, 620, 340};
  const Scale xs{t0, t1, f.left, f.right()};
  const Scale ys{0.0, ymax, f.bottom(), f.top};
  const double W = f.right() + 24 + 270, H = f.bottom() + 58;
  header(o, W, H, (opt.scenario.empty() ? std::string("Run") : opt.scenario) + " \u2014 distance to the closest obstacle");
  const double xstep = nice_step((t1 - t0) / tu, 8) * tu;
  // Ticks at multiples of the step from t0 (time is shown from the start of the run).
  const Scale xs_rel{0.0, t1 - t0, f.left, f.right()};
  axes(o, f, xs_rel, ys, xstep, ystep, tu, opt.length_unit, minutes ? "Time [min]" : "Time [s]",
       "Distance [" + opt.length_unit_name + "]");

  o << "<defs><clipPath id=\"plot\"><rect x=\"" << f1(f.left) << "\" y=\"" << f1(f.top) << "\" width=\"" << f1(f.width)
    << "\" height=\"" << f1(f.height) << "\"/></clipPath></defs>\n<g clip-path=\"url(#plot)\">\n";
  // Below d_safety: faint red band.
  o << "<rect x=\"" << f1(f.left) << "\" y=\"" << f1(ys(run.safety_distance)) << "\" width=\"" << f1(f.width)
    << "\" height=\"" << f1(f.bottom() - ys(run.safety_distance)) << "\" fill=\"#d62728\" fill-opacity=\"0.07\"/>\n";
  auto series = [&](const std::vector<double>& v, const char* colour, double width) {
    o << "<polyline points=\"";
    for (std::size_t i : decimate(v, 3000)) o << f1(xs(run.t[i]), 2) << "," << f1(ys(v[i]), 2) << " ";
    o << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"" << f1(width) << "\" stroke-linejoin=\"round\"/>\n";
  };
  if (!ds.fixed.empty()) series(ds.fixed, kFixedColour, 1.8);
  for (std::size_t j = 0; j < ds.target.size(); ++j) series(ds.target[j], target_colour(j), 1.8);
  // Minimum of each series marked.
  auto mark_min = [&](const std::vector<double>& v, const char* colour) {
    const auto it = std::min_element(v.begin(), v.end());
    const auto i = static_cast<std::size_t>(it - v.begin());
    o << "<circle cx=\"" << f1(xs(run.t[i])) << "\" cy=\"" << f1(ys(*it)) << "\" r=\"3.5\" fill=\"white\" stroke=\""
      << colour << "\" stroke-width=\"1.5\"/>\n";
  };
  if (!ds.fixed.empty()) mark_min(ds.fixed, kFixedColour);
  for (std::size_t j = 0; j < ds.target.size(); ++j) mark_min(ds.target[j], target_colour(j));
  o << "<line x1=\"" << f1(f.left) << "\" y1=\"" << f1(ys(run.safety_distance)) << "\" x2=\"" << f1(f.right())
    << "\" y2=\"" << f1(ys(run.safety_distance)) << "\" stroke=\"black\" stroke-width=\"1.4\" stroke-dasharray=\"7 4\"/>\n";
  label(o, f.right() - 6, ys(run.safety_distance) - 6, "d_safety", 12, "end", "black");
  // Faults: a dashed line where each began, a shaded band over its window, its recovery marked.
  for (const auto& fr : run.faults) {
    if (!std::isfinite(fr.t)) continue;
    const double x0 = xs(fr.t);
    if (std::isfinite(fr.t_end))
      o << "<rect x=\"" << f1(x0) << "\" y=\"" << f1(f.top) << "\" width=\"" << f1(std::max(1.0, xs(fr.t_end) - x0))
        << "\" height=\"" << f1(f.height) << "\" fill=\"#ff7f0e\" fill-opacity=\"0.12\"/>\n";
    o << "<line x1=\"" << f1(x0) << "\" y1=\"" << f1(f.top) << "\" x2=\"" << f1(x0) << "\" y2=\"" << f1(f.bottom())
      << "\" stroke=\"#ff7f0e\" stroke-width=\"1.2\" stroke-dasharray=\"3 3\"/>\n";
    label(o, x0 + 3, f.top + 12, fr.what, 10, "start", "#a04000");
    if (std::isfinite(fr.t_recovered))
      o << "<circle cx=\"" << f1(xs(fr.t_recovered)) << "\" cy=\"" << f1(f.top + 20) << "\" r=\"3\" fill=\"#2ca02c\"/>\n";
  }
  o << "</g>\n";

  Legend L{o, f.right() + 24, f.top + 8};
  const double u = opt.length_unit;
  const std::string un = " " + opt.length_unit_name;
  for (std::size_t j = 0; j < run.targets.size(); ++j) {
    const double dmin = *std::min_element(ds.target[j].begin(), ds.target[j].end());
    L.line(target_colour(j), 1.8, "Target " + std::to_string(run.targets[j].id) + " (min " + f1(dmin / u, 2) + un + ")");
  }
  if (!ds.fixed.empty()) {
    const double dmin = *std::min_element(ds.fixed.begin(), ds.fixed.end());
    L.line(kFixedColour, 1.8, "Fixed obstacles (min " + f1(dmin / u, 2) + un + ")");
  }
  L.line("black", 1.4, "d_safety = " + f1(run.safety_distance / u, 1) + un, "7 4");
  L.row("<circle cx=\"13\" cy=\"0\" r=\"3.5\" fill=\"white\" stroke=\"#555\" stroke-width=\"1.5\"/>", "Minimum");
  if (!run.faults.empty()) {
    L.line("#ff7f0e", 1.2, "Fault injected (window shaded)", "3 3");
    L.row("<circle cx=\"13\" cy=\"0\" r=\"3\" fill=\"#2ca02c\"/>", "Component back");
  }
  L.y += 10;
  L.note("below d_safety: " + f1(m.safety_violation_s, 1) + " s", m.safety_violation_s > 0 ? "#b00000" : "#333333");
  o << "</svg>\n";
}

}  // namespace mpgc::scenario_runner
