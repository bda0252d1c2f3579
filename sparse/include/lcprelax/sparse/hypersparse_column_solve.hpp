#pragma once
// Hypersparse solves with a KLU factorization: x = A⁻¹b for a sparse b, with work
// proportional to the nonzeros of the factors that the solution touches, not to n or
// nnz(L + U). Used for the entering column of each Lemke pivot (B₀⁻¹ times a column of the
// tableau, lcp/lemke_basis.hpp), where a dense triangular solve per pivot (klu_solve) was
// more than half of a pile step's time (measured on a 1,000-body pile, perf).
//
// Method (the mirror of hypersparse_solve.hpp's transposed solve). KLU factorizes
// N = L·U + F with N_kl = A(P[k], Q[l]) / Rs[k] (KluLu::Factors). Ax = b is N u = b̃ with
// b̃_k = b_{P[k]} / Rs[k] and x_{Q[l]} = u_l. As N is block upper triangular, N u = b̃
// reads, block by block from the last,
//     L v = b̃ − F u,    U u = v.
// Nodes v_k and u_k per position k; an edge from x to y when y's equation uses x:
//     v_p → v_q  (L_qp ≠ 0, q > p),   v_p → u_p,   u_q → u_p  (U_pq ≠ 0, p < q),
//     u_q → v_p  (F_pq ≠ 0, p in an earlier block).
// The graph is acyclic (inside a block v runs forward, u backward and v → u only; F leads
// to earlier blocks), so a depth-first search from the nonzeros of b̃ gives every node
// that can be nonzero in reverse topological order (Gilbert & Peierls 1988; Davis,
// "Direct Methods for Sparse Linear Systems", SIAM 2006, §3.2), and the numeric solve
// visits those nodes and their edges only. KLU's factors are column-wise already, which
// is the order a column-oriented (scatter) solve needs, so no copy is transposed.
//
// solve_dense is the same solve for a dense right-hand side without the search: positions
// in their topological order (blocks from the last; v forward, then u backward, in each),
// a column of L, U or F scattered only when its solution entry is nonzero. Work O(n) plus
// the factors' entries in the columns of nonzero entries: for solutions of medium density,
// where the reach costs as much as the solve and klu_solve scatters every column, zeros
// included (Lemke's entering columns on piles of hundreds of bodies: ~40% nonzero). The
// operations on nonzero entries are klu_solve's, in its order (column-oriented L and U
// solves per block, then the block's F columns), so the results agree to roundoff.
//
// Conventions: no tolerance (exact zeros of the factors are skipped; the result may hold
// numerically zero entries, all reached positions are reported). Rounding differs from
// klu_solve only in the order of the sums.
#include <lcprelax/sparse/detail/reach_work.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <vector>

namespace lcprelax::sparse {

class HypersparseColumnSolver {
 public:
  /// Reserves storage for the factors of klu's last factorization (no other work: call it
  /// where allocation is allowed, e.g. right after the factorization).
  void reserve(const KluLu& klu);
  /// Extracts klu's factors (O(nnz(L + U + F)) work; allocates only beyond the reserved
  /// storage). False when klu is not factorized.
  bool build(const KluLu& klu);
  bool built() const { return built_; }
  /// Forget the factors (built() becomes false; storage kept).
  void invalidate() { built_ = false; }

  /// x = A⁻¹b for b given by its nonzeros (b_index[k], b_value[k], k < nb; repeated
  /// indices add up). Writes the positions of x that the reach contains (in no particular
  /// order) and their values. The work arrays are sized by build(); x_index and x_value
  /// allocate only below capacity n.
  void solve(int nb, const int* b_index, const double* b_value, std::vector<int>& x_index,
             std::vector<double>& x_value);

  /// x = A⁻¹b, x dense of size n, for b given by its nonzeros as in solve(); the columns
  /// of the factors whose solution entry is zero are skipped (see the header comment).
  /// Returns the number of nonzero entries of x. Allocates nothing.
  Index solve_dense(int nb, const int* b_index, const double* b_value, Eigen::Ref<Vector> x);

  /// Nodes visited by the last solve() (v and u nodes: at most 2n; instrumentation).
  int last_reach() const { return last_reach_; }

 private:
  int next_child(int j, int& e) const;

  int n_ = 0;
  bool built_ = false;
  KluLu::Factors f_;  // column-wise, as extracted
  std::vector<double> udiag_;
  std::vector<int> pinv_;  // position k of row i: P[k] = i
  std::vector<double> dense_;  // solve_dense's work vector, by position (zero between solves)
  detail::ReachWork work_;  // size 2n
  int last_reach_ = 0;
};

}  // namespace lcprelax::sparse
