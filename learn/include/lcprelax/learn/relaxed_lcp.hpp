#pragma once
// The relaxed (soft-LCP) loss of one sample and its gradient by the envelope theorem.
//
// Parmar, Halm & Posa, "Fundamental Challenges in Deep Learning for Stiff Contact
// Dynamics", IROS 2021: instead of solving the LCP 0 ≤ λ ⊥ Mλ + q ≥ 0 and then measuring
// the prediction error (the "hard" loss, whose gradient vanishes where a bad prior makes
// contacts stick), the prediction error is moved INTO the contact subproblem, which is
// softened into a convex QP; the loss is the subproblem's optimal value. The formulation
// (weights, settings, the 1e-3·I regularization) follows the seeds' reference code.
//
// Data of one sample: an LCP (sparse M n×n, q n) whose solution λ predicts the next state
// linearly, x̂(λ) = Pλ + p (sparse P k×n, p k), and the observed next state x̄ (k).
// Optional "maximum dissipation" term a5‖Eλ − e‖² (sparse E r×n, e r): for the 1-D block
// E = [1 1 0], e = μmg pushes |λ| towards the friction bound (the seeds' max-dissipation).
//
// QP variables x = [λ (n); s (n, only with soft_nonnegativity); t (n, only with
// soft_lambdas)], and
//     c = min  a1‖Pλ + p − x̄‖² + a2 λᵀ(Mλ + q) + S(s) + T(t) + [a5‖Eλ − e‖²  if qp]
//              + (ε/2)‖x‖²
//     s.t.  Mλ + q (+ s) ≥ 0,   λ ≥ 0  (or λ + t ≥ 0 with soft_lambdas),  s, t ≥ 0,
// where S(s) = (a3/2)‖s‖² (or a3·Σs with l1_softness), T(t) = (a4/2)‖t‖² (or a4·Σt), and
// ε = regularization (default 1e-3, as the seeds' "Q + 0.001·I"). NOTE the factor ½ on the
// slack penalties: the seeds put a3, a4 on the diagonal of the QP matrix Q of ½xᵀQx, and
// this file follows them (defaults a1 = a2 = 1, a3 = a4 = 20, a5 = 0.1).
// With max_dissipation = ext the term a5‖Eλ* − e‖² is added AFTER the QP, at its solution
// λ*, and is not part of the subproblem (the seeds' "force_max_dissipation_ext").
// The QP's Hessian of ½xᵀHx is H_λλ = 2a1 PᵀP + a2(M + Mᵀ) [+ 2a5 EᵀE] + εI,
// H_ss = a3 I + εI (ε I with l1), H_tt likewise; the constant a1‖p − x̄‖² [+ a5‖e‖²] is
// part of c.
//
// Convexity: c is a convex QP iff H is PSD; H ⪰ εI > 0 holds whenever sym(a2·M) +
// a1·PᵀP ⪰ 0, e.g. for the 1-D block (sym(M) = [[1,−1,0],[−1,1,0],[0,0,0]]/m ⪰ 0) and for
// any LCP whose M has a PSD symmetric part. Stewart–Trinkle LCPs with a normal phase are
// NOT of this kind in general (λᵀMλ contains μγλn, indefinite), so solve() checks H with
// a sparse LLᵀ (Eigen's simplicial, which fails on a pivot ≤ 0) before the interior point:
//   - NonconvexPolicy::report (default): status nonconvex, no QP solve, c = NaN;
//   - NonconvexPolicy::shift: H_λλ += δI with the smallest δ = 10ᵏ·max(ε, 1e-8)
//     (k = 0, 1, …, 12) for which LLᵀ succeeds; δ is reported in Result::shift and the
//     shifted problem is the one solved and differentiated (c includes (δ/2)‖λ‖²). δ does
//     not depend on the data (no ‖H‖ factor), so the envelope gradient, which holds δ
//     fixed, is exact except where a change of θ changes k (a kink of c). Scale the
//     unknowns so that ε is meaningful.
//
// Gradient (envelope theorem; Milgrom & Segal 2002). At the optimum with the QpSolver's
// multipliers (qp_problem.hpp: Hx + h + Gᵀz + z_bounds = 0, z < 0 on an active lower side), the
// Lagrangian is L = f(x; data) + Σᵢ zᵢ (Gᵢx − lᵢ) with rows Gx = Mλ (+ s), lower bound
// l = −q; hence, with ρ = Pλ + p − x̄, σ = Eλ − e:
//     ∂c/∂M_ij = a2 λi λj + zi λj,   ∂c/∂q = a2 λ + z,
//     ∂c/∂P = 2a1 ρ λᵀ,  ∂c/∂p = 2a1 ρ,  ∂c/∂x̄ = −2a1 ρ,
//     ∂c/∂E = 2a5 σ λᵀ,  ∂c/∂e = −2a5 σ       (qp mode),
// matrices on their input sparsity patterns. No extra linear solve is needed. In ext mode
// the extra term depends on λ*(data), so its part is added by one QpSolver::backward()
// (adjoint, reusing the final factorization). relaxed_lcp_gradient_adjoint() computes the
// whole gradient by the adjoint alone (backward with ∂c/∂x, chained through the assembly
// of H, h, G, l), as the check of the envelope formulas (tests/learn_relaxed_lcp_test).
// Where the QP's solution is degenerate (weakly active constraints) the two agree only up
// to the interior point's tolerance (see qp_solver.hpp).
#include <lcprelax/kkt/qp_result.hpp>
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/sparse/types.hpp>

#include <memory>
#include <string>

