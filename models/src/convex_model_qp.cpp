// The convex model's phase QPs in the dual and the lifted formulation (convex_model_qp.hpp).
#include "convex_model_qp.hpp"

#include <lcprelax/models/convex_qp_rows.hpp>
#include <lcprelax/sparse/triplets.hpp>

#include <cmath>
#include <limits>
#include <vector>

namespace lcprelax {

void lifted_momentum_equality(const ContactSystem& s, bool friction, QpProblem& p) {
  const Index nv = s.num_dofs(), nc = s.num_contacts();
  std::vector<Triplet> t;
  for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, 1.0 / s.minv(i));
  append_triplets(t, s.Jn, 0, nv, -1.0, /*transpose=*/true);
  if (friction) append_triplets(t, s.Jt, 0, nv + nc, -1.0, /*transpose=*/true);
  p.A = from_triplets(nv, p.num_variables(), t);
  p.b = Vector::Zero(nv);
}

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

}  // namespace lcprelax

namespace lcprelax::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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
  if (form == ConvexFormulation::dual) W = delassus(s);
}

ConvexPhaseQp convex_phase1_qp(const ConvexModelData& d, const NormalSofteningTerms& soft) {
  const ContactSystem& s = d.s;
  const Index nc = s.num_contacts(), nv = s.num_dofs();
  ConvexPhaseQp out;
  if (d.form == ConvexFormulation::dual) {
    out.problem = QpProblem(nc);
    out.problem.P = upper_triangle(d.W.topLeftCorner(nc, nc));
  } else {  // x = (w, λn): ½ wᵀ M w + bnᵀ λn, M w = Jnᵀ λn
    out.problem = QpProblem(nv + nc);
    std::vector<Triplet> t;
    for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, 1.0 / s.minv(i));
    out.problem.P = from_triplets(nv + nc, nv + nc, t);
    lifted_momentum_equality(s, /*friction=*/false, out.problem);
    out.lambda_offset = nv;
  }
  QpProblem& p = out.problem;
  p.q.tail(nc) = d.bn - soft.v_ref;  // v_ref = 0 (exp_phi) leaves bn bitwise unchanged
  p.xl.tail(nc).setZero();
  return out;
}

ConvexPhaseQp convex_phase2_qp(const ConvexModelData& d, const NormalSofteningTerms& soft) {
  const ContactSystem& s = d.s;
  const Index nc = s.num_contacts(), nf = s.num_friction(), nv = s.num_dofs();
  const bool lifted = d.form == ConvexFormulation::lifted;
  const Index ln = lifted ? nv : 0, lt = ln + nc, n = lt + nf, m = nc + 1 + 2 * nf;
  ConvexPhaseQp out;
  out.problem = QpProblem(n);
  out.lambda_offset = ln;
  QpProblem& p = out.problem;
  std::vector<Triplet> g;  // rows 0..nc: Jn v⁺ + max(φ,0)/Δt ≥ 0, i.e. (Jn w or Wn λ) ≥ −bn
  if (lifted) {
    std::vector<Triplet> t;
    for (Index i = 0; i < nv; ++i) t.emplace_back(i, i, 1.0 / s.minv(i));
    for (Index i = 0; i < nc; ++i) t.emplace_back(ln + i, ln + i, soft.g(i) * d.w_nn(i));
    p.P = from_triplets(n, n, t);
    lifted_momentum_equality(s, /*friction=*/true, p);
    append_triplets(g, s.Jn, 0, 0, 1.0);
  } else {
    SparseMatrix P = d.W;
    for (Index i = 0; i < nc; ++i) P.coeffRef(i, i) += soft.g(i) * d.w_nn(i);
    p.P = upper_triangle(P);
    for (Index c = 0; c < n; ++c)
      for (SparseMatrix::InnerIterator it(d.W, c); it; ++it)
        if (it.row() < nc) g.emplace_back(it.row(), c, it.value());
  }
  p.q.segment(ln, nc) = s.Jn * s.v_star - soft.v_ref;
  p.q.segment(lt, nf) = s.Jt * s.v_star;
  append_friction_cone_rows(s, ln, lt, g);
  p.G = from_triplets(m, n, g);
  p.l = Vector::Constant(m, -kInf);
  p.u = Vector::Constant(m, kInf);
  p.l.head(nc) = -d.bn;
  for (Index f = 0; f < nf; ++f) {
    p.u(nc + 1 + 2 * f) = 0.0;
    p.l(nc + 2 + 2 * f) = 0.0;
  }
  p.xl.segment(ln, nc).setZero();
  return out;
}

}  // namespace lcprelax::detail
