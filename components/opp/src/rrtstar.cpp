// RRT* of seed 000 §3 with the problem set-up of §4 and the COLREG constraint of §5, behind the
// planning interface: every edge is checked by the ValidityChecker and costed by the Objective.
//
// Tree nodes carry the cost-to-come of eq. 5 (the cost of a waypoint sums over its path from the
// root), the path length (time = length / speed, for the target positions of eq. 3) and the unit
// direction of the incoming leg (for the turning angle of eq. 2 and the steering cost of eq. 6).
// Because the time at a node and the turning angle at a node depend on the path to it, a rewire
// re-validates the moved subtree (moving targets, COLREG, turn at the rewired node) and is
// refused if any edge there would become invalid; costs of the subtree are recomputed.
// The goal is not a tree node: every node within one step of it may hold a checked goal edge;
// the best solution is the cheapest node + goal edge and is snapshotted whenever it improves, so
// the reported cost never increases (anytime).
#include "mpgc/opp/rrtstar.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>

#include "mpgc/opp/node_grid.hpp"
#include "mpgc/runtime/params.hpp"

namespace mpgc::opp {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;
__extension__ typedef unsigned __int128 Key128;  // GCC's and Clang's; ISO C++ has no 128-bit integer

void require(bool ok, const char* field, const std::string& why) {
  if (!ok) throw std::invalid_argument(std::string("opp::Params.") + field + " " + why);
}
}  // namespace

void RrtStarParams::validate() const {
  auto fin = [](double v) { return std::isfinite(v); };
  require(fin(step) && step > 0, "step", "must be finite and > 0");
  require(fin(goal_bias) && goal_bias >= 0 && goal_bias <= 1, "goal_bias", "must be in [0, 1]");
  require(fin(rewire_factor) && rewire_factor >= 1, "rewire_factor", "must be >= 1");
  require(restart_after >= 0, "restart_after", "must be >= 0");
  require(fin(compliant_share) && compliant_share > 0 && compliant_share <= 1, "compliant_share",
          "must be in (0, 1]");
}

void Params::validate() const {
  ConstraintParams::validate();
  ObjectiveParams::validate();
  RrtStarParams::validate();
  Budget::validate();
}

ConstraintParams Params::constraints() const {
  ConstraintParams c = *this;
  c.colreg_spacing = step;
  return c;
}

namespace {

// Random numbers with a fixed recipe (not std::uniform_real_distribution) so that the same seed
// gives the same path on any standard library.
struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t s) : g(s) {}
  double u01() { return static_cast<double>(g() >> 11) * (1.0 / 9007199254740992.0); }
};

class Tree {
 public:
  Tree(const ValidityChecker& v, const Objective& o, const Params& pr, Stats& st, const Hooks& hooks, uint64_t seed)
      : v_(v), o_(o), pb_(v.problem()), pr_(pr), st_(st), hooks_(hooks), rng_(seed) {
    const Problem& pb = pb_;
    grid_.reset(pb.bounds.min_x, pb.bounds.min_y, pb.bounds.max_x, pb.bounds.max_y);
    nodes_.reserve(static_cast<size_t>(std::min(pr.max_iterations, 100000)) + 64);  // grows beyond
    const double dim = 2.0;
    k_rrt_ = pr.rewire_factor * (std::exp(1.0) + std::exp(1.0) / dim);
    const double measure = (pb.bounds.max_x - pb.bounds.min_x) * (pb.bounds.max_y - pb.bounds.min_y);
    r_rrt_ = pr.rewire_factor * std::sqrt(2.0 * (1.0 + 1.0 / dim) * (measure / kPi));
    goal_clear_ = o_.uses_fixed() ? v_.fixed_nearest(pb.goal.p) : kNaN;
    goal_fixed_ = o_.fixed_term_at(goal_clear_);
    approach_ = std::isfinite(pb.goal.heading) && pb.goal.heading_tolerance < kPi;
    root_fixed_d_ = v_.fixed_distance(true);
    Node root;
    root.p = pb.start;
    root.dir = {std::cos(pb.heading), std::sin(pb.heading)};
    set_clearance(root);
    root.cost = root.fixed + o_.moving_term(pb.start, 0.0);  // k = 0 terms of eq. 7-8
    root.len = 0.0;
    add_node(root);
    if (pr.connect_goal) try_goal(0);
  }

  ColregLevel colreg = ColregLevel::kFull;  // COLREG enforced on new edges
  double incumbent = kInf;  // the best cost of every tree so far (informed sampling)

