#pragma once
// Rows shared by every QP posed on an island's ContactSystem in the lifted form or with
// Coulomb's friction cone (the convex contact model, models/contact_step.hpp, and the
// convex learning loss, learn/step_loss_convex.hpp).
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/models/contact_system.hpp>

#include <vector>

namespace lcprelax {

/// The lifted momentum equality M w − Jnᵀλn (− Jtᵀλt when `friction`) = 0 as p.A, p.b, with
/// w (3 per body) first in x, λn from column nv, λt from nv + nc (M = diag(1/minv)).
void lifted_momentum_equality(const ContactSystem& s, bool friction, QpProblem& p);

/// Appends the phase-2 rows after the nc contact rows: eᵀλn ≤ κ (row nc), then
/// λt − μλn ≤ 0 and λt + μλn ≥ 0 per friction row (rows nc + 1 + 2f, nc + 2 + 2f);
/// λn starts at column `ln`, λt at `lt`.
void append_friction_cone_rows(const ContactSystem& s, Index ln, Index lt, std::vector<Triplet>& t);

}  // namespace lcprelax