namespace lcprelax::learn {

enum class MaxDissipation { none, qp, ext };
const char* to_string(MaxDissipation m);
/// "none", "qp" or "ext"; throws InputError otherwise.
MaxDissipation parse_max_dissipation(const std::string& s);

enum class NonconvexPolicy { report, shift };

struct RelaxedLcpSettings {
  double a1 = 1.0;    ///< weight of the prediction error ‖Pλ + p − x̄‖²
  double a2 = 1.0;    ///< weight of the complementarity term λᵀ(Mλ + q)
  double a3 = 20.0;   ///< weight of the nonnegativity slacks s (soft_nonnegativity)
  double a4 = 20.0;   ///< weight of the λ slacks t (soft_lambdas)
  double a5 = 0.1;    ///< weight of the maximum-dissipation term
  bool soft_nonnegativity = false;  ///< Mλ + q + s ≥ 0 instead of Mλ + q ≥ 0
  bool soft_lambdas = false;        ///< λ + t ≥ 0 instead of λ ≥ 0
  bool l1_softness = false;         ///< linear slack penalties a3·Σs, a4·Σt
  MaxDissipation max_dissipation = MaxDissipation::none;
  double regularization = 1e-3;     ///< ε of (ε/2)‖x‖² (the seeds' 1e-3·I), ≥ 0
  NonconvexPolicy nonconvex = NonconvexPolicy::report;
  /// Empty if valid (weights finite and ≥ 0, a1 > 0), else a message naming the first bad field.
  std::string validation_error() const;
};

/// One sample's data. E, e are used only with max_dissipation qp or ext (may be empty).
struct RelaxedLcpData {
  SparseMatrix M;   ///< n×n
  Vector q;         ///< n
  SparseMatrix P;   ///< k×n
  Vector p;         ///< k
  Vector target;    ///< x̄, k
  SparseMatrix E;   ///< r×n
  Vector e;         ///< r
  /// Checks the data against `settings` (E and e only with max dissipation qp or ext):
  /// throws InputError naming the first inconsistent or non-finite field.
  void validate(const RelaxedLcpSettings& settings) const;
};

enum class RelaxedLcpStatus { solved, nonconvex, qp_failed };
const char* to_string(RelaxedLcpStatus s);

struct RelaxedLcpGradient {
  SparseMatrix dM;   ///< ∂c/∂M on M's pattern
  Vector dq;
  SparseMatrix dP;   ///< ∂c/∂P on P's pattern
  Vector dp;
  Vector dtarget;    ///< ∂c/∂x̄
  SparseMatrix dE;   ///< on E's pattern (zero matrix without max dissipation)
  Vector de;
};

struct RelaxedLcpResult {
  RelaxedLcpStatus status = RelaxedLcpStatus::qp_failed;
  std::string message;       ///< why, when not solved
  double cost = 0.0;         ///< c (plus the ext term in ext mode); NaN unless solved
  Vector lambda;             ///< λ (n)
  Vector slack;              ///< s (n; zeros without soft_nonnegativity)
  Vector lambda_slack;       ///< t (n; zeros without soft_lambdas)
  Vector multipliers;        ///< z of the rows Mλ (+s) ≥ −q (≤ 0), n
  double shift = 0.0;        ///< δ added to H_λλ (NonconvexPolicy::shift), else 0
  QpStatus qp_status = QpStatus::unsolved;
  int iterations = 0;
  RelaxedLcpGradient gradient;  ///< filled when solved and gradients were requested
  Vector qp_x, qp_z, qp_z_bounds;  ///< the raw QP solution (for warm_start())
  double assembly_seconds = 0.0, solve_seconds = 0.0, gradient_seconds = 0.0;
};

/// A reusable workspace: keeps the relaxed QP, the QpSolver (symbolic analysis done once
/// per sparsity pattern, numeric refactorization on new values) and the convexity check's
/// factor. While the sparsity patterns of M, P, E repeat, the new values are written into
/// the QP's existing matrices in place and QpSolver::update() reuses the analysis; on
/// another pattern the QP is built from triplets and analysed again. Both paths give the
/// same result bit for bit. Not thread-safe: one per thread. Samples with different
/// patterns may share a workspace.
class RelaxedLcpSolver {
 public:
  /// Throws InputError when settings.validation_error() or qp_settings is not valid.
  explicit RelaxedLcpSolver(RelaxedLcpSettings settings = {}, QpSettings qp_settings = {});
  ~RelaxedLcpSolver();
  RelaxedLcpSolver(RelaxedLcpSolver&&) noexcept;
  RelaxedLcpSolver& operator=(RelaxedLcpSolver&&) noexcept;

  const RelaxedLcpSettings& settings() const;
  /// Solves the relaxed QP for `data` (validated; throws InputError on bad data), and,
  /// when `gradient` is true, fills Result::gradient by the envelope theorem (+ one
  /// adjoint solve in ext mode). The reference stays valid until the next call.
  const RelaxedLcpResult& solve(const RelaxedLcpData& data, bool gradient = true);
  /// The same gradient of the last solve() computed by the QP adjoint alone (the check).
  /// Requires the last solve() to have status solved (else std::logic_error).
  RelaxedLcpGradient gradient_adjoint();
  /// Warm start the next solve() from a previous result of the same sample (same sizes).
  void warm_start(const RelaxedLcpResult& previous);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One-shot convenience: a fresh workspace, solve with gradient.
RelaxedLcpResult relaxed_lcp(const RelaxedLcpData& data, const RelaxedLcpSettings& settings = {},
                             const QpSettings& qp_settings = {});

}  // namespace lcprelax::learn