  // Inserts a previous path as a chain from the root (warm start). Returns true if it reaches the goal.
  bool seed_chain(const std::vector<Vec2>& pts) {
    int cur = 0;
    for (const Vec2& p : pts) {
      if (norm2(p - pb_.goal.p) < 1e-12) break;
      if (!in_bounds(p)) break;
      const Node& a = nodes_[cur];
      const Vec2 seg = p - a.p;
      const double len = norm(seg);
      if (len < 1e-9) continue;
      const bool root = cur == 0;
      if (!v_.turn_ok(a.dir, seg, len, root)) break;
      if (edge_reject(a.p, a.len * inv_speed(), p, len, root) != ValidityChecker::kValid) break;
      Node n;
      n.p = p;
      set_clearance(n);
      if (!v_.fixed_clear(a.p, p, root ? root_fixed_d_ : pr_.safety_distance, clear_of(cur), clear_of(n))) break;
      n.dir = (1.0 / len) * seg;
      n.len = a.len + len;
      n.cost = a.cost + o_.edge_cost(a.dir, root, seg, len, n.fixed, p, n.len * inv_speed());
      n.parent = cur;
      cur = add_node(n);
      try_goal(cur);
    }
    update_best();
    return best_node_ >= 0;
  }

  // One RRT* iteration (§3).
  void iterate() {
    ++st_.iterations;
    const bool goal_sample = rng_.u01() < pr_.goal_bias;
    Vec2 q;
    if (goal_sample) {
      q = pb_.goal.p;
      // With an arrival heading (§6), every other goal sample is an approach point one step
      // before the goal on a course inside the tolerance, so nodes appear where a goal edge
      // can meet the heading.
      if (approach_ && rng_.u01() < 0.5) {
        const double h = pb_.goal.heading + (2.0 * rng_.u01() - 1.0) * pb_.goal.heading_tolerance;
        const double dist = pr_.step * (0.5 + 0.5 * rng_.u01());
        q = pb_.goal.p - dist * Vec2{std::cos(h), std::sin(h)};
        q.x = std::clamp(q.x, pb_.bounds.min_x, pb_.bounds.max_x);
        q.y = std::clamp(q.y, pb_.bounds.min_y, pb_.bounds.max_y);
      }
    } else if (!informed_sample(q)) {
      q.x = pb_.bounds.min_x + rng_.u01() * (pb_.bounds.max_x - pb_.bounds.min_x);
      q.y = pb_.bounds.min_y + rng_.u01() * (pb_.bounds.max_y - pb_.bounds.min_y);
    }
    const int near = grid_.nearest(q);
    const Vec2 pn = nodes_[near].p;
    const double d = norm(q - pn);
    if (d < 1e-9) return;
    const Vec2 xnew = d > pr_.step ? pn + (pr_.step / d) * (q - pn) : q;
    // A goal sample that reaches the goal is not a node: it asks the goal's neighbours for edges.
    if (norm2(xnew - pb_.goal.p) < 1e-12) {
      grid_.within(pb_.goal.p, pr_.step, nbh_);
      for (const auto& [d2, j] : nbh_) {
        (void)d2;
        if (!nodes_[j].goal_edge) try_goal(j);
      }
      update_best();
      return;
    }
    neighbours(xnew, near);
    xnew_ = xnew;
    clear_new_ = o_.uses_fixed() ? v_.fixed_nearest(xnew) : kNaN;
    if (end_blocked()) return;
    const double fixed_new = o_.fixed_term_at(clear_new_);
    // Choose parent: the candidates are checked in order of cost (the first valid wins). The
    // steering term (an acos) is paid only for those whose cost bound without it does not rule
    // them out: the cheapest candidate not yet costed is at least its bound.
    cand_.clear();
    for (const auto& [d2, j] : nbh_) {
      const Node& a = nodes_[j];
      const double len = std::sqrt(d2);
      if (len < 1e-9) return;  // duplicate of an existing node
      const Vec2 seg = xnew - a.p;
      if (!v_.turn_ok(a.dir, seg, len, j == 0)) {
        ++rejects_[ValidityChecker::kTurn];
        continue;
      }
      const double mv = o_.moving_term(xnew, (a.len + len) * inv_speed());
      cand_.push_back({a.cost + o_.edge_sum(0.0, fixed_new, mv, len), mv, len, j});
    }
    auto before = [](const Cand& x, const Cand& y) { return x.cost < y.cost || (x.cost == y.cost && x.idx < y.idx); };
    std::sort(cand_.begin(), cand_.end(), before);
    auto after = [&](const Cand& x, const Cand& y) { return before(y, x); };  // min-heap of costed ones
    costed_.clear();
    int parent = -1;
    double parent_cost = 0, parent_len = 0;
    for (size_t next = 0;;) {
      while (next < cand_.size() && (costed_.empty() || !(costed_.front().cost < cand_[next].cost))) {
        Cand c = cand_[next++];
        const Node& a = nodes_[c.idx];
        c.cost = a.cost + o_.edge_sum(o_.steer_term(a.dir, xnew - a.p, c.len, c.idx == 0), fixed_new, c.moving, c.len);
        costed_.push_back(c);
        std::push_heap(costed_.begin(), costed_.end(), after);
      }
      if (costed_.empty()) break;
      std::pop_heap(costed_.begin(), costed_.end(), after);
      const Cand c = costed_.back();
      costed_.pop_back();
      const Node& a = nodes_[c.idx];
      ++st_.edge_checks;
      const auto r = edge_reject(a.p, a.len * inv_speed(), xnew, c.len, c.idx == 0);
      if (r != ValidityChecker::kValid) {
        ++rejects_[r];
        continue;
      }
      if (!fixed_clear(c.idx, a.p, xnew)) {
        ++rejects_[ValidityChecker::kFixed];
        continue;
      }
      parent = c.idx;
      parent_cost = c.cost;
      parent_len = c.len;
      break;
    }
    if (parent < 0) return;
    Node n;
    n.p = xnew;
    n.dir = (1.0 / parent_len) * (xnew - nodes_[parent].p);
    n.fixed = fixed_new;
    n.clear = clear_new_;
    n.cost = parent_cost;
    n.len = nodes_[parent].len + parent_len;
    n.parent = parent;
    const int ni = add_node(n);
    // Rewire (§3): the new node as parent of its neighbours.
    for (const auto& [d2, j] : nbh_) {
      if (j == parent || j == 0) continue;
      rewire(ni, j, std::sqrt(d2));
    }
    if (pr_.connect_goal) try_goal(ni);
    update_best();
  }

