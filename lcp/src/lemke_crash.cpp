// Warm and crash starts of Lemke's method (lemke.hpp): the warm basis as given, its repair
// when singular, and Lemke's pivots from it when it factorizes but is infeasible.
#include "lemke_impl.hpp"

#include <lcprelax/sparse/klu_lu.hpp>

#include <vector>

namespace lcprelax {

// Whether the factorization holds the basis `warm` (in its own column order).
bool LemkeSolver::Impl::warm_basis_is_factored() const {
  if (!factor_current) return false;
  for (Index k = 0; k < n; ++k) {
    const Index v = factored_basic[k];
    if (v >= 2 * n || (v >= n) != static_cast<bool>(warm[v < n ? v : v - n])) return false;
  }
  return true;
}

// Sets the basis to `warm`; true when it factorizes (x_B = B⁻¹q then holds its values).
bool LemkeSolver::Impl::load_warm_basis() {
  if (warm_basis_is_factored()) basic = factored_basic;
  else
    for (Index i = 0; i < n; ++i) basic[i] = warm[i] ? n + i : i;
  return refactor(xB);
}

// factorized: load_warm_basis() (directly or as flip_infeasible's last step) has just set
// x_B from a factorization of the current basis, so extract_solution need not recompute it.
bool LemkeSolver::Impl::try_warm_start(bool factorized) {
  if (!factorized || xB.minCoeff() < -tol) return false;
  extract_solution(/*xb_is_current=*/true);
  result.info.warm_started = has_solution(result.info.status);
  return result.info.warm_started;
}

// Basis repair of a singular crash basis (as simplex codes repair a singular crash basis
// by exchanging dependent columns for slacks, e.g. Bixby, "Implementing the simplex method:
// the initial basis", ORSA J. Comput. 4, 1992): the z columns that a KLU factorization of
// B = [e_i (w_i basic) | −M_:j (z_j basic)] leaves with a zero pivot (relative 1e-10)
// become their complements w_j, for at most kRepairRounds factorizations. A granular
// pile's approximate solution loads more contacts than the bodies have degrees of
// freedom, and the basis it suggests is singular. Allocates (a crash start only).
namespace {
constexpr int kRepairRounds = 8;
}  // namespace

bool LemkeSolver::Impl::repair_warm_basis() {
  for (int round = 0; round < kRepairRounds; ++round) {
    std::vector<Triplet> t;
    t.reserve(static_cast<std::size_t>(M.nonZeros() + n));
    for (Index j = 0; j < n; ++j) {
      if (!warm[static_cast<std::size_t>(j)]) {
        t.emplace_back(j, j, 1.0);
        continue;
      }
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) t.emplace_back(it.row(), j, -it.value());
    }
    SparseMatrix B(n, n);
    B.setFromTriplets(t.begin(), t.end());
    B.makeCompressed();
    sparse::KluLu klu;
    if (!klu.analyze(B).ok()) return false;
    const std::vector<Index> dependent = klu.zero_pivot_columns(B, 1e-10);
    if (dependent.empty()) return round > 0;
    bool changed = false;
    for (Index j : dependent)
      if (warm[static_cast<std::size_t>(j)]) {
        warm[static_cast<std::size_t>(j)] = false;
        changed = true;
      }
    if (!changed) return false;
    ++result.info.repair_rounds;
  }
  return false;
}

// Lemke from the factorized warm basis B whose basic solution x_B = B⁻¹q has negative
// entries (a crash start, LemkeSettings::crash_start): with the covering vector d = B·1
// the artificial z₀'s column −d reads −1 in B's coordinates, so z₀ enters at the most
// negative x_B,i exactly as it enters at the most negative q_i from the all-w basis, and
// the pivots that follow are Lemke's method on the principal pivotal transform of the
// LCP with respect to B (Cottle, Pang & Stone 1992, §4.4 and §2.3). A basis close to the
// solution's leaves few negative entries and the path is short. With
// crash_covering_from_basis = false d stays the settings' covering vector: for a basis that
// solves q + δd the path is the homotopy from q + θd (θ ≤ δ) back to q, and z₀ enters
// only where it raises x_B ((B⁻¹d)_i > 0; lemke_pivot.cpp refuses a start it cannot cover).
// d is restored afterwards; true only when the path ends solved.
bool LemkeSolver::Impl::try_crash_start() {
  d_cover = d;
  if (settings.crash_covering_from_basis) {
    d.setZero();
    const detail::LemkeColumns cols{&M, &d, n};
    for (Index k = 0; k < n; ++k) cols.add_to(basic[k], 1.0, d);
  }
  pivot_from_current_basis(!settings.crash_covering_from_basis);
  d = d_cover;
  const bool solved = has_solution(result.info.status);
  result.info.crash_started = true;
  result.info.crash_pivots = result.info.pivots;
  return solved;
}

// Block principal pivoting rounds on the crash basis before Lemke runs from it (Júdice &
// Pires, "A block principal pivoting algorithm for large-scale strictly monotone linear
// complementarity problems", Comput. Oper. Res. 21, 1994; Kostreva 1978): every basic
// variable with x_B,i < −tol is exchanged for its complement, the basis repaired when
// singular and refactorized, for at most LemkeSettings::crash_flip_rounds rounds; the
// basis with the fewest infeasible entries seen is kept (the method cycles on matrices
// that are not P-matrices, hence the cap). Returns whether the kept basis factorizes.
bool LemkeSolver::Impl::flip_infeasible(bool factorized) {
  auto infeasible = [&] {
    Index c = 0;
    for (Index k = 0; k < n; ++k) c += xB(k) < -tol;
    return c;
  };
  if (!factorized) return false;
  std::vector<bool> best = warm;
  Index best_count = infeasible();
  for (int round = 0; round < settings.crash_flip_rounds && best_count > 0; ++round) {
    for (Index k = 0; k < n; ++k)
      if (xB(k) < -tol) {
        const Index v = basic[k], j = v < n ? v : v - n;
        if (v < 2 * n) warm[static_cast<std::size_t>(j)] = v < n;
      }
    bool ok = load_warm_basis();
    if (!ok && repair_warm_basis()) ok = load_warm_basis();
    if (!ok) break;
    const Index count = infeasible();
    if (count >= best_count) break;
    best = warm;
    best_count = count;
  }
  if (best != warm) {
    warm = best;
    return load_warm_basis();
  }
  return true;
}

}  // namespace lcprelax
