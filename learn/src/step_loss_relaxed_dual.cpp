// The dual-form relaxed loss of one island (step_loss_relaxed_dual.hpp): the scaled sparse
// Stewart–Trinkle LCP solved by RelaxedLcpSolver, its envelope gradient chained through the
// scaling S and stewart_trinkle_pullback to ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/learn/step_loss_relaxed_dual.hpp>
#include <lcprelax/learn/stewart_trinkle_pullback.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <limits>
#include <string>

namespace lcprelax::learn {

const char* to_string(RelaxedDualScaling s) {
  switch (s) {
    case RelaxedDualScaling::energy: return "energy";
    case RelaxedDualScaling::velocity: return "velocity";
  }
  return "unknown";
}

RelaxedDualStepLossSettings::RelaxedDualStepLossSettings() {
  relaxed.nonconvex = NonconvexPolicy::shift;
  relaxed.a2 = 0.1;
  relaxed.regularization = 1e-6;
}

std::string RelaxedDualStepLossSettings::validation_error() const {
  std::string e = relaxed.validation_error();
  if (!e.empty()) return "relaxed: " + e;
  if (relaxed.max_dissipation != MaxDissipation::none) return "relaxed: max_dissipation must be none for an island";
  e = qp.validation_error();
  if (!e.empty()) return "qp: " + e;
  if (scaling != RelaxedDualScaling::energy && scaling != RelaxedDualScaling::velocity) return "scaling: unknown value";
  return {};
}

struct RelaxedDualStepLossWorkspace::Impl {
  RelaxedDualStepLossSettings settings;
  RelaxedLcpSolver solver;
  RelaxedLcpResult empty;
  const RelaxedLcpResult* last = &empty;
  Vector S;
  Impl(const RelaxedDualStepLossSettings& st) : settings(st), solver(st.relaxed, st.qp) {}
};

RelaxedDualStepLossWorkspace::RelaxedDualStepLossWorkspace(RelaxedDualStepLossSettings settings) {
  const std::string e = settings.validation_error();
  if (!e.empty()) throw InputError("RelaxedDualStepLossSettings: " + e);
  impl_ = std::make_unique<Impl>(settings);
}
RelaxedDualStepLossWorkspace::~RelaxedDualStepLossWorkspace() = default;
RelaxedDualStepLossWorkspace::RelaxedDualStepLossWorkspace(RelaxedDualStepLossWorkspace&&) noexcept = default;
RelaxedDualStepLossWorkspace& RelaxedDualStepLossWorkspace::operator=(RelaxedDualStepLossWorkspace&&) noexcept =
    default;

const RelaxedDualStepLossSettings& RelaxedDualStepLossWorkspace::settings() const { return impl_->settings; }
const RelaxedLcpResult& RelaxedDualStepLossWorkspace::last() const { return *impl_->last; }
const Vector& RelaxedDualStepLossWorkspace::scaling() const { return impl_->S; }

StepLossResult RelaxedDualStepLossWorkspace::evaluate(const ContactSystem& s, const Vector& target, double dt) {
  validate_step_loss_input(s, target, dt);
  if (s.lcp_block.enabled)
    throw InputError("the relaxed step loss does not take World::lcp_block (the per-contact LCP correction): learn it "
                     "with the hard loss");
  if (has_normal_softness(s))
    throw InputError("the relaxed-dual step loss does not take normal compliance or erp (FrictionTable): learn them "
                     "with the relaxed (lifted) or the hard loss");
  Impl& m = *impl_;
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const Index n = nc + 3 * nf;
  const double a1 = m.settings.relaxed.a1;
  StepLossResult r;
  r.grad.set_zero(s);
  m.last = &m.empty;
  if (nc == 0) {  // no contact: the subproblem has no variables, ℓ = a1‖v* − v̄‖²
    m.S.resize(0);
    r.status = ContactStatus::solved;
    r.v_next = s.v_star;
    r.loss = a1 * (s.v_star - target).squaredNorm();
    r.grad.v_star = 2.0 * a1 * (s.v_star - target);
    return r;
  }

  // S per contact (reduced mass over the x columns of Jn's row), then per LCP unknown.
  Vector inv_mass = Vector::Zero(nc);
  for (Index k = 0; k < s.Jn.outerSize(); k += 3)
    for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it) inv_mass(it.row()) += s.minv(k);
  const Vector Sc = inv_mass.cwiseInverse();
  const bool energy = m.settings.scaling == RelaxedDualScaling::energy;
  Vector& S = m.S;
  S = Vector::Ones(n);
  S.head(nc) = Sc;
  Vector R = Vector::Ones(n);  // row scaling: S (energy), or 1/S_c(f) on the γ rows (velocity)
  for (Index f = 0; f < nf; ++f) {
    const double sf = Sc(s.friction_rows[static_cast<std::size_t>(f)]);
    S(nc + f) = S(nc + nf + f) = sf;
    if (!energy) R(nc + 2 * nf + f) = 1.0 / sf;
  }
  if (energy) R = S;

  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
  const StewartTrinklePrediction pred = stewart_trinkle_prediction(s);
  RelaxedLcpData data;
  data.M = lcp.M;
  for (Index j = 0; j < data.M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(data.M, j); it; ++it) it.valueRef() *= R(it.row()) * S(j);
  data.q = R.cwiseProduct(lcp.q);
  data.P = pred.P;  // same pattern, columns scaled
  for (Index j = 0; j < data.P.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(data.P, j); it; ++it) it.valueRef() *= S(j);
  data.p = pred.p;
  data.target = target;
  const RelaxedLcpResult& res = m.solver.solve(data, true);
  m.last = &res;
  r.work = res.iterations;
  if (res.status != RelaxedLcpStatus::solved) {
    r.status = ContactStatus::failed;
    r.message = std::string("relaxed dual: ") + to_string(res.status) + ": " + res.message;
    r.loss = std::numeric_limits<double>::quiet_NaN();
    r.v_next = s.v_star;
    return r;
  }
  r.status = res.qp_status == QpStatus::solved ? ContactStatus::solved : ContactStatus::solved_inaccurate;
  r.loss = res.cost;
  r.v_next = pred.P * S.cwiseProduct(res.lambda) + pred.p;

