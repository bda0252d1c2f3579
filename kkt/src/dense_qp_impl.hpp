#pragma once
// DenseQpSolver's private state, shared by dense_qp_solver.cpp (forward) and
// dense_qp_backward.cpp (adjoint). Internal.
#include <lcprelax/kkt/dense_qp_solver.hpp>
#include <lcprelax/kkt/qp_solver.hpp>

#include "qp_solver_impl.hpp"

#include "small_cholesky.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <vector>

namespace lcprelax {

struct DenseQpSolver::Impl {
  // Where an internal equality row comes from, and where a one-sided constraint does.
  enum class EqSource { a_row, g_row, fixed_variable };
  struct EqRow {
    EqSource source;
    Index index;  // row of A or G, or variable
  };
  struct Side {
    bool on_g_row;  // else a variable bound
    Index index;    // row of G (into G) or variable
    Index gi_row;   // row of Gi (inequality rows of G), when on_g_row
    double sign;    // +1 lower side (c = g, d = l), −1 upper side (c = −g, d = −u)
  };

  QpSettings settings;
  QpProblem problem;  // the user's data (residuals, gradients' patterns, fallback)
  Index n = 0, me = 0, mc = 0;
  DenseMatrix P, A, G;    // dense copies (P full symmetric)
  DenseMatrix Ae;         // me×n internal equality rows
  DenseMatrix Gi;         // inequality rows of G (those with a constraint side)
  std::vector<Index> gi_source;  // G row of each Gi row
  std::vector<EqRow> eq_rows;
  std::vector<Side> sides;
  std::vector<char> row_class, var_class;  // side classes of G's rows and of the bounds
  Vector be, d;           // me, mc
  double reg_base = 0.0;  // ρ and δ start here

  // Iterate and work arrays (sized by size_work()).
  Vector x, y, s, lam;
  Vector rd, re, rp, rc, dx, dy, ds, dlam, f, Gx, w, Drow, tmp_n, tmp_me, cx;
  DenseMatrix K, W, S;
  detail::SmallCholesky llt_K, llt_S;
  bool factorized_at_final = false;
  // The adjoint's factorization at the solution (dense_qp_backward.cpp): constraints with
  // W = s/λ < 1 stay as rows of E = [Ae; C_active] with −W on the diagonal, the others are
  // eliminated into K_adj = P + C_inactiveᵀ W⁻¹ C_inactive (+ρI).
  std::vector<Index> active, weak;
  DenseMatrix E, K_adj, WE, S_adj;  // E, WE, S_adj at full size; the first ne_adj rows/cols used
  Index ne_adj = 0;
  detail::SmallCholesky llt_Kadj, llt_Sadj;
  Vector W_sides;
  struct AdjointWork {  // backward()'s vectors, kept between calls (no allocation once sized)
    Vector g_y, g_l, fy, fl, a, b, ct, r1, r2, r3, da, db, dct, Ctv, Cv, alpha_a, beta_a, alpha_g, beta_g;
    Vector wl, f, ka, u, rhs, Ca, dk;
  } aw;

  // Goldfarb–Idnani active-set method (dense_qp_active_set.cpp).
  bool use_active_set = true;
  bool exact_active_set = false;   // the last solution came from it
  detail::SmallCholesky llt_P;     // P = LLᵀ, kept while P's values repeat (p_factor_ready)
  DenseMatrix J0, J, R;            // J0 = L⁻ᵀ
  Vector p_values;                 // P's stored values of the last fill
  bool p_factor_ready = false;
  std::vector<Index> as_index;     // active constraints: side k ≥ 0, equality row r as −1 − r
  std::vector<char> as_active;     // per side
  Vector as_u, as_d, as_z, as_r, as_normal, side_norm1;

  struct ResidualProducts {  // P x, A x, G x, Aᵀy, Gᵀz of the termination test
    Vector Px, Ax, Gx, Aty, Gtz;
  } rv;

  QpResult result;
  bool used_fallback = false;
  std::unique_ptr<QpSolver> fallback;
  bool fallback_ready = false;
  bool has_setup = false;

  void load(const QpProblem& p);   // classification, work arrays, then fill_values()
  void fill_values();              // dense copies of `problem`'s values (same classes)
  bool same_classes(const QpProblem& p) const;
  void size_work();
  // C·v (uses Gx as scratch) and Cᵀ·v accumulated into out (out = Cᵀv).
  void apply_C(const Vector& v, Vector& out);
  void apply_Ct(const Vector& v, Vector& out);
  // K = P + Cᵀ diag(dk) C + ρI factorized (raising ρ up to 8 times); the Schur
  // complement of the equality rows too. False when the factorization fails.
  bool factorize(const Vector& dk);
  // Solves K dx − Aeᵀ dy = rhs_x, Ae dx = rhs_e with the factorizations (f is clobbered).
  void solve_reduced(const Vector& rhs_x, const Vector& rhs_e, Vector& out_x, Vector& out_y);
  // The iterate in the user's conventions (result.x, y, z, z_bounds) and its residuals;
  // returns whether they are within eps.
  bool fill_result_and_check();
  bool factorize_adjoint();
  bool factor_adjoint_split();  // the split and factors for the current W_sides
  bool factor_exact_active_set();  // the same at an exact active set with weak sides, one pass
  // Solves [P Aeᵀ Cᵀ; Ae 0 0; C 0 −W] (a, b, c̃) = (fx, fy, fl) with factorize_adjoint()'s factors.
  void adjoint_solve(const Vector& fx, const Vector& fy, const Vector& fl, Vector& a, Vector& b, Vector& ct);
  bool run_dense();                            // the interior point (dense_qp_interior_point.cpp)
  int max_interior_point_iterations() const;  // min(60, settings.max_iter), then QpSolver
  bool run_active_set();
  void run_fallback(const char* why);
};

}  // namespace lcprelax