  double best_cost() const { return snap_cost_; }
  bool solved() const { return snap_cost_ < kInf; }
  const std::vector<Vec2>& best_path() const { return snap_; }
  int size() const { return static_cast<int>(nodes_.size()); }
  ColregLevel best_level() const { return snap_level_; }
  const uint64_t* rejects() const { return rejects_; }
  int goal_attempts() const { return goal_attempts_; }
  double closest_to_goal() const { return closest_goal_; }

 private:
  struct Node {
    Vec2 p, dir;
    double cost = 0, len = 0, fixed = 0, goal_cost = kInf;
    double clear = kNaN;  // fixed().nearest(p), NaN until needed (fixed_clear's certificate)
    int parent = -1, first_child = -1, next_sibling = -1;
    bool goal_edge = false;
    uint8_t goal_fixed = 0;  // the fixed clearance of the goal edge: 0 unknown, 1 clear, 2 blocked
  };
  struct Cand {
    double cost, moving, len;  // cost: the bound without steering until costed
    int idx;
  };

  // Informed sampling (RrtStarParams::informed): a point uniform in the ellipse where a path
  // cheaper than the incumbent can pass (length < incumbent / gamma_l) and inside the sampling
  // box. False (sample the box) without an incumbent, where the ellipse is no smaller than the
  // box, or when 16 tries all fell outside the box.
  bool informed_sample(Vec2& q) {
    if (!pr_.informed || !(incumbent < kInf) || !(pr_.gamma_l > 0.0)) return false;
    const Vec2 s = pb_.start, g = pb_.goal.p;
    const double a = 0.5 * incumbent / pr_.gamma_l, f = 0.5 * norm(g - s);
    if (!(a > f)) return false;
    const double b = std::sqrt(a * a - f * f);
    const double box = (pb_.bounds.max_x - pb_.bounds.min_x) * (pb_.bounds.max_y - pb_.bounds.min_y);
    if (!(kPi * a * b < box)) return false;
    const Vec2 c = 0.5 * (s + g);
    const Vec2 e = f > 0.0 ? (0.5 / f) * (g - s) : Vec2{1.0, 0.0};  // major axis
    for (int k = 0; k < 16; ++k) {
      const double r = std::sqrt(rng_.u01()), th = 2.0 * kPi * rng_.u01();
      const double u = a * r * std::cos(th), v = b * r * std::sin(th);
      q = c + u * e + v * Vec2{-e.y, e.x};
      if (in_bounds(q)) return true;
    }
    return false;
  }

  double inv_speed() const { return 1.0 / pb_.speed; }
  bool in_bounds(Vec2 p) const {
    return p.x >= pb_.bounds.min_x && p.x <= pb_.bounds.max_x && p.y >= pb_.bounds.min_y && p.y <= pb_.bounds.max_y;
  }