  // Unscale: ∂ℓ/∂(M, q, P), ∂ℓ/∂S and ∂ℓ/∂R (every entry of Ms = R M S depends on R and S,
  // the constant entries too).
  const RelaxedLcpGradient& g = res.gradient;
  Vector dS = Vector::Zero(n);
  Vector dR = g.dq.cwiseProduct(lcp.q);
  SparseMatrix dM = g.dM;  // Ms's pattern = M_lcp's
  for (Index j = 0; j < dM.outerSize(); ++j) {
    SparseMatrix::InnerIterator mv(lcp.M, j);
    for (SparseMatrix::InnerIterator it(dM, j); it; ++it, ++mv) {
      const Index i = it.row();
      const double e = it.value() * mv.value();  // ∂ℓ/∂Ms_ij · M_ij
      dR(i) += e * S(j);
      dS(j) += e * R(i);
      it.valueRef() *= R(i) * S(j);
    }
  }
  SparseMatrix dP = g.dP;  // Ps's pattern = P's
  for (Index j = 0; j < dP.outerSize(); ++j) {
    SparseMatrix::InnerIterator pv(pred.P, j);
    for (SparseMatrix::InnerIterator it(dP, j); it; ++it, ++pv) {
      dS(j) += it.value() * pv.value();
      it.valueRef() *= S(j);
    }
  }
  const Vector dq = R.cwiseProduct(g.dq);
  r.grad = stewart_trinkle_pullback(s, dt, dM, dq, dP, g.dp);

  // ∂ℓ/∂S_c (λn_c and the β± of c's rows; R = S, or R_γf = 1/S_c(f)) → ∂ℓ/∂minv(3b) = −S_c² ∂ℓ/∂S_c.
  if (energy) dS += dR;
  Vector dSc = dS.head(nc);
  for (Index f = 0; f < nf; ++f) {
    const Index c = s.friction_rows[static_cast<std::size_t>(f)];
    dSc(c) += dS(nc + f) + dS(nc + nf + f);
    if (!energy) dSc(c) -= dR(nc + 2 * nf + f) / (Sc(c) * Sc(c));
  }
  for (Index k = 0; k < s.Jn.outerSize(); k += 3)
    for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it)
      r.grad.minv(k) -= Sc(it.row()) * Sc(it.row()) * dSc(it.row());
  return r;
}

StepLossResult relaxed_dual_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                      const RelaxedDualStepLossSettings& settings) {
  RelaxedDualStepLossWorkspace ws(settings);
  return ws.evaluate(s, target, dt);
}

}  // namespace lcprelax::learn
