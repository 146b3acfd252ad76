// Uniform-grid nearest-neighbour index over the RRT* nodes (2-D, bounded sampling region).
// The grid is rebuilt finer as the tree grows so a cell holds 2..8 nodes on average; nearest and
// k-nearest searches scan rings of cells outwards and stop when no unscanned cell can hold a
// closer point. Exact (not approximate) answers; deterministic order.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "mpgc/opp/geometry.hpp"

namespace mpgc::opp::detail {

class NodeGrid {
 public:
  void reset(double min_x, double min_y, double max_x, double max_y) {
    x0_ = min_x;
    y0_ = min_y;
    w_ = std::max(max_x - min_x, 1e-9);
    h_ = std::max(max_y - min_y, 1e-9);
    pts_.clear();
    rebuild(1);
  }

  int size() const { return static_cast<int>(pts_.size()); }

  void add(Vec2 p) {
    const int idx = size();
    pts_.push_back(p);
    if (pts_.size() > 8 * cells_.size()) {
      rebuild(pts_.size() / 2);
    } else {
      cells_[cell_of(p)].push_back({p.x, p.y, idx});
    }
  }

  int nearest(Vec2 q) const {
    int best = -1;
    double bd = INFINITY;
    int ci, cj;
    cell_ij(q, ci, cj);
    const double m = margin(q, ci, cj);
    const int rmax = std::max(nx_, ny_);
    for (int r = 0; r <= rmax; ++r) {
      ring(ci, cj, r, [&](const std::vector<Entry>& c) {
        for (const Entry& e : c) {
          const double d = (e.x - q.x) * (e.x - q.x) + (e.y - q.y) * (e.y - q.y);
          if (d < bd) {
            bd = d;
            best = e.idx;
          }
        }
      });
      const double lb = r * cell_ + m;
      if (best >= 0 && bd <= lb * lb) break;
    }
    return best;
  }

  // The k nearest nodes (any order) into `out` as (squared distance, index): the k least pairs,
  // ties of distance by index, so the set is unique. Every point of the scanned rings is kept and
  // the k-th distance found by selection, cheaper than a bounded heap for the k of RRT* (about
  // 40); once k are held, a point farther than the k-th is not even kept (it cannot be among the
  // k least), which spares most of the outer rings' selection work.
  void k_nearest(Vec2 q, int k, std::vector<std::pair<double, int>>& out) const {
    out.clear();
    if (k <= 0) return;
    int ci, cj;
    cell_ij(q, ci, cj);
    const double m = margin(q, ci, cj);
    const int rmax = std::max(nx_, ny_);
    const size_t kk = static_cast<size_t>(k);
    double kth = INFINITY;  // the k-th least distance so far
    for (int r = 0; r <= rmax; ++r) {
      ring(ci, cj, r, [&](const std::vector<Entry>& c) {
        for (const Entry& e : c) {
          const double d = (e.x - q.x) * (e.x - q.x) + (e.y - q.y) * (e.y - q.y);
          if (d <= kth) out.emplace_back(d, e.idx);
        }
      });
      if (out.size() < kk) continue;
      if (out.size() > kk) {
        std::nth_element(out.begin(), out.begin() + (kk - 1), out.end());
        out.resize(kk);
      } else {
        std::swap(*std::max_element(out.begin(), out.end()), out.back());
      }
      kth = out.back().first;  // out.back() is the k-th least pair
      const double lb = r * cell_ + m;
      if (kth <= lb * lb) break;
    }
    if (out.size() > kk) out.resize(kk);
  }

  // Every node within distance r (inclusive) of q.
  void within(Vec2 q, double rad, std::vector<std::pair<double, int>>& out) const {
    out.clear();
    const int i0 = clampi(static_cast<int>(std::floor((q.x - rad - x0_) * inv_)), nx_);
    const int i1 = clampi(static_cast<int>(std::floor((q.x + rad - x0_) * inv_)), nx_);
    const int j0 = clampi(static_cast<int>(std::floor((q.y - rad - y0_) * inv_)), ny_);
    const int j1 = clampi(static_cast<int>(std::floor((q.y + rad - y0_) * inv_)), ny_);
    const double r2 = rad * rad;
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j)
        for (const Entry& e : cells_[static_cast<size_t>(i) * ny_ + j]) {
          const double d = (e.x - q.x) * (e.x - q.x) + (e.y - q.y) * (e.y - q.y);
          if (d <= r2) out.emplace_back(d, e.idx);
        }
  }

 private:
  struct Entry {
    double x, y;
    int idx;
  };

  static int clampi(int v, int n) { return v < 0 ? 0 : (v >= n ? n - 1 : v); }
  void cell_ij(Vec2 p, int& i, int& j) const {
    i = clampi(static_cast<int>(std::floor((p.x - x0_) * inv_)), nx_);
    j = clampi(static_cast<int>(std::floor((p.y - y0_) * inv_)), ny_);
  }
  size_t cell_of(Vec2 p) const {
    int i, j;
    cell_ij(p, i, j);
    return static_cast<size_t>(i) * ny_ + j;
  }
  // Distance from q to the border of its own cell (0 when q lies outside the grid).
  double margin(Vec2 q, int i, int j) const {
    const double cx0 = x0_ + i * cell_, cy0 = y0_ + j * cell_;
    const double m = std::min({q.x - cx0, cx0 + cell_ - q.x, q.y - cy0, cy0 + cell_ - q.y});
    return std::max(0.0, m);
  }
  template <class F>
  void ring(int ci, int cj, int r, F&& f) const {
    if (r == 0) {
      f(cells_[static_cast<size_t>(ci) * ny_ + cj]);
      return;
    }
    const int ilo = ci - r, ihi = ci + r, jlo = cj - r, jhi = cj + r;
    const int ja = std::max(jlo, 0), jb = std::min(jhi, ny_ - 1);
    if (ilo >= 0)
      for (int j = ja; j <= jb; ++j) f(cells_[static_cast<size_t>(ilo) * ny_ + j]);
    if (ihi < nx_)
      for (int j = ja; j <= jb; ++j) f(cells_[static_cast<size_t>(ihi) * ny_ + j]);
    const int ia = std::max(ilo + 1, 0), ib = std::min(ihi - 1, nx_ - 1);
    if (jlo >= 0)
      for (int i = ia; i <= ib; ++i) f(cells_[static_cast<size_t>(i) * ny_ + jlo]);
    if (jhi < ny_)
      for (int i = ia; i <= ib; ++i) f(cells_[static_cast<size_t>(i) * ny_ + jhi]);
  }
  void rebuild(size_t target_cells) {
    target_cells = std::max<size_t>(target_cells, 1);
    cell_ = std::sqrt(w_ * h_ / static_cast<double>(target_cells));
    cell_ = std::max(cell_, 1e-6);
    inv_ = 1.0 / cell_;
    nx_ = std::max(1, static_cast<int>(std::ceil(w_ * inv_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(h_ * inv_)));
    cells_.assign(static_cast<size_t>(nx_) * ny_, {});
    for (int k = 0; k < size(); ++k) cells_[cell_of(pts_[k])].push_back({pts_[k].x, pts_[k].y, k});
  }

  double x0_ = 0, y0_ = 0, w_ = 1, h_ = 1, cell_ = 1, inv_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<Vec2> pts_;
  std::vector<std::vector<Entry>> cells_;
};

}  // namespace mpgc::opp::detail
