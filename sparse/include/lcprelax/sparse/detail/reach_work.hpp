#pragma once
// Internal: the work arrays and the depth-first search of a Gilbert–Peierls reach over the
// 2n nodes (v and u per position) of a hypersparse triangular solve with KLU's factors,
// shared by the transposed (hypersparse_solve.hpp) and the column (hypersparse_column_solve.hpp)
// solvers, which differ only in the edges of their graphs.
#include <cstddef>
#include <vector>

namespace lcprelax::sparse::detail {

struct ReachWork {
  std::vector<double> x;  // values by node
  std::vector<char> mark;
  std::vector<int> reach, stack, edge;  // reach filled from the top down; DFS stack; edge cursor

  void reserve(std::size_t nodes) {
    x.reserve(nodes);
    mark.reserve(nodes);
    for (auto* v : {&reach, &stack, &edge}) v->reserve(nodes);
  }
  void reset(std::size_t nodes) {
    x.assign(nodes, 0.0);
    mark.assign(nodes, 0);
    reach.resize(nodes);
    stack.resize(nodes);
    edge.resize(nodes);
  }

  /// Depth-first search from `root` (unmarked) without recursion; finished nodes go to
  /// reach[--top]; returns the new top. next_child(j, e) returns the target of node j's
  /// next edge from cursor e and advances e (skipping edges of zero entries), −1 when j
  /// has no edge left.
  template <class NextChild>
  int dfs(int root, int top, NextChild&& next_child) {
    int head = 0;
    stack[0] = root;
    mark[static_cast<std::size_t>(root)] = 1;
    edge[static_cast<std::size_t>(root)] = 0;
    while (head >= 0) {
      const int j = stack[static_cast<std::size_t>(head)];
      int& e = edge[static_cast<std::size_t>(j)];
      int child = -1;
      while (child < 0) {
        const int c = next_child(j, e);
        if (c < 0) break;
        if (!mark[static_cast<std::size_t>(c)]) child = c;
      }
      if (child >= 0) {
        mark[static_cast<std::size_t>(child)] = 1;
        edge[static_cast<std::size_t>(child)] = 0;
        stack[static_cast<std::size_t>(++head)] = child;
      } else {
        --head;
        reach[static_cast<std::size_t>(--top)] = j;
      }
    }
    return top;
  }

  /// Clears the values and marks of the nodes reach[top, end).
  void clear(int top, int end) {
    for (int t = top; t < end; ++t) {
      const std::size_t j = static_cast<std::size_t>(reach[static_cast<std::size_t>(t)]);
      x[j] = 0.0;
      mark[j] = 0;
    }
  }
};

}  // namespace lcprelax::sparse::detail
