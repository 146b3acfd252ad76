#include "mpgc/opp/turning_tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "mpgc/geo/angles.hpp"

namespace mpgc::opp {

using geom::Vec2;

double interpolate_linear(double x1, double f1, double x2, double f2, double x) {
  if (!(x2 != x1)) throw std::invalid_argument("interpolate_linear: x1 == x2");
  return f1 + (f2 - f1) * (x - x1) / (x2 - x1);
}

StateVector interpolate_linear(double x1, const StateVector& s1, double x2, const StateVector& s2, double x) {
  auto f = [&](double a, double b) { return interpolate_linear(x1, a, x2, b, x); };
  return {f(s1.x, s2.x), f(s1.y, s2.y), f(s1.psi, s2.psi), f(s1.r, s2.r), f(s1.u, s2.u), f(s1.v, s2.v)};
}

double interpolate_bilinear(double a1, double a2, double b1, double b2, double f11, double f21, double f12,
                            double f22, double a, double b) {
  const double f_b1 = interpolate_linear(a1, f11, a2, f21, a);
  const double f_b2 = interpolate_linear(a1, f12, a2, f22, a);
  return interpolate_linear(b1, f_b1, b2, f_b2, b);
}

std::array<double, 4> quad_weights(const std::array<Vec2, 4>& nodes, Vec2 p) {
  std::array<double, 4> d{};
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += d[i] = geom::norm(p - nodes[i]);
  if (!std::isfinite(sum)) throw std::invalid_argument("quad_weights: non-finite node or point");
  if (sum == 0.0) return {0.25, 0.25, 0.25, 0.25};
  // Eq. 4: w_i = (D - d_i) / D; sum_i w_i = 3, so f0 = sum w_i f_i / 3.
  std::array<double, 4> w{};
  for (int i = 0; i < 4; ++i) w[i] = (sum - d[i]) / sum / 3.0;
  return w;
}

double quad_interpolate(const std::array<Vec2, 4>& nodes, const std::array<double, 4>& f, Vec2 p) {
  const auto w = quad_weights(nodes, p);
  return w[0] * f[0] + w[1] * f[1] + w[2] * f[2] + w[3] * f[3];
}

std::optional<std::array<double, 2>> quad_inverse_bilinear(const std::array<Vec2, 4>& n, Vec2 p, double tol) {
  // p - n0 = s E + t F + s t G. Crossing with (E + t G) removes s:
  // cross(F, G) t^2 + (cross(F, E) - cross(H, G)) t - cross(H, E) = 0, then s by projection.
  const Vec2 E = n[1] - n[0], F = n[3] - n[0], G = n[0] - n[1] + n[2] - n[3], H = p - n[0];
  const double a = geom::cross(F, G), b = geom::cross(F, E) - geom::cross(H, G), c = -geom::cross(H, E);
  double roots[2];
  int nroots = 0;
  const double scale = std::abs(b) + std::abs(c) + std::abs(a);
  if (!(scale > 0.0) || !std::isfinite(scale)) return std::nullopt;
  if (std::abs(a) <= 1e-12 * scale) {
    if (std::abs(b) <= 1e-12 * scale) return std::nullopt;
    roots[nroots++] = -c / b;
  } else {
    const double disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return std::nullopt;
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));  // no cancellation
    roots[nroots++] = q / a;
    if (q != 0.0) roots[nroots++] = c / q;
  }
  for (int i = 0; i < nroots; ++i) {
    const double t = roots[i];
    if (!(t >= -tol && t <= 1.0 + tol)) continue;
    const Vec2 d = E + t * G;
    const double dd = geom::norm2(d);
    if (!(dd > 0.0)) continue;  // a degenerate edge at this t (the first quad's apex)
    const double s = geom::dot(H - t * F, d) / dd;
    if (s >= -tol && s <= 1.0 + tol) return std::array<double, 2>{std::clamp(s, 0.0, 1.0), std::clamp(t, 0.0, 1.0)};
  }
  return std::nullopt;
}