  int add_node(const Node& n) {
    const int i = static_cast<int>(nodes_.size());
    nodes_.push_back(n);
    if (n.parent >= 0) link(n.parent, i);
    grid_.add(n.p);
    fixed_cache_.push_back(0);
    return i;
  }
  void link(int parent, int child) {
    nodes_[child].parent = parent;
    nodes_[child].next_sibling = nodes_[parent].first_child;
    nodes_[parent].first_child = child;
  }
  void unlink(int child) {
    const int p = nodes_[child].parent;
    int* slot = &nodes_[p].first_child;
    while (*slot != child) slot = &nodes_[*slot].next_sibling;
    *slot = nodes_[child].next_sibling;
    nodes_[child].next_sibling = -1;
  }

  void neighbours(Vec2 x, int near) {
    const double n = static_cast<double>(nodes_.size());
    if (pr_.k_nearest) {
      const int k = static_cast<int>(std::ceil(k_rrt_ * std::log(n + 1.0)));
      grid_.k_nearest(x, k, nbh_);
    } else {
      const double card = n + 1.0;
      const double r = std::min(pr_.step, r_rrt_ * std::sqrt(std::log(card) / card));
      grid_.within(x, r, nbh_);
    }
    bool has_near = false;
    for (const auto& e : nbh_) has_near = has_near || e.second == near;
    if (!has_near) nbh_.emplace_back(norm2(x - nodes_[near].p), near);
    // The neighbour set arrives in heap / cell order: sort for a deterministic, readable order.
    // Sorted as one 128-bit key each, (the distance's bits, the index): a non-negative double's
    // bits order as the double does, so the order is the pairs' own, with a branch-free compare.
    keys_.clear();
    for (const auto& [d2, j] : nbh_) {
      uint64_t b;
      std::memcpy(&b, &d2, sizeof b);
      keys_.push_back((static_cast<Key128>(b) << 32) | static_cast<uint32_t>(j));
    }
    std::sort(keys_.begin(), keys_.end());
    for (size_t i = 0; i < keys_.size(); ++i) {
      const uint64_t b = static_cast<uint64_t>(keys_[i] >> 32);
      std::memcpy(&nbh_[i].first, &b, sizeof b);
      nbh_[i].second = static_cast<int>(static_cast<uint32_t>(keys_[i]));
    }
    // fixed_cache_[j]: 0 unknown, 1 clear, 2 blocked for the segment j <-> current new point.
    for (const auto& e : nbh_) fixed_cache_[e.second] = 0;
  }

  // The clearance of the fixed obstacles at p, with the node term of eq. 7 from it (one query).
  void set_clearance(Node& n) const {
    n.clear = o_.uses_fixed() ? v_.fixed_nearest(n.p) : kNaN;
    n.fixed = o_.fixed_term_at(n.clear);
  }
  double clear_of(int j) {
    if (std::isnan(nodes_[j].clear)) nodes_[j].clear = v_.fixed_nearest(nodes_[j].p);
    return nodes_[j].clear;
  }
  double clear_of(Node& n) const {
    if (std::isnan(n.clear)) n.clear = v_.fixed_nearest(n.p);
    return n.clear;
  }
  double clear_new() {
    if (std::isnan(clear_new_)) clear_new_ = v_.fixed_nearest(xnew_);
    return clear_new_;
  }
  double goal_clear() {
    if (std::isnan(goal_clear_)) goal_clear_ = v_.fixed_nearest(pb_.goal.p);
    return goal_clear_;
  }

  // A new point closer than d_safety to a fixed obstacle ends no leg (eq. 4 at its end): every
  // candidate parent would be refused by fixed_clear's certificate, after paying for its cost and
  // its targets. Refused here at once, the same way (half the canal's and 43 % of the Annapolis
  // chart's new points; counted as fixed rejections, the turn's first as before). A leg from the
  // start has its own distance (escape) and is left to the search.
  bool end_blocked() {
    if (std::isnan(clear_new_)) return false;
    double reach = 0.0;
    for (const auto& e : nbh_) {
      if (e.second == 0) return false;
      const Vec2 a = nodes_[e.second].p;
      reach = std::max({reach, std::fabs(a.x), std::fabs(a.y)});
    }
    if (!v_.fixed_blocks_end(xnew_, clear_new_, pr_.safety_distance, reach)) return false;
    for (const auto& [d2, j] : nbh_) {
      const Node& a = nodes_[j];
      const double len = std::sqrt(d2);
      if (len < 1e-9) return true;  // duplicate of an existing node
      ++rejects_[v_.turn_ok(a.dir, xnew_ - a.p, len, false) ? ValidityChecker::kFixed : ValidityChecker::kTurn];
    }
    return true;
  }

