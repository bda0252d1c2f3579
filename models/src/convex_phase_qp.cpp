// The convex model's phase QPs in the dual and the lifted formulation (convex_phase_qp.hpp).
#include <lcprelax/models/convex_phase_qp.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax::detail {
namespace {

// The lifted momentum equality M w − Jnᵀλn (− Jtᵀλt when `friction`) = 0 as p.A, p.b, with
// w (3 per body) first in x, λn from column nv, λt from nv + nc (M = diag(1/minv)).
void lifted_momentum_equality(const ContactSystem& s, bool friction, QpProblem& p) {
  const Index nv = s.num_dofs(), nc = s.num_contacts();
  std::vector<Triplet> t;
  for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, 1.0 / s.minv(i));
  append_triplets(t, s.Jn, 0, nv, -1.0, /*transpose=*/true);
  if (friction) append_triplets(t, s.Jt, 0, nv + nc, -1.0, /*transpose=*/true);
  p.A = from_triplets(nv, p.num_variables(), t);
  p.b = Vector::Zero(nv);
}

// Rows 0..nc, non-penetration: Jn w (lifted) or W's entries in rows < nc and columns < `cols`.
void append_contact_rows(const ConvexModelData& d, Index cols, std::vector<Triplet>& g) {
  const Index nc = d.s.num_contacts();
  if (d.lifted()) {
    append_triplets(g, d.s.Jn, 0, 0, 1.0);
    return;
  }
  for (Index c = 0; c < cols; ++c)
    for (SparseMatrix::InnerIterator it(d.W, c); it; ++it)
      if (it.row() < nc) g.emplace_back(it.row(), c, it.value());
}

// The rows after the nc contact rows: eᵀλn ≤ κ (row nc), then λt − μλn ≤ 0 and
// λt + μλn ≥ 0 per friction row; λn starts at column `ln`, λt at `lt`.
void append_friction_cone_rows(const ContactSystem& s, Index ln, Index lt, std::vector<Triplet>& t) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  for (Index i = 0; i < nc; ++i) t.emplace_back(nc, ln + i, 1.0);
  for (Index f = 0; f < nf; ++f) {
    t.emplace_back(nc + 1 + 2 * f, lt + f, 1.0);
    t.emplace_back(nc + 1 + 2 * f, ln + s.friction_rows[f], -s.mu(f));
    t.emplace_back(nc + 2 + 2 * f, lt + f, 1.0);
    t.emplace_back(nc + 2 + 2 * f, ln + s.friction_rows[f], s.mu(f));
  }
}

}  // namespace

ConvexFormulation resolve_convex_formulation(ConvexFormulation requested, const ContactSystem& s) {
  if (requested != ConvexFormulation::automatic) return requested;
  return s.num_contacts() >= kLiftedMinContacts ? ConvexFormulation::lifted : ConvexFormulation::dual;
}

ConvexModelData::ConvexModelData(const ContactSystem& system, const Vector& bn_in, ConvexFormulation requested)
    : s(system), form(resolve_convex_formulation(requested, system)), bn(bn_in) {
  const Index nc = s.num_contacts();
  w_nn = Vector::Zero(nc);
  for (Index j = 0; j < s.Jn.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) w_nn(it.row()) += it.value() * it.value() * s.minv(j);
  if (form == ConvexFormulation::dual) {
    W = delassus(s);
    W.makeCompressed();
  }
}

ConvexPhaseQp convex_phase1_qp(const ConvexModelData& d, const NormalSofteningTerms& soft,
                               const ConvexPhaseTerms& terms) {
  const ContactSystem& s = d.s;
  const Index nc = s.num_contacts(), nv = s.num_dofs();
  const double scale = terms.hessian_scale, r = terms.regularization;
  ConvexPhaseQp out;
  if (!d.lifted()) {
    out.problem = QpProblem(nc);
    SparseMatrix P = d.W.topLeftCorner(nc, nc);
    if (scale != 1.0) P *= scale;
    if (r > 0.0)
      for (Index i = 0; i < nc; ++i) P.coeffRef(i, i) += r * d.w_nn(i);
    out.problem.P = upper_triangle(P);
  } else {  // x = (w, λn): ½ s wᵀ M w + ½ r Σ Wnn_ii λn_i² + qnᵀ λn, M w = Jnᵀ λn
    out.problem = QpProblem(nv + nc);
    std::vector<Triplet> t;
    for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, scale / s.minv(i));
    if (r > 0.0)
      for (Index i = 0; i < nc; ++i) t.emplace_back(nv + i, nv + i, r * d.w_nn(i));
    out.problem.P = from_triplets(nv + nc, nv + nc, t);
    lifted_momentum_equality(s, /*friction=*/false, out.problem);
    out.lambda_offset = nv;
  }
  QpProblem& p = out.problem;
  if (terms.contact_rows) {
    std::vector<Triplet> g;
    append_contact_rows(d, nc, g);
    p.G = from_triplets(nc, p.num_variables(), g);
    p.l = -d.bn;
    p.u = Vector::Constant(nc, kInf);
  }
  // v_ref = 0 (exp_phi) leaves the linear term bitwise unchanged.
  p.q.tail(nc) = (terms.qn ? *terms.qn : d.bn) - soft.v_ref;
  p.xl.tail(nc).setZero();
  return out;
}