QuadShape::QuadShape(const std::array<Vec2, 4>& nodes) : n(nodes) {
  // Turn at every vertex between non-degenerate edges: all of one sign <=> convex (4 vertices
  // cannot wind twice). A zero-length edge (coincident nodes) is skipped.
  for (int i = 0; i < 4; ++i) e[i] = n[(i + 1) % 4] - n[i];
  for (int i = 0; i < 4; ++i) len[i] = geom::norm(e[i]);
  for (const double l : len) scale = std::max(scale, l);
  if (!(scale > 0.0)) return;
  const double eps = 1e-12 * scale * scale;
  for (int i = 0; i < 4; ++i) {
    if (len[i] <= 1e-12 * scale) continue;
    int j = (i + 1) % 4;
    while (len[j] <= 1e-12 * scale) j = (j + 1) % 4;
    const double c = geom::cross(e[i], e[j]);
    if (std::abs(c) <= eps) continue;  // collinear edges
    const int s = c > 0 ? 1 : -1;
    if (sign == 0) sign = s;
    if (s != sign) {
      sign = 0;
      return;
    }
  }
}

bool QuadShape::contains(Vec2 p, double tol) const {
  if (sign == 0) return false;  // not convex, or no area
  for (int i = 0; i < 4; ++i) {
    if (len[i] <= 1e-12 * scale) continue;
    if (sign * geom::cross(e[i], p - n[i]) < -tol * len[i]) return false;
  }
  return true;
}

bool convex_quad_contains(const std::array<Vec2, 4>& n, Vec2 p, double tol) { return QuadShape(n).contains(p, tol); }

// ---------------------------------------------------------------------------------------------

TurningTables::TurningTables(std::vector<double> rudders, std::vector<double> r0s, double dt, int n_times,
                             std::vector<StateVector> samples, std::string source)
    : rudders_(std::move(rudders)),
      r0s_(std::move(r0s)),
      dt_(dt),
      n_times_(n_times),
      samples_(std::move(samples)),
      source_(std::move(source)) {
  auto fail = [&](const std::string& what) { throw std::invalid_argument(source_ + ": " + what); };
  auto check_axis = [&](const std::vector<double>& a, const char* name) {
    if (a.empty()) fail(std::string("no ") + name);
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!std::isfinite(a[i])) fail(std::string(name) + " not finite");
      if (i > 0 && !(a[i] > a[i - 1])) fail(std::string(name) + " not strictly increasing");
    }
  };
  check_axis(rudders_, "rudder angles");
  check_axis(r0s_, "initial yaw rates");
  if (!(dt_ > 0.0) || !std::isfinite(dt_)) fail("time step must be > 0");
  if (n_times_ < 2) fail("each trial needs at least 2 rows (t = 0 and t = dt)");
  if (samples_.size() != rudders_.size() * r0s_.size() * static_cast<std::size_t>(n_times_))
    fail("sample count is not rudders x r0s x times");
  const double u0 = samples_[0].u;
  if (!(u0 > 0.0)) fail("approach speed u at t = 0 must be > 0");
  for (std::size_t i = 0; i < rudders_.size(); ++i)
    for (std::size_t j = 0; j < r0s_.size(); ++j) {
      for (int k = 0; k < n_times_; ++k) {
        const auto& s = node(i, j, k);
        if (!(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.psi) && std::isfinite(s.r) &&
              std::isfinite(s.u) && std::isfinite(s.v)))
          fail("non-finite state in trial rudder " + std::to_string(geo::rad2deg(rudders_[i])) + " deg");
      }
      const auto& s0 = node(i, j, 0);  // eq. 3
      if (std::abs(s0.x) > 1e-6 || std::abs(s0.y) > 1e-6 || std::abs(s0.psi) > 1e-9 || std::abs(s0.v) > 1e-6 ||
          std::abs(s0.r - r0s_[j]) > 1e-9 || std::abs(s0.u - u0) > 1e-6 * u0)
        fail("t = 0 row of trial rudder " + std::to_string(geo::rad2deg(rudders_[i])) + " deg, r0 " +
             std::to_string(geo::rad2deg(r0s_[j])) +
             " deg/s is not eq. 3 (x = y = psi = v = 0, r = r0, u = the first trial's)");
    }
}

double TurningTables::approach_speed() const { return samples_[0].u; }

