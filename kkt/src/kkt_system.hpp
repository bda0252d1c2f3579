#pragma once
// The regularized Newton/KKT system of the interior point (internal).
//
// Unknowns (dx, dy, dζ) for the n variables, me equality rows and mg inequality rows of a
// StandardForm. The unregularized operator is
//     K0 = [P + diag(Db)   Eᵀ   Gᵀ        ]
//          [E              0    0         ]
//          [G              0   −diag(1/Dg)]
// with Db ≥ 0 (bound barrier terms) and Dg > 0 (row barrier terms: Dg = z_u/s_u + z_l/s_l).
// The factorized matrix adds +ρ on the first block, −δ on the equality block and −δ_g on
// the inequality block (δ_g ≤ δ; that block is already negative definite through −1/Dg,
// so δ_g may be 0: qp_ipm_loop.cpp drops it when the refinement stalls). Full form:
// the upper triangle of that quasi-definite matrix, CHOLMOD LDLᵀ. Eliminated form (only
// when me = 0): H = P + Db + ρI + Gᵀ diag(Dg/(1 + δ Dg)) G by CHOLMOD supernodal LLᵀ.
// The data → K index maps are built once, so refilling values is a scatter. CHOLMOD's
// fill-reducing ordering: KktOrdering (AMD, or the fewest predicted flops of AMD, METIS and
// NESDIS for expensive factors); the automatic form compares nnz(L) of the kept orderings.
// Backend dense (tiny problems): the same K (either form) by sparse::DenseLdlt, whose
// pivot signs are checked in both forms (n positive pivots).
// Solves are refined against K0 (iterative refinement; stop when the residual improves
// less than 5× or reaches roundoff).
// Memory: setup() sizes every scratch vector; factorize() (value scatter and numeric
// refactorization) and solve() allocate nothing with the dense backend and CHOLMOD's
// simplicial LDLᵀ (full form); CHOLMOD's supernodal numeric factorization (eliminated form)
// allocates inside CHOLMOD: the permuted transpose of H, its dense update workspace and an
// OpenMP team per parallel region.
#include "standard_form.hpp"

#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/sparse/factorization.hpp>

#include <memory>
#include <vector>

namespace lcprelax::detail {

class KktSystem {
 public:
  /// Chooses the form (automatic: smaller predicted nnz(L)), builds pattern, maps and the
  /// symbolic analysis. Returns false with a message if the analysis fails.
  /// `backend` must be resolved (not automatic: see resolve_backend).
  bool setup(const StandardForm& f, KktForm requested, KktBackend backend, std::string& message,
             KktOrdering ordering = KktOrdering::automatic);
  /// automatic → dense when n + me + mg ≤ dense_max_kkt, else cholmod; others unchanged.
  static KktBackend resolve_backend(KktBackend requested, const StandardForm& f, int dense_max_kkt);
  /// Fills values for (Db, Dg, ρ, δ, δ_g) and factorizes numerically.
  sparse::FactorResult factorize(const StandardForm& f, const Vector& Db, const Vector& Dg, double rho,
                                 double delta, double delta_rows);
  /// Solves K0 (dx, dy, dz) = (rx, ry, rz) with the current factorization and refinement.
  /// Returns the number of refinement steps taken.
  int solve(const StandardForm& f, const Vector& rx, const Vector& ry, const Vector& rz, Vector& dx, Vector& dy,
            Vector& dz, int max_refinement) const;
  /// Refinement target of solve(): K0 (default) or the factorized, regularized matrix (the
  /// proximal iteration's Newton system, whose regularization is part of the step).
  void refine_against_regularized(bool on) { refine_regularized_ = on; }

  KktForm form() const { return form_; }
  KktBackend backend() const { return backend_; }
  /// ‖K0·d − rhs‖∞ / (1 + ‖rhs‖∞) after the last solve's refinement.
  double last_relative_residual() const { return last_relative_residual_; }
  long factor_nnz() const;
  /// Predicted flops of one numeric factorization (0 when the backend does not say).
  double factor_flops() const;
  int numeric_factorizations() const;

 private:
  void build_full_pattern(const StandardForm& f);
  bool build_eliminated_pattern(const StandardForm& f);
  void apply_k0(const StandardForm& f, const Vector& dx, const Vector& dy, const Vector& dz, Vector& ox, Vector& oy,
                Vector& oz) const;
  void approximate_solve(const StandardForm& f, const Vector& rx, const Vector& ry, const Vector& rz, Vector& dx,
                         Vector& dy, Vector& dz) const;

  KktForm form_ = KktForm::full;
  KktBackend backend_ = KktBackend::cholmod;
  SparseMatrix K_;                       // upper triangle of the factorized matrix
  std::unique_ptr<sparse::Factorization> factor_;
  std::vector<Index> p_pos_;             // P entry k (off-diagonal) → K value slot, −1 for diagonal
  std::vector<Index> diag_pos_;          // diagonal slot of every K column
  std::vector<Index> e_pos_;             // Eᵀ entry k (CSC of Et) → K slot (full form)
  std::vector<Index> g_pos_;             // Gᵀ entry k (CSC of Gt) → K slot (full form)
  struct ProductTerm {                   // eliminated form: H[pos] += w_row * Gt[a] * Gt[b]
    Index pos, row, a, b;
  };
  std::vector<ProductTerm> products_;
  Vector Db_, Dg_;                       // values of the last factorization
  double rho_ = 0.0, delta_ = 0.0, delta_rows_ = 0.0;
  bool refine_regularized_ = false;
  mutable double last_relative_residual_ = 0.0;
  mutable Vector work_;                  // scratch for solves
  mutable Vector ox_, oy_, oz_, cx_, cy_, cz_, nx_, ny_, nz_;  // refinement scratch (no allocation per solve)
  mutable Vector wr_, rzw_;              // eliminated form: row weights and weighted rhs
};

}  // namespace lcprelax::detail