ConvexPhaseQp convex_phase2_qp(const ConvexModelData& d, const NormalSofteningTerms& soft,
                               const ConvexPhaseTerms& terms) {
  const ContactSystem& s = d.s;
  const Index nc = s.num_contacts(), nf = s.num_friction(), nv = s.num_dofs();
  const bool lifted = d.lifted();
  const double scale = terms.hessian_scale;
  const Index ln = lifted ? nv : 0, lt = ln + nc, n = lt + nf, m = nc + 1 + 2 * nf;
  ConvexPhaseQp out;
  out.problem = QpProblem(n);
  out.lambda_offset = ln;
  QpProblem& p = out.problem;
  if (lifted) {
    std::vector<Triplet> t;
    for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, scale / s.minv(i));
    for (Index i = 0; i < nc; ++i) t.emplace_back(ln + i, ln + i, soft.g(i) * d.w_nn(i));
    for (Index i = 0; i < soft.compliance.size(); ++i)  // a pair's normal compliance (add_pair_softness)
      if (soft.compliance(i) != 0.0) t.emplace_back(ln + i, ln + i, soft.compliance(i));
    p.P = from_triplets(n, n, t);
    lifted_momentum_equality(s, /*friction=*/true, p);
  } else {
    SparseMatrix P = d.W;
    if (scale != 1.0) P *= scale;
    for (Index i = 0; i < nc; ++i) P.coeffRef(i, i) += soft.g(i) * d.w_nn(i);
    for (Index i = 0; i < soft.compliance.size(); ++i) P.coeffRef(i, i) += soft.compliance(i);
    p.P = upper_triangle(P);
  }
  std::vector<Triplet> g;
  append_contact_rows(d, n, g);
  append_friction_cone_rows(s, ln, lt, g);
  p.G = from_triplets(m, n, g);
  p.l = Vector::Constant(m, -kInf);
  p.u = Vector::Constant(m, kInf);
  p.l.head(nc) = -d.bn;
  for (Index f = 0; f < nf; ++f) {
    p.u(nc + 1 + 2 * f) = 0.0;
    p.l(nc + 2 + 2 * f) = 0.0;
  }
  if (terms.qn)
    p.q.segment(ln, nc) = *terms.qn - soft.v_ref;
  else
    p.q.segment(ln, nc) = s.Jn * s.v_star - soft.v_ref;
  if (terms.qt)
    p.q.segment(lt, nf) = *terms.qt;
  else
    p.q.segment(lt, nf) = s.Jt * s.v_star;
  p.xl.segment(ln, nc).setZero();
  return out;
}

Index release_open_contacts(const ConvexModelData& d, const Vector& lambda1, QpProblem& phase2, Index lambda_offset,
                            double dt) {
  const ContactSystem& s = d.s;
  const Index nc = s.num_contacts();
  const Vector slack = d.bn + s.Jn * s.minv.cwiseProduct(s.Jn.transpose() * lambda1);  // Jn v1 + max(φ, 0)/Δt
  const double min_slack = kOpenContactMinGap / dt;  // m/s
  Index released = 0;
  for (Index i = 0; i < nc; ++i)
    if (s.phi(i) > 0.0 && slack(i) > d.w_nn(i) * lambda1(i) + min_slack) {
      phase2.xu(lambda_offset + i) = 0.0;
      ++released;
    }
  return released;
}

}  // namespace lcprelax::detail