const StateVector& TurningTables::node(std::size_t i, std::size_t j, int k) const {
  return samples_[(i * r0s_.size() + j) * static_cast<std::size_t>(n_times_) + static_cast<std::size_t>(k)];
}

std::size_t TurningTables::bracket(const std::vector<double>& axis, double value, const char* what,
                                   double& w) const {
  const double slack = 1e-9 * std::max(1.0, std::abs(axis.back() - axis.front()));
  if (!(value >= axis.front() - slack && value <= axis.back() + slack))
    throw std::out_of_range(source_ + ": " + what + " " + std::to_string(value) + " outside the tables' [" +
                            std::to_string(axis.front()) + ", " + std::to_string(axis.back()) + "]");
  w = 0.0;
  if (axis.size() == 1) return 0;
  std::size_t i = 0;
  while (i + 2 < axis.size() && value > axis[i + 1]) ++i;
  w = std::clamp((value - axis[i]) / (axis[i + 1] - axis[i]), 0.0, 1.0);
  return i;
}

StateVector TurningTables::row(double rudder, double r0, int k) const {
  if (k < 0 || k >= n_times_) throw std::out_of_range(source_ + ": row index outside the tables");
  double wa = 0.0, wb = 0.0;
  const std::size_t i = bracket(rudders_, rudder, "rudder [rad]", wa);
  const std::size_t j = bracket(r0s_, r0, "r0 [rad/s]", wb);
  const std::size_t i2 = std::min(i + 1, rudders_.size() - 1), j2 = std::min(j + 1, r0s_.size() - 1);
  // Fig. 3 on both axes (two-line interpolation): along r0 at each of the two rudders, then along
  // the rudder. Written with weights so an axis with one node needs no special case.
  auto mix = [](const StateVector& a, const StateVector& b, double w) {
    const double o = 1.0 - w;  // exact on a node (w = 0 or 1)
    return StateVector{o * a.x + w * b.x, o * a.y + w * b.y, o * a.psi + w * b.psi,
                       o * a.r + w * b.r, o * a.u + w * b.u, o * a.v + w * b.v};
  };
  const StateVector at_i = mix(node(i, j, k), node(i, j2, k), wb);
  const StateVector at_i2 = mix(node(i2, j, k), node(i2, j2, k), wb);
  return mix(at_i, at_i2, wa);
}

StateVector TurningTables::at(double rudder, double r0, double t) const {
  if (!(t >= 0.0 && t <= duration() * (1.0 + 1e-12)))
    throw std::out_of_range(source_ + ": t " + std::to_string(t) + " s outside [0, " + std::to_string(duration()) +
                            "] s");
  const int k = std::min(static_cast<int>(t / dt_), n_times_ - 2);
  const double w = std::clamp(t / dt_ - k, 0.0, 1.0);
  return interpolate_linear(0.0, row(rudder, r0, k), 1.0, row(rudder, r0, k + 1), w);
}

// ---------------------------------------------------------------------------------------------

namespace {

constexpr const char* kHeader = "rudder_deg,r0_deg_s,t_s,x_m,y_m,psi_rad,r_rad_s,u_m_s,v_m_s";

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

struct Row {
  int line;
  double cell[9];
};

}  // namespace

