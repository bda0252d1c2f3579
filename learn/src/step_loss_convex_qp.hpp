#pragma once
// The two phase QPs of the convex step loss (the simulator's, models/convex_phase_qp.hpp,
// with the loss's terms) in the dual or the lifted formulation, and the pullback of their QpGradient to the island data (step_loss_convex.hpp states the model,
// the formulations and the chain rule). Internal to lcprelax_learn.
#include <lcprelax/kkt/qp_gradient.hpp>
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/convex_phase_qp.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/models/normal_softening.hpp>

namespace lcprelax::learn::detail {

/// What both phases need of one island: the simulator's phase data (models/convex_phase_qp.hpp)
/// and the loss's linear terms.
struct ConvexLossData {
  ConvexLossData(const ContactSystem& system, const Vector& target, double dt, double w, bool lifted);
  ConvexLossData(const ConvexLossData&) = delete;
  ConvexLossData& operator=(const ConvexLossData&) = delete;
  const ContactSystem& s;
  double dt, w;
  bool lifted;
  Index nc, nf, nv;
  Vector gap;   ///< max(φ, 0)/Δt per contact (m/s)
  Vector c;     ///< (1 + w)v* − w v̄: the linear terms are J c (+ gap in phase 1)
  Vector qn1;   ///< phase 1's λn term Jn c + gap
  Vector qn2;   ///< phase 2's λn term Jn c
  Vector qt2;   ///< phase 2's λt term Jt c
  lcprelax::detail::ConvexModelData model;  ///< bn = Jn v* + gap, diag(Wnn), W (dual)
  const Vector& bn;        ///< model.bn
  const Vector& w_nn;      ///< model.w_nn: diag(Jn D Jnᵀ)
  const SparseMatrix& W;   ///< model.W: J D Jᵀ (dual only)
  SparseMatrix J;          ///< [Jn; Jt] (dual only)
};

/// A phase QP; x(lambda_offset + i) is λn_i (i < nc) or λt_(i − nc).
struct ConvexLossQp {
  QpProblem problem;
  Index lambda_offset = 0;
  NormalSofteningTerms softening;  ///< the normal softening's terms (phase 1 uses v_ref only)
};

/// Phase 1 with regularization r, the deviation's curvature (1 + w) and, for w > 0, the
/// non-penetration rows; its λn term is lowered by the softening's v_ref too.
ConvexLossQp convex_loss_phase1(const ConvexLossData& d, double r, const NormalSofteningTerms& softening);
/// Phase 2 with u(nc) = +∞ (the caller sets the κ bound), softened by `softening`
/// (models/normal_softening.hpp: ½ Σ g_i Wnn_i λn_i² − λnᵀ v_ref).
ConvexLossQp convex_loss_phase2(const ConvexLossData& d, const NormalSofteningTerms& softening);

/// Cotangents of the intermediate quantities, accumulated over both phases, then pulled
/// back to the island data by finish().
struct ConvexLossPullback {
  explicit ConvexLossPullback(const ConvexLossData& d);
  /// Adds phase `phase` (1 or 2)'s QP gradient; returns ∂ℓ/∂u(nc) for phase 2 (else 0).
  double add_phase(int phase, const ConvexLossQp& qp, const QpGradient& g, double rho);
  /// Adds ∂ℓ/∂J_ij = a_i b_j on J's pattern (rows: contacts, then friction rows).
  void add_outer(const Vector& a, const Vector& b);
  /// Writes the total into `out` (whose fields already hold explicit terms, added to).
  void finish(ContactSystemCotangent& out);

  const ConvexLossData& d;
  SparseMatrix Jn_bar, Jt_bar;  ///< on Jn's and Jt's patterns
  SparseMatrix W_bar;           ///< dual: on W's pattern (not symmetric)
  Vector bn_bar, gap_bar, c_bar, w_nn_bar, phi_bar, mu_bar, minv_bar;
  Vector compliance_bar, erp_bar;  ///< a pair's normal softness (normal_softening.hpp add_pair_softness)
  Vector vn_bar;  ///< of vn = Jn v* in the softening's target velocity

 private:
  void add_J(Index row, Index col, double v);
};

/// A's pattern with zero values.
SparseMatrix zero_like(const SparseMatrix& A);

}  // namespace lcprelax::learn::detail