  // The leg between node j and the current new point xnew_ (either way round).
  bool fixed_clear(int j, Vec2 a, Vec2 b) {
    if (j == 0) return v_.fixed_clear(a, b, root_fixed_d_, clear_of(0), clear_new());  // leg from the start (escape)
    if (fixed_cache_[j] == 0)
      fixed_cache_[j] = v_.fixed_clear(a, b, pr_.safety_distance, clear_of(j), clear_new()) ? 1 : 2;
    return fixed_cache_[j] == 1;
  }

  ValidityChecker::Reject edge_reject(Vec2 a, double ta, Vec2 b, double len, bool from_root = false) const {
    return v_.moving(a, ta, b, len, colreg, from_root && pr_.escape_start);
  }

  // Tries the edge node -> goal (heading tolerance, turn, targets, COLREG, fixed).
  void try_goal(int i) {
    Node& a = nodes_[i];
    const Vec2 seg = pb_.goal.p - a.p;
    const double len2 = norm2(seg);
    closest_goal_ = std::min(closest_goal_, std::sqrt(len2));
    if (len2 > pr_.step * pr_.step) return;
    ++goal_attempts_;
    const double len = std::sqrt(len2);
    if (len < 1e-9) return;
    if (!v_.goal_heading_ok(seg)) {
      ++rejects_[ValidityChecker::kGoalHeading];
      return;
    }
    if (!v_.turn_ok(a.dir, seg, len, i == 0)) {
      ++rejects_[ValidityChecker::kTurn];
      return;
    }
    const double ta = a.len * inv_speed();
    ++st_.edge_checks;
    const auto r = edge_reject(a.p, ta, pb_.goal.p, len, i == 0);
    if (r != ValidityChecker::kValid) {
      ++rejects_[r];
      return;
    }
    // The goal edge of a node is tried again at every goal sample; its fixed clearance never changes.
    if (a.goal_fixed == 0)
      a.goal_fixed = v_.fixed_clear(a.p, pb_.goal.p, i == 0 ? root_fixed_d_ : pr_.safety_distance, clear_of(i), goal_clear())
                         ? 1 : 2;
    if (a.goal_fixed != 1) {
      ++rejects_[ValidityChecker::kFixed];
      return;
    }
    a.goal_edge = true;
    a.goal_cost = o_.edge_cost(a.dir, i == 0, seg, len, goal_fixed_, pb_.goal.p, (a.len + len) * inv_speed());
    goal_nodes_.push_back(i);
    goal_dirty_ = true;
  }

  // x_new (index s) as the new parent of node j at distance len (rewiring, §3).
  void rewire(int s, int j, double len) {
    const Node& a = nodes_[s];
    Node& b = nodes_[j];
    const Vec2 seg = b.p - a.p;
    const double tb = (a.len + len) * inv_speed();
    const double mv = o_.moving_term(b.p, tb), bar = b.cost - 1e-12 * std::max(1.0, std::fabs(b.cost));
    if (!(a.cost + o_.edge_sum(0.0, b.fixed, mv, len) < bar)) return;  // no cheaper even unsteered
    const double new_cost = a.cost + o_.edge_sum(o_.steer_term(a.dir, seg, len, false), b.fixed, mv, len);
    if (!(new_cost < bar)) return;
    if (!v_.turn_ok(a.dir, seg, len, false)) return;
    ++st_.edge_checks;
    if (edge_reject(a.p, a.len * inv_speed(), b.p, len) != ValidityChecker::kValid) return;
    if (!fixed_clear(j, a.p, b.p)) return;
    const Vec2 new_dir = (1.0 / len) * seg;
    const double new_len = a.len + len;
    // Re-validate and re-cost the subtree of j under its new time and incoming direction.
    upd_.clear();
    upd_.push_back({j, new_cost, new_len, 0.0});
    const bool uniform = !v_.has_targets() && pr_.gamma_s == 0.0;  // costs shift by one delta
    const bool need_turn = v_.turn_limited();
    const bool need_check = v_.has_targets() || need_turn;
    if (uniform && !need_check) {
      apply_uniform(j, new_cost - b.cost, new_len - b.len, new_dir, s);
      return;
    }
    for (size_t k = 0; k < upd_.size(); ++k) {
      const int mi = upd_[k].idx;
      const Node& mnode = nodes_[mi];
      const Vec2 mdir = mi == j ? new_dir : mnode.dir;
      const double tm = upd_[k].len * inv_speed();
      if (mnode.goal_edge) {
        const Vec2 gs = pb_.goal.p - mnode.p;
        const double gl = norm(gs);
        if (mi == j && !v_.turn_ok(mdir, gs, gl, false)) return;
        if (v_.has_targets() && edge_reject(mnode.p, tm, pb_.goal.p, gl) != ValidityChecker::kValid) return;
        upd_[k].goal_cost = o_.edge_cost(mdir, false, gs, gl, goal_fixed_, pb_.goal.p, (upd_[k].len + gl) * inv_speed());
      }
      for (int c = mnode.first_child; c >= 0; c = nodes_[c].next_sibling) {
        const Node& cn = nodes_[c];
        const Vec2 cs = cn.p - mnode.p;
        const double cl = norm(cs);
        if (mi == j && !v_.turn_ok(mdir, cs, cl, false)) return;
        if (v_.has_targets() && edge_reject(mnode.p, tm, cn.p, cl) != ValidityChecker::kValid) return;
        const double cc = uniform ? cn.cost + (new_cost - b.cost)
                                  : upd_[k].cost + o_.edge_cost(mdir, false, cs, cl, cn.fixed, cn.p,
                                                                (upd_[k].len + cl) * inv_speed());
        upd_.push_back({c, cc, upd_[k].len + cl, 0.0});
      }
    }
    // Commit.
    ++st_.rewires;
    unlink(j);
    link(s, j);
    nodes_[j].dir = new_dir;
    for (const Upd& u : upd_) {
      Node& n = nodes_[u.idx];
      n.cost = u.cost;
      n.len = u.len;
      if (n.goal_edge) {
        n.goal_cost = u.goal_cost;
        goal_dirty_ = true;
      }
    }
  }