TurningTables load_turning_tables(std::istream& in, const std::string& source) {
  static const char* kNames[9] = {"rudder_deg", "r0_deg_s", "t_s", "x_m", "y_m", "psi_rad", "r_rad_s", "u_m_s", "v_m_s"};
  auto fail = [&](int line, const std::string& what) {
    throw std::runtime_error(source + ":" + std::to_string(line) + ": " + what);
  };
  std::vector<Row> rows;
  std::string text;
  int line = 0;
  bool header = false;
  while (std::getline(in, text)) {
    ++line;
    text = trim(text);
    if (text.empty() || text[0] == '#') continue;
    if (!header) {
      if (text != kHeader) fail(line, "header must be '" + std::string(kHeader) + "', got '" + text + "'");
      header = true;
      continue;
    }
    Row r{line, {}};
    std::stringstream ss(text);
    std::string cell;
    int n = 0;
    while (std::getline(ss, cell, ',')) {
      if (n >= 9) fail(line, "more than 9 cells");
      cell = trim(cell);
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (cell.empty() || end != cell.c_str() + cell.size())
        fail(line, std::string(kNames[n]) + " '" + cell + "' is not a number");
      if (!std::isfinite(v)) fail(line, std::string(kNames[n]) + " is not finite ('" + cell + "')");
      r.cell[n++] = v;
    }
    if (n != 9) fail(line, std::to_string(n) + " cells, expected 9 (" + kHeader + ")");
    rows.push_back(r);
  }
  if (!header) fail(line, "no header line '" + std::string(kHeader) + "' (empty file?)");
  if (rows.empty()) fail(line, "no data rows");

  // Group consecutive rows into trials; check the order rudder, r0, t.
  struct Trial {
    double rudder_deg, r0_deg_s;
    std::size_t first, count;
  };
  std::vector<Trial> trials;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double d = rows[i].cell[0], r0 = rows[i].cell[1];
    if (trials.empty() || d != trials.back().rudder_deg || r0 != trials.back().r0_deg_s) {
      if (!trials.empty()) {
        const Trial& p = trials.back();
        if (d < p.rudder_deg || (d == p.rudder_deg && r0 <= p.r0_deg_s))
          fail(rows[i].line, "trial (rudder " + std::to_string(d) + " deg, r0 " + std::to_string(r0) +
                                 " deg/s) out of order: rows must be sorted by rudder, then r0, ascending, one block per trial");
      }
      trials.push_back({d, r0, i, 0});
    }
    ++trials.back().count;
  }
  // Time grid from the first trial: 0, dt, 2 dt, ... (uneven or non-increasing is an error).
  const Trial& t0 = trials.front();
  if (t0.count < 2) fail(rows[t0.first].line, "the first trial has fewer than 2 rows");
  const double dt = rows[t0.first + 1].cell[2] - rows[t0.first].cell[2];
  if (!(dt > 0.0)) fail(rows[t0.first + 1].line, "t_s not increasing");
  int n_times = 0;  // the longest trial: a shorter one is missing rows
  for (const Trial& tr : trials) n_times = std::max(n_times, static_cast<int>(tr.count));
  std::vector<double> rudders_deg, r0s_deg;
  for (const Trial& tr : trials) {
    if (rudders_deg.empty() || tr.rudder_deg != rudders_deg.back()) rudders_deg.push_back(tr.rudder_deg);
    if (rudders_deg.size() == 1) r0s_deg.push_back(tr.r0_deg_s);
  }
  for (const Trial& tr : trials) {
    const int l = rows[tr.first].line;
    std::ostringstream id;
    id << "trial (rudder " << tr.rudder_deg << " deg, r0 " << tr.r0_deg_s << " deg/s)";
    if (static_cast<int>(tr.count) != n_times)
      fail(l, id.str() + " has " + std::to_string(tr.count) + " rows, another trial " + std::to_string(n_times) +
                  ": missing or extra rows");
    for (std::size_t k = 0; k < tr.count; ++k) {
      const double t = rows[tr.first + k].cell[2], want = static_cast<double>(k) * dt;
      if (std::abs(t - want) > 1e-6 * std::max(1.0, want))
        fail(rows[tr.first + k].line, id.str() + ": t_s " + std::to_string(t) + " where the time grid (0, " +
                                          std::to_string(dt) + ", ...) has " + std::to_string(want) +
                                          " (missing, repeated or uneven rows)");
    }
  }
  // A full grid: every rudder has the same r0s.
  if (trials.size() != rudders_deg.size() * r0s_deg.size()) {
    std::size_t i = 0;
    for (double d : rudders_deg) {
      for (double r0 : r0s_deg) {
        if (i >= trials.size() || trials[i].rudder_deg != d || trials[i].r0_deg_s != r0) {
          std::ostringstream o;
          o << "missing trial (rudder " << d << " deg, r0 " << r0 << " deg/s): every rudder needs every r0 of rudder "
            << rudders_deg.front() << " deg";
          fail(i < trials.size() ? rows[trials[i].first].line : line, o.str());
        }
        ++i;
      }
    }
    fail(line, "trials do not form a full rudder x r0 grid");
  }
  for (std::size_t i = 0; i < trials.size(); ++i)
    if (trials[i].r0_deg_s != r0s_deg[i % r0s_deg.size()])
      fail(rows[trials[i].first].line, "trial r0 " + std::to_string(trials[i].r0_deg_s) +
                                           " deg/s where the grid of the first rudder has " +
                                           std::to_string(r0s_deg[i % r0s_deg.size()]) + ": not a full grid");

  std::vector<double> rudders, r0s;
  for (double d : rudders_deg) rudders.push_back(geo::deg2rad(d));
  for (double r : r0s_deg) r0s.push_back(geo::deg2rad(r));
  std::vector<StateVector> samples;
  samples.reserve(rows.size());
  for (const Row& r : rows) samples.push_back({r.cell[3], r.cell[4], r.cell[5], r.cell[6], r.cell[7], r.cell[8]});
  try {
    return TurningTables(std::move(rudders), std::move(r0s), dt, n_times, std::move(samples), source);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

TurningTables load_turning_tables_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open turning-circle tables");
  return load_turning_tables(in, path);
}

