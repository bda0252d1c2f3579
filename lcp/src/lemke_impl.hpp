#pragma once
// Internal: the state of LemkeSolver and the steps of a solve, split by file:
// - lemke.cpp: setup, the retries of solve(), the factorization of the current basis;
// - lemke_pivot.cpp: the cold start, Lemke's pivots and the lexicographic ratio test;
// - lemke_crash.cpp: the warm and crash starts and the repair of a singular warm basis;
// - lemke_purify.cpp: the vertex basis of an approximate solution (warm_start_point);
// - lemke_solution.cpp: the solution from the final basis, and backward().
// Conventions (variable numbering, tableau) in lemke_basis.hpp; the method in lemke.hpp.
#include <lcprelax/lcp/lemke.hpp>

#include "lemke_basis.hpp"
#include "lemke_lexicographic.hpp"

#include <limits>
#include <memory>
#include <vector>

namespace lcprelax {

struct LemkeSolver::Impl {
  LemkeSettings settings;
  Index n = 0;
  // M as given to setup(M, q, ...), or formed from the lifted form on first need
  // (setup(lifted, q): ensure_matrix(); until then matrix_formed is false and M empty).
  mutable SparseMatrix M;
  mutable bool matrix_formed = true;
  Vector q_user;     // q as given
  Vector q, d;       // q = q_user / q_norm: the pivoting runs on ‖q‖∞ = 1 (z scales with q)
  double q_norm = 1.0;
  double tol = 0, res_tol = 0;
  double mnorm = 0;  // ‖M‖∞
  long max_pivots = 0;
  bool is_setup = false;
  LemkeMethod method = LemkeMethod::dense;  // the basis in use (settled at setup)
  std::vector<bool> warm;
  Vector warm_point;  // warm_start_point (user units); empty when none
  std::vector<bool> warm_fallback;  // its fallback basis; empty: the one the point suggests
  LcpResult result;
  std::vector<Index> basic;  // variable per row: [0,n) w, [n,2n) z, 2n z0
  std::unique_ptr<detail::LemkeBasis> basis;
  // Lifted form of M (setup's LcpLiftedForm): J, Jᵀ, H, d; lifted_shift is the εI of a
  // regularization retry (the basis adds it to H's diagonal).
  bool has_lifted = false;
  SparseMatrix lifted_J, lifted_JT, lifted_H;
  Vector lifted_d;
  double lifted_shift = 0.0;
  std::shared_ptr<LemkeSharedFactorization> shared_lu;  // share_factorization(); nullptr: none
  void (*refactor_hook)(bool) = nullptr;
  std::vector<Index>* pivot_trace = nullptr;  // set_pivot_trace
  long pivot_trace_limit = -1;                // its pivots recorded at most (< 0: all)
  void trace_pivot(Index entering, Index leaving) {
    if (!pivot_trace) return;
    if (pivot_trace_limit >= 0 && static_cast<long>(pivot_trace->size()) >= 2 * pivot_trace_limit) return;
    pivot_trace->push_back(entering);
    pivot_trace->push_back(leaving);
  }

  // Which basis the factorization holds: factored_basic, valid while factor_current
  // (cleared by a column replacement and by any change of M or d).
  std::vector<Index> factored_basic;
  bool factor_current = false;

  // Work arrays, sized at setup (the pivot loop allocates nothing).
  Vector xB, a, ratio_col, refine;  // x_B; B⁻¹(entering column); ratio denominators; residual
  Vector refine_z, refine_dof;       // residual_of_basic's z_B (n) and J's dofs (lifted basis)
  Vector z_spare, w_spare;           // storage of result.z / result.w between solves
  Vector z_clip, w_clip;             // z clipped at 0 and its w (extract_solution)
  Vector d_cover;                    // the settings' covering vector during a crash start
  std::vector<Index> rows, keep;     // candidate rows of the ratio test
  detail::LexicographicTie ties;     // the tie-break on rows of B⁻¹ (lemke_lexicographic.hpp)

  Index z0() const { return 2 * n; }
  static Index complement(Index var, Index n) { return var < n ? var + n : var - n; }

  // lemke.cpp
  void setup(const SparseMatrix& M, const Vector& q);
  void setup_sizes(const Vector& q, double m_norm);
  void set_lifted(const LcpLiftedForm& lifted, Index n_of_m);
  void ensure_matrix() const;
  void apply_matrix(const Vector& z, Vector& out);  // out = M z (lifted products while M is unformed)
  void set_q(const Vector& q_in);
  void allocate();
  void new_basis();
  void reset_result();
  void discard_solution();
  void take(Vector& v, Vector& spare) const;
  bool refactor(Vector& x);
  void residual_of_basic(const Vector& x, Vector& r);  // r = q − B x (lemke.cpp)
  bool factorize_basic();
  void finish(LcpStatus status, const char* message) {
    result.info.status = status;
    result.info.message = message;
  }

  // lemke_pivot.cpp
  void run();
  /// covered_rows_only: z₀ enters only at rows where B⁻¹d > 0 (a crash path with the
  /// settings' d, not B·1); a negative basic value elsewhere ends it with numerical_error.
  void pivot_from_current_basis(bool covered_rows_only = false);
  bool entering_candidates(Index entering);
  bool drop_vanished_z0(Index entering);
  // |z₀|·‖d‖∞ (normalized units, ‖q‖∞ = 1) below which a ray tries drop_vanished_z0.
  static constexpr double kVanishedZ0 = 1e-6;
  // Residual bound of x_B after an ill-conditioned basis update (LcpInfo::update_checks),
  // relative to max(1, ‖M‖∞)·max(1, ‖x_B‖∞), normalized units: 10× below the final
  // solution's default residual tolerance (1e-9·‖q‖∞).
  static constexpr double kUpdateResidual = 1e-10;
  Index lexicographic_row(const Vector& den, const Vector& x, bool prefer_z0);

  // lemke_crash.cpp
  bool warm_basis_is_factored() const;
  bool load_warm_basis();
  bool try_warm_start(bool factorized);
  bool repair_warm_basis();
  bool try_crash_start();
  bool flip_infeasible(bool factorized);

  // lemke_purify.cpp
  bool purify_warm_point();
  bool purify_into_warm();
  Index purify_ratio_row(double limit, Index prefer) const;
  bool purify_exchange(Index r, Index entering, double value);
  bool purify_pair_swap(Index ws, Index j);
  int purify_degenerate_exchange(Index p, Index var);
  bool purify_path(Index s, Index leaving, Vector& z_super, std::vector<Index>& position, long& budget);
  bool purify_match_pairs(std::vector<Index>& position);

  // lemke_solution.cpp
  /// xb_is_current: x_B was just computed by refactor(xB) for the current basis (a warm
  /// start), so the fresh factorization and solve that would recompute it are skipped
  /// (they would give the same numbers).
  void extract_solution(bool xb_is_current = false);
};

}  // namespace lcprelax
