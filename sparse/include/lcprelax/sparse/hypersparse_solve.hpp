#pragma once
// Hypersparse transposed solves with a KLU factorization: y = A⁻ᵀb for a sparse b, with
// work proportional to the nonzeros of the factors that the solution touches, not to n or
// nnz(L + U). Used for rows of a basis inverse (eᵢᵀB⁻¹ = (B⁻ᵀeᵢ)ᵀ) in Lemke's
// lexicographic ratio test, where a dense transposed solve per row dominated the solve.
//
// Method. KLU factorizes N = L·U + F with N_kl = A(P[k], Q[l]) / Rs[k] (KluLu::Factors:
// BTF blocks, L unit lower and U upper within the diagonal blocks, F the entries above
// them). Aᵀy = b is Nᵀu = b̃ with b̃_l = b_{Q[l]}, y_{P[k]} = u_k / Rs[k]. As N is block upper triangular,
// Nᵀu = b̃ reads, with v = Lᵀu (block by block),
//     Uᵀv = b̃ − Fᵀu,    Lᵀu = v.
// Both unknowns are nodes of one graph, v_k and u_k per position k, with an edge from x to
// y when y's equation uses x:
//     v_p → v_q  (U_pq ≠ 0, p < q),   v_p → u_p,   u_p → u_q  (L_pq ≠ 0, p > q),
//     u_p → v_q  (F_pq ≠ 0, q in a later block).
// The graph is acyclic (inside a block v runs forward, u backward and v → u only; F leads to
// later blocks), so a depth-first search from the nonzeros of b̃ yields every node that can
// be nonzero, in reverse topological order, and the numeric solve visits only those nodes
// and their edges: Gilbert & Peierls' reach (J. R. Gilbert, T. Peierls, "Sparse partial
// pivoting in time proportional to arithmetic operations", SIAM J. Sci. Stat. Comput. 9,
// 1988; T. A. Davis, "Direct Methods for Sparse Linear Systems", SIAM 2006, §3.2), here on
// the two triangular factors and the BTF off-diagonal block at once. The factors are
// kept row-wise (the transposed solves scatter along rows of U, L and F).
//
// Conventions: no tolerance (exact zeros of the factors are skipped at build; the result
// may hold numerically zero entries, all reached positions are reported). Rounding differs
// from klu_tsolve only in the order of the sums.
#include <lcprelax/sparse/detail/reach_work.hpp>
#include <lcprelax/sparse/klu_lu.hpp>

#include <vector>

namespace lcprelax::sparse {

class HypersparseTransposedSolver {
 public:
  /// Reserves storage for the factors of klu's last factorization (no other work: call it
  /// where allocation is allowed, e.g. right after the factorization).
  void reserve(const KluLu& klu);
  /// Extracts klu's factors and makes their row-wise copies (O(nnz(L + U + F)) work;
  /// allocates only beyond the reserved storage). False when klu is not factorized.
  bool build(const KluLu& klu);
  bool built() const { return built_; }
  /// Forget the factors (built() becomes false; storage kept).
  void invalidate() { built_ = false; }

  /// y = A⁻ᵀb for b given by its nonzeros (b_index[k], b_value[k], k < nb; repeated indices
  /// add up). Writes the positions of y that the reach contains (in no particular order)
  /// and their values. The work arrays are sized by build(); y_index and y_value allocate
  /// only below capacity n.
  void solve(int nb, const int* b_index, const double* b_value, std::vector<int>& y_index,
             std::vector<double>& y_value);

  /// Nodes visited by the last solve() (v and u nodes: at most 2n; instrumentation).
  int last_reach() const { return last_reach_; }

 private:
  struct RowWise {  // CSR of a factor without its diagonal
    std::vector<int> start, col;
    std::vector<double> val;
  };
  void transpose_strict(const std::vector<int>& p, const std::vector<int>& i, const std::vector<double>& x,
                        RowWise& out, std::vector<double>* diag);
  int next_child(int j, int& e) const;

  int n_ = 0;
  bool built_ = false;
  KluLu::Factors factors_;  // as extracted (column-wise)
  std::vector<int> next_;   // transposition cursor
  RowWise U_, L_, F_;
  std::vector<double> udiag_, rs_;
  std::vector<int> p_, qinv_;
  detail::ReachWork work_;  // size 2n
  int last_reach_ = 0;
};

}  // namespace lcprelax::sparse