  void apply_uniform(int j, double dcost, double dlen, Vec2 new_dir, int s) {
    ++st_.rewires;
    unlink(j);
    link(s, j);
    nodes_[j].dir = new_dir;
    // Iterative DFS over the subtree: same cost and length shift everywhere (no targets, no eq. 6).
    stack_.clear();
    stack_.push_back(j);
    while (!stack_.empty()) {
      const int mi = stack_.back();
      stack_.pop_back();
      Node& n = nodes_[mi];
      n.cost += dcost;
      n.len += dlen;
      if (n.goal_edge) goal_dirty_ = true;
      for (int c = n.first_child; c >= 0; c = nodes_[c].next_sibling) stack_.push_back(c);
    }
  }

  void update_best() {
    if (!goal_dirty_) return;
    goal_dirty_ = false;
    double best = kInf;
    int bi = -1;
    for (int i : goal_nodes_) {
      const double c = nodes_[i].cost + nodes_[i].goal_cost;
      if (c < best) {
        best = c;
        bi = i;
      }
    }
    best_node_ = bi;
    if (bi >= 0 && best < snap_cost_) {
      snap_cost_ = best;
      snap_level_ = colreg;
      snap_.clear();
      for (int i = bi; i >= 0; i = nodes_[i].parent) snap_.push_back(nodes_[i].p);
      std::reverse(snap_.begin(), snap_.end());
      snap_.push_back(pb_.goal.p);
      if (st_.first_solution_iteration < 0) {
        st_.first_solution_iteration = st_.iterations;
        if (hooks_.elapsed) st_.first_solution_time = hooks_.elapsed();
      }
    }
  }

  struct Upd {
    int idx;
    double cost, len, goal_cost;
  };

  const ValidityChecker& v_;
  const Objective& o_;
  const Problem& pb_;
  const Params& pr_;
  Stats& st_;
  const Hooks& hooks_;
  Rng rng_;
  detail::NodeGrid grid_;
  std::vector<Node> nodes_;
  std::vector<uint8_t> fixed_cache_;
  std::vector<std::pair<double, int>> nbh_;
  std::vector<Key128> keys_;
  std::vector<Cand> cand_, costed_;
  std::vector<Upd> upd_;
  std::vector<int> stack_;
  std::vector<int> goal_nodes_;
  bool goal_dirty_ = false;
  bool approach_ = false;
  int best_node_ = -1;
  double snap_cost_ = kInf;
  ColregLevel snap_level_ = ColregLevel::kNone;
  std::vector<Vec2> snap_;
  double k_rrt_ = 0, r_rrt_ = 0, goal_fixed_ = 0, root_fixed_d_ = 0;
  Vec2 xnew_;                                    // the current iteration's new point
  double goal_clear_ = kNaN, clear_new_ = kNaN;  // fixed().nearest of the goal, of xnew_
  uint64_t rejects_[ValidityChecker::kRejectCount] = {};
  int goal_attempts_ = 0;
  double closest_goal_ = kInf;
};

}  // namespace