// ---------------------------------------------------------------------------------------------

StateVector to_world(const StateVector& start, const StateVector& s) {
  const double c = std::cos(start.psi), sn = std::sin(start.psi);
  // §2: the table frame (eq. 3) turned by the start's course and moved to its position.
  return {start.x + c * s.x - sn * s.y, start.y + sn * s.x + c * s.y, start.psi + s.psi, s.r, s.u, s.v};
}

StateVector predict(const TurningTables& tables, const StateVector& start, double rudder, double t) {
  return to_world(start, tables.at(rudder, start.r, t));
}

std::optional<PointState> state_at_point(const TurningTables& tables, double r0, Vec2 p, QuadRule rule) {
  if (tables.rudders().size() < 2) return std::nullopt;  // a single rudder gives a line, not a fan
  return TurningFan(tables, r0).state_at(p, rule);
}

TurningFan::TurningFan(const TurningTables& tables, double r0)
    : r0_(r0), dt_(tables.dt()), rudders_(tables.rudders()), nt_(tables.n_times()) {
  const std::size_t nr = rudders_.size();
  if (nr < 2) throw std::invalid_argument("TurningFan: the tables need at least two rudder settings");
  // Fig. 3 (linear in r0) first: the fan of trials at r0, one per table rudder.
  fan_.resize(nr * static_cast<std::size_t>(nt_));
  for (std::size_t i = 0; i < nr; ++i)
    for (int k = 0; k < nt_; ++k) fan_[i * nt_ + k] = tables.row(rudders_[i], r0, k);
  quads_.reserve((nr - 1) * static_cast<std::size_t>(nt_ - 1));
  for (int k = 0; k + 1 < nt_; ++k)
    for (std::size_t i = 0; i + 1 < nr; ++i) {
      auto xy = [&](std::size_t ii, int kk) { return Vec2{fan_[ii * nt_ + kk].x, fan_[ii * nt_ + kk].y}; };
      quads_.emplace_back(std::array<Vec2, 4>{xy(i, k), xy(i + 1, k), xy(i + 1, k + 1), xy(i, k + 1)});
    }
}

