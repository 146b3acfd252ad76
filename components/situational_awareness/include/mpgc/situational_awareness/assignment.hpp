// Global-nearest-neighbour assignment: the optimal one-to-one matching of rows (tracks) to
// columns (measurements) that minimises the summed cost, each row free to stay unassigned at a
// fixed price (the gate). Hungarian algorithm with shortest augmenting paths, O(n^2 m).
#pragma once

#include <vector>

namespace mpgc::sa {

// cost[i][j] for i < rows, j < cols; a cost >= unassigned_cost (or non-finite) means "not allowed".
// Returns for every row the assigned column or -1. Minimises sum(cost of assigned pairs) +
// unassigned_cost * (number of unassigned rows), so a pair is only used when it beats leaving
// both its row and column free.
std::vector<int> solve_assignment(const std::vector<std::vector<double>>& cost, int cols, double unassigned_cost);

}  // namespace mpgc::sa
