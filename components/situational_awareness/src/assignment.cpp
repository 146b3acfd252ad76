#include "mpgc/situational_awareness/assignment.hpp"

#include <cmath>
#include <limits>

namespace mpgc::sa {

std::vector<int> solve_assignment(const std::vector<std::vector<double>>& cost, int cols, double unassigned_cost) {
  const int n = static_cast<int>(cost.size());
  if (n == 0) return {};
  // Square-up: columns 0..cols-1 are measurements, cols+i is row i's private "unassigned" column.
  const int m = cols + n;
  const double kForbidden = 1e12 + 4.0 * unassigned_cost;  // never chosen while a dummy is free
  auto c = [&](int i, int j) {
    if (j >= cols) return j - cols == i ? unassigned_cost : kForbidden;
    const double v = cost[i][j];
    return (std::isfinite(v) && v < unassigned_cost) ? v : kForbidden;
  };
  // Shortest-augmenting-path Hungarian (potentials u, v; 1-based with a virtual column 0).
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = c(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> out(n, -1);
  for (int j = 1; j <= cols; ++j) {
    if (p[j] != 0 && c(p[j] - 1, j - 1) < kForbidden) out[p[j] - 1] = j - 1;
  }
  return out;
}

}  // namespace mpgc::sa