std::optional<PointState> TurningFan::state_at(Vec2 p, QuadRule rule) const {
  const std::size_t nr = rudders_.size();
  const int nt = nt_;
  auto at = [&](std::size_t i, int k) -> const StateVector& { return fan_[i * nt + k]; };
  for (int k = 0; k + 1 < nt; ++k)
    for (std::size_t i = 0; i + 1 < nr; ++i) {
      if (!quads_[static_cast<std::size_t>(k) * (nr - 1) + i].contains(p, 1e-6)) continue;
      const std::array<std::size_t, 4> ii{i, i + 1, i + 1, i};
      const std::array<int, 4> kk{k, k, k + 1, k + 1};
      PointState out;
      for (int n = 0; n < 4; ++n) {
        out.node_states[n] = at(ii[n], kk[n]);
        out.nodes[n] = {out.node_states[n].x, out.node_states[n].y};
        out.node_t[n] = kk[n] * dt_;
        out.node_rudder[n] = rudders_[ii[n]];
      }
      std::array<double, 4> w{};
      if (rule == QuadRule::kEq4) {
        w = quad_weights(out.nodes, p);
      } else {
        const auto st = quad_inverse_bilinear(out.nodes, p, 1e-6);
        if (!st) continue;
        const double a = (*st)[0], b = (*st)[1];
        w = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
      }
      auto f = [&](auto get) {
        double s = 0.0;
        for (int n = 0; n < 4; ++n) s += w[n] * get(n);
        return s;
      };
      out.state = {p.x,
                   p.y,
                   f([&](int n) { return out.node_states[n].psi; }),
                   f([&](int n) { return out.node_states[n].r; }),
                   f([&](int n) { return out.node_states[n].u; }),
                   f([&](int n) { return out.node_states[n].v; })};
      out.t = f([&](int n) { return out.node_t[n]; });
      out.rudder = f([&](int n) { return out.node_rudder[n]; });
      return out;
    }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------

void AccuracyParams::validate() const {
  auto bad = [](const std::string& f) { throw std::invalid_argument("AccuracyParams." + f); };
  if (cases < 1 || cases > 100000) bad("cases must be in 1..100000");
  if (substeps < 1 || substeps > 1000) bad("substeps must be in 1..1000");
  for (auto [v, n] : {std::pair{floor_xy, "floor_xy"}, {floor_psi, "floor_psi"}, {floor_r, "floor_r"},
                      {floor_uv, "floor_uv"}, {floor_t, "floor_t"}})
    if (!(v > 0.0) || !std::isfinite(v)) bad(std::string(n) + " must be > 0");
}

double max_of(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  return *std::max_element(v.begin(), v.end());
}

double median_of(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

namespace {

// Error of `got` against `want` as % of the node spread of values f (floored).
double pct(double got, double want, const double* f, double floor) {
  const double spread = std::abs(*std::max_element(f, f + 4) - *std::min_element(f, f + 4));
  return 100.0 * std::abs(got - want) / std::max(spread, floor);
}

std::string describe(double r0, double rudder, double t, const char* param, double p) {
  std::ostringstream o;
  o.precision(4);
  o << "r0 " << geo::rad2deg(r0) << " deg/s, rudder " << geo::rad2deg(rudder) << " deg, t " << t << " s: " << param
    << " " << p << " %";
  return o.str();
}

}  // namespace

AccuracyReport check_accuracy(const TurningTables& tt, const TrialFn& truth, const AccuracyParams& prm) {
  prm.validate();
  if (!truth) throw std::invalid_argument("check_accuracy: no model");
  AccuracyReport rep;
  std::mt19937_64 rng(prm.seed);
  std::uniform_real_distribution<double> ur0(tt.r0s().front(), tt.r0s().back());
  std::uniform_real_distribution<double> ud(tt.rudders().front(), tt.rudders().back());
  const int sub = prm.substeps, nt = tt.n_times();
  const int n_truth = (nt - 1) * sub + 1;
  std::uniform_int_distribution<int> ut(sub, n_truth - 1);
  double worst3 = -1.0, worst4 = -1.0;
  for (int c = 0; c < prm.cases; ++c) {
    const double r0 = ur0(rng), rudder = ud(rng);
    const int kstar = ut(rng);
    const auto sim = truth(r0, rudder, tt.dt() / sub, n_truth);
    if (static_cast<int>(sim.size()) != n_truth) throw std::runtime_error("check_accuracy: model gave a short trial");

    // Fig. 3: the four trials around (rudder, r0) are the nodes.
    const auto& R = tt.rudders();
    const auto& Q = tt.r0s();
    std::size_t i = 0, j = 0;
    while (i + 2 < R.size() && rudder > R[i + 1]) ++i;
    while (j + 2 < Q.size() && r0 > Q[j + 1]) ++j;
    const std::size_t i2 = std::min(i + 1, R.size() - 1), j2 = std::min(j + 1, Q.size() - 1);
    double case3 = 0.0;
    std::string what3;
    std::map<std::string, double> by3;
    for (int k = 1; k < nt; ++k) {
      const StateVector got = tt.row(rudder, r0, k), want = sim[static_cast<std::size_t>(k) * sub];
      const StateVector* n[4] = {&tt.node(i, j, k), &tt.node(i2, j, k), &tt.node(i, j2, k), &tt.node(i2, j2, k)};
      auto one = [&](const char* name, double StateVector::*m, double floor) {
        const double f[4] = {n[0]->*m, n[1]->*m, n[2]->*m, n[3]->*m};
        const double e = pct(got.*m, want.*m, f, floor);
        by3[name] = std::max(by3[name], e);
        if (e > case3) {
          case3 = e;
          what3 = describe(r0, rudder, k * tt.dt(), name, e);
        }
      };
      one("x", &StateVector::x, prm.floor_xy);
      one("y", &StateVector::y, prm.floor_xy);
      one("psi", &StateVector::psi, prm.floor_psi);
      one("r", &StateVector::r, prm.floor_r);
      one("u", &StateVector::u, prm.floor_uv);
      one("v", &StateVector::v, prm.floor_uv);
    }
    rep.fig3_pct.push_back(case3);
    for (const auto& [name, e] : by3) rep.fig3_by_param[name].push_back(e);
    if (case3 > worst3) worst3 = case3, rep.fig3_worst = what3;

    // Eq. 4 at the model's position at t*.
    const StateVector want = sim[static_cast<std::size_t>(kstar)];
    const double tstar = kstar * tt.dt() / sub;
    const auto ps = state_at_point(tt, r0, {want.x, want.y});
    if (!ps) {
      ++rep.eq4_not_located;
      continue;
    }
    double case4 = 0.0;
    std::string what4;
    const double eps = 1e-12;
    if (!(ps->node_rudder[0] <= rudder + eps && rudder <= ps->node_rudder[1] + eps)) ++rep.eq4_other_rudder;
    auto one = [&](const char* name, double got, double w, const std::array<double, 4>& f, double floor) {
      const double e = pct(got, w, f.data(), floor);
      rep.eq4_by_param[name].push_back(e);
      if (e > case4) case4 = e, what4 = describe(r0, rudder, tstar, name, e);
    };
    auto nodes = [&](double StateVector::*m) {
      return std::array<double, 4>{ps->node_states[0].*m, ps->node_states[1].*m, ps->node_states[2].*m,
                                   ps->node_states[3].*m};
    };
    one("psi", ps->state.psi, want.psi, nodes(&StateVector::psi), prm.floor_psi);
    one("r", ps->state.r, want.r, nodes(&StateVector::r), prm.floor_r);
    one("u", ps->state.u, want.u, nodes(&StateVector::u), prm.floor_uv);
    one("v", ps->state.v, want.v, nodes(&StateVector::v), prm.floor_uv);
    one("t", ps->t, tstar, ps->node_t, prm.floor_t);
    rep.eq4_pct.push_back(case4);
    if (case4 > worst4) worst4 = case4, rep.eq4_worst = what4;

    // The same point by the inverse bilinear map of the quad (for comparison).
    if (const auto pi = state_at_point(tt, r0, {want.x, want.y}, QuadRule::kInverseBilinear)) {
      double worst = 0.0;
      auto inv = [&](const char* name, double got, double w, const std::array<double, 4>& f, double floor) {
        const double e = pct(got, w, f.data(), floor);
        rep.inv_by_param[name].push_back(e);
        worst = std::max(worst, e);
      };
      auto nd = [&](double StateVector::*m) {
        return std::array<double, 4>{pi->node_states[0].*m, pi->node_states[1].*m, pi->node_states[2].*m,
                                     pi->node_states[3].*m};
      };
      inv("psi", pi->state.psi, want.psi, nd(&StateVector::psi), prm.floor_psi);
      inv("r", pi->state.r, want.r, nd(&StateVector::r), prm.floor_r);
      inv("u", pi->state.u, want.u, nd(&StateVector::u), prm.floor_uv);
      inv("v", pi->state.v, want.v, nd(&StateVector::v), prm.floor_uv);
      inv("t", pi->t, tstar, pi->node_t, prm.floor_t);
      rep.inv_pct.push_back(worst);
    }
  }
  return rep;
}

}  // namespace mpgc::opp