Result plan(const Problem& problem, const Params& params, const Hooks& hooks, const std::vector<Vec2>& warm) {
  Result res;
  const double t0 = hooks.elapsed ? hooks.elapsed() : 0.0;
  try {
    params.validate();
  } catch (const std::invalid_argument& e) {
    res.status = Status::kInvalidInput;
    res.reason = e.what();
    return res;
  }
  const ConstraintParams constraints = params.constraints();
  res.reason = check_problem(problem, constraints);
  if (!res.reason.empty()) {
    res.status = Status::kInvalidInput;
    return res;
  }
  const ValidityChecker checker(problem, constraints);
  const Objective objective(problem, params);
  if (norm(problem.goal.p - problem.start) < 1e-6) {
    res.status = Status::kOk;
    res.colreg_compliant = true;
    res.path = {{problem.start, 0.0}};
    return res;
  }
  auto tree = std::make_unique<Tree>(checker, objective, params, res.stats, hooks, params.seed);
  tree->colreg = problem.colreg ? ColregLevel::kFull : ColregLevel::kNone;
  bool any_duty = false, any_17c = false;
  for (const Target& t : problem.targets) {
    any_duty = any_duty || is_duty(t.pinned.obligation);
    any_17c = any_17c || t.pinned.obligation == Obligation::kCrossingStandOn;
  }
  if (!warm.empty()) res.stats.warm_started = tree->seed_chain(warm_tail(warm, problem.start));
  // Best over restarted trees (the incumbent survives a restart, so the cost stays monotone).
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<Vec2> best_pts;
  ColregLevel best_level = tree->colreg;
  int last_improvement = 0;
  auto adopt = [&] {
    if (!(tree->best_cost() < best_cost)) return;
    best_cost = tree->best_cost();
    best_pts = tree->best_path();
    best_level = tree->best_level();
    last_improvement = res.stats.iterations;
  };
  adopt();
  // Budget shares after which a level still without a solution gives way to the next (§6): the
  // full constraint for compliant_share; the pinned duties (rule 17(b): the stand-on ship may act
  // when the other does not), with rule 17(c) for a quarter of the rest and without it to half the
  // rest; then none.
  const double cs = params.compliant_share;
  auto share = [&](ColregLevel l) {
    if (l == ColregLevel::kFull) return cs;
    if (l == ColregLevel::kPinned17c && any_duty) return cs + 0.25 * (1.0 - cs);
    return 0.5 * (1.0 + cs);
  };
  auto next = [&](ColregLevel l) {
    if (l == ColregLevel::kFull && any_17c) return ColregLevel::kPinned17c;
    if ((l == ColregLevel::kFull || l == ColregLevel::kPinned17c) && any_duty) return ColregLevel::kPinned;
    return ColregLevel::kNone;
  };
  while (res.stats.iterations < params.max_iterations) {
    const double el = hooks.elapsed ? hooks.elapsed() - t0 : 0.0;
    if (hooks.elapsed && el >= params.time_budget) break;
    if (hooks.stop && hooks.stop()) break;
    if (tree->colreg != ColregLevel::kNone && best_pts.empty()) {
      const double sh = share(tree->colreg);
      if (res.stats.iterations >= static_cast<int>(std::ceil(sh * params.max_iterations)) ||
          (hooks.elapsed && el >= sh * params.time_budget)) {
        if (tree->colreg == ColregLevel::kFull) res.stats.iterations_compliant = res.stats.iterations;
        // §6: relax; the tree stays valid under the weaker constraint.
        tree->colreg = next(tree->colreg);
        // The previous plan, if valid at the level now in force, is the incumbent there as it is
        // at the full one: a relaxed manoeuvre is held from re-plan to re-plan unless a cheaper
        // one is found, not drawn afresh each time (DNV 54 swung between port and starboard for
        // 400 s, then ran out of room).
        if (!warm.empty() && tree->seed_chain(warm_tail(warm, problem.start))) {
          res.stats.warm_started = true;
          adopt();
        }
      }
    }
    // A tree whose solution has not improved for restart_after iterations is stuck in one timing
    // of the targets (the time at a node is fixed by its path): start a fresh tree.
    if (params.restart_after > 0 && !best_pts.empty() && res.stats.iterations - last_improvement >= params.restart_after) {
      const ColregLevel colreg = tree->colreg;
      ++res.stats.restarts;
      tree = std::make_unique<Tree>(checker, objective, params, res.stats, hooks,
                                    params.seed + 0x9E3779B97F4A7C15ULL * static_cast<uint64_t>(res.stats.restarts));
      tree->colreg = colreg;
      last_improvement = res.stats.iterations;
    }
    tree->incumbent = best_cost;
    tree->iterate();
    adopt();
    if (hooks.progress) hooks.progress(res.stats.iterations, best_cost);
  }
  if (tree->colreg == ColregLevel::kFull) res.stats.iterations_compliant = res.stats.iterations;
  res.stats.nodes = tree->size();
  res.stats.planning_time = hooks.elapsed ? hooks.elapsed() - t0 : 0.0;
  if (res.stats.first_solution_time >= 0) res.stats.first_solution_time -= t0;
  if (best_pts.empty()) {
    const uint64_t* r = tree->rejects();
    std::ostringstream os;
    os << "no path within " << res.stats.iterations << " iterations";
    if (hooks.elapsed) os << " / " << fmt(res.stats.planning_time) << " s";
    os << " (" << tree->size() << " nodes; ";
    if (tree->goal_attempts() == 0)
      os << "the tree never came within one step of the goal, closest " << fmt(tree->closest_to_goal()) << " m";
    else
      os << tree->goal_attempts() << " goal connections tried";
    os << "; edges rejected: fixed obstacles " << r[ValidityChecker::kFixed] << ", targets " << r[ValidityChecker::kTarget] << ", turn "
       << r[ValidityChecker::kTurn] << ", COLREG " << r[ValidityChecker::kColreg] << ", arrival heading " << r[ValidityChecker::kGoalHeading] << ")";
    res.status = Status::kNoPath;
    res.reason = os.str();
    return res;
  }
  const bool relaxed = problem.colreg && best_level != ColregLevel::kFull;
  Stats stats = res.stats;
  res = finish(problem, best_pts, relaxed, checker, objective);
  res.stats = stats;
  if (relaxed)
    res.reason = best_level == ColregLevel::kPinned17c
                     ? "no COLREG-compliant path within the compliant budget share; relaxed to the pinned duties and "
                       "rule 17(c) (stand-on targets otherwise unconstrained)"
                 : best_level == ColregLevel::kPinned
                     ? "no COLREG-compliant path within the compliant budget share; relaxed to the pinned obligations "
                       "(stand-on and no-risk targets unconstrained)"
                     : "no COLREG-compliant path within the compliant budget share; constraint relaxed";
  if (params.escape_start) {
    std::string inside;
    if (checker.fixed_clearance(problem.start) < params.safety_distance) inside = "a fixed obstacle or the chart's edge";
    for (const Target& t : problem.targets)
      if (inside.empty() && norm(t.p - problem.start) < params.safety_distance + t.margin)
        inside = "target id " + std::to_string(t.id);
    if (!inside.empty())
      res.reason += std::string(res.reason.empty() ? "" : "; ") + "start within d_safety of " + inside +
                    ": the first leg only keeps its initial distance (escape)";
  }
  return res;
}

std::string check_path(const Problem& pb, const Params& pr, const std::vector<Vec2>& path, bool colreg) {
  const ConstraintParams c = pr.constraints();
  return ValidityChecker(pb, c).check_path(path, colreg);
}

CostTerms path_cost(const Problem& pb, const Params& pr, const std::vector<Vec2>& path) {
  return Objective(pb, pr).path_cost(path);
}

void RrtStar::declare(rt::ParamSet& ps) {
  ps.add("plan.step", &p_.step, 500.0, "m", 1.0, 1e5, "RRT* steer step (also the spacing of the COLREG checks along a leg)");
  ps.add("plan.goal_bias", &p_.goal_bias, 0.05, "-", 0.0, 1.0, "probability of sampling the goal");
  ps.add("plan.rewire_factor", &p_.rewire_factor, 1.1, "-", 1.0, 10.0, "scales the k-nearest neighbourhood");
  ps.add("plan.k_nearest", &p_.k_nearest, true, "k-nearest neighbourhood (false: the shrinking radius of RRT*)");
  ps.add("plan.connect_goal", &p_.connect_goal, true,
         "try a goal edge from every new node within one step (false: only goal samples connect, as OMPL's RRTstar)");
  ps.add("plan.informed", &p_.informed, false,
         "once a path exists, sample only the ellipse where a cheaper one can pass (informed RRT*)");
  ps.add("plan.restart_after", &p_.restart_after, 1000, "-", 0, 10000000,
         "iterations without improvement before a fresh tree is grown (0 = never)");
  ps.add("plan.compliant_share", &p_.compliant_share, 0.5, "-", 0.01, 1.0,
         "budget share after which a compliant pass without any solution is relaxed");
}

Result RrtStar::solve(const Request& rq, const Hooks& hooks) {
  Params prm;
  static_cast<ConstraintParams&>(prm) = rq.constraints;
  static_cast<ObjectiveParams&>(prm) = rq.objective;
  static_cast<Budget&>(prm) = rq.budget;
  static_cast<RrtStarParams&>(prm) = p_;
  return plan(rq.problem, prm, hooks, rq.warm);
}

}  // namespace mpgc::opp
