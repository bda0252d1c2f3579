// The relaxed loss of one island, lifted (step_loss_relaxed.hpp): the QP's assembly, the
// workspace that reuses the QpSolver's analysis, and the envelope-theorem gradient.
#include <lcprelax/core/errors.hpp>
#include <lcprelax/core/math_constants.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>
#include <lcprelax/learn/step_loss_relaxed.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace lcprelax::learn {
namespace {


// Dynamic bodies (local index) of each contact, from Jn's row pattern.
std::vector<std::vector<int>> contact_bodies(const ContactSystem& s) {
  std::vector<std::vector<int>> b(static_cast<std::size_t>(s.num_contacts()));
  for (Index col = 0; col < s.Jn.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(s.Jn, col); it; ++it) {
      auto& v = b[static_cast<std::size_t>(it.row())];
      const int body = static_cast<int>(col / 3);
      if (std::find(v.begin(), v.end(), body) == v.end()) v.push_back(body);
    }
  return b;
}

// S_c = 1/Σ_b minv(3b) over contact c's dynamic bodies (kg).
Vector contact_scales(const ContactSystem& s, const std::vector<std::vector<int>>& bodies) {
  Vector S(s.num_contacts());
  for (Index c = 0; c < S.size(); ++c) {
    double sum = 0.0;
    for (int b : bodies[static_cast<std::size_t>(c)]) sum += s.minv(3 * b);
    if (!(sum > 0.0)) throw InputError("step loss: Jn: row " + std::to_string(c) + " has no entry");
    S(c) = 1.0 / sum;
  }
  return S;
}

// Σ_b m_b over the island's dynamic bodies (kg, the x entries of M) and their count.
std::pair<double, int> dynamic_mass_sum(const ContactSystem& s) {
  double sum = 0.0;
  int n = 0;
  for (Index k = 0; k < s.num_dofs(); k += 3)
    if (s.minv(k) > 0.0) {
      sum += 1.0 / s.minv(k);
      ++n;
    }
  return {sum, n};
}

// The settings with a2 replaced by a2/σ when normalize_by_mass (header comment).
RelaxedStepLossSettings effective_settings(const ContactSystem& s, const RelaxedStepLossSettings& st) {
  RelaxedStepLossSettings e = st;
  if (!st.normalize_by_mass) return e;
  const auto [sum, n] = dynamic_mass_sum(s);
  if (n == 0 || !(sum > 0.0) || !std::isfinite(sum))
    throw InputError("relaxed step loss: normalize_by_mass: the island has no dynamic body with finite mass");
  e.a2 = st.a2 * n / sum;
  return e;
}

void check_center(const ContactSystem& s, const Vector& center) {
  const Index n = s.num_contacts() + s.num_friction();
  if (center.size() != n || !center.allFinite())
    throw InputError("relaxed step loss: proximal center: expected " + std::to_string(n) +
                     " finite entries [λ̃n; γ], got " + std::to_string(center.size()));
}

// The centred shift's linear and constant parts, (b/2)(t(λ̃n − c_λ)² + (γ − c_γ)²/t) minus
// its quadratic part (which is in P), added to q and r of the relaxed QP.
void add_center_terms(const ContactSystem& s, const Vector& S, const RelaxedStepLossSettings& st, const Vector& center,
                      QpProblem& qp) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), ln = s.num_dofs(), gm = ln + nc + 2 * nf;
  const double t = st.shift_balance;
  for (Index f = 0; f < nf; ++f) {
    const int c = s.friction_rows[static_cast<std::size_t>(f)];
    const double b = st.a2 * s.mu(f) * S(c), cl = center(c), cg = center(nc + f);
    qp.q(ln + c) -= t * b * cl;
    qp.q(gm + f) -= b * cg / t;
    qp.r += 0.5 * b * (t * cl * cl + cg * cg / t);
  }
}

}  // namespace

std::string RelaxedStepLossSettings::validation_error() const {
  if (!(a1 > 0.0) || !std::isfinite(a1)) return "a1: must be finite and > 0";
  if (!(a2 >= 0.0) || !std::isfinite(a2)) return "a2: must be finite and >= 0";
  if (!(regularization > 0.0) || !std::isfinite(regularization)) return "regularization: must be finite and > 0";
  if (!(shift_balance > 0.0) || !std::isfinite(shift_balance)) return "shift_balance: must be finite and > 0";
  if (proximal_iterations < 1) return "proximal_iterations: must be >= 1";
  if (!(proximal_tolerance >= 0.0) || !std::isfinite(proximal_tolerance)) return "proximal_tolerance: must be finite and >= 0";
  const std::string e = qp.validation_error();
  return e.empty() ? e : "qp: " + e;
}

QpProblem relaxed_step_qp(const ContactSystem& s, const Vector& target, double dt,
                          const RelaxedStepLossSettings& given, const Vector* center) {
  if (const std::string e = given.validation_error(); !e.empty()) throw InputError("RelaxedStepLossSettings: " + e);
  validate_step_loss_input(s, target, dt);
  if (s.lcp_block.enabled)
    throw InputError("the relaxed step loss does not take World::lcp_block (the per-contact LCP correction): learn it "
                     "with the hard loss");
  const RelaxedStepLossSettings st = effective_settings(s, given);
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  if (center != nullptr) check_center(s, *center);
  const Index ln = nd, bp = nd + nc, bm = bp + nf, gm = bm + nf, nx = gm + nf;
  const Vector S = contact_scales(s, contact_bodies(s));
  const Vector m = s.minv.cwiseInverse();
  const double eps = st.regularization, t = st.shift_balance;
  QpProblem qp;
  // Cost.
  std::vector<Triplet> pt;
  pt.reserve(static_cast<std::size_t>(nx + nf));
  for (Index k = 0; k < nd; ++k) pt.emplace_back(k, k, 2.0 * (st.a1 + st.a2 * m(k)));
  Vector diag_n = Vector::Constant(nc, eps), diag_g = Vector::Constant(nf, eps);
  for (Index f = 0; f < nf; ++f) {
    const int c = s.friction_rows[static_cast<std::size_t>(f)];
    const double b = st.a2 * s.mu(f) * S(c);
    diag_n(c) += t * b;
    diag_g(f) += b / t;
    pt.emplace_back(ln + c, gm + f, b);  // a2 μ S γ λ̃n
  }
  // Normal compliance c (contact_system.hpp): a2 c λn² = a2 c S² λ̃n² in zᵀw.
  if (s.compliance.size() > 0) diag_n += 2.0 * st.a2 * s.compliance.cwiseProduct(S.cwiseProduct(S));
  for (Index c = 0; c < nc; ++c) pt.emplace_back(ln + c, ln + c, diag_n(c));
  for (Index f = 0; f < nf; ++f) {
    pt.emplace_back(bp + f, bp + f, eps);
    pt.emplace_back(bm + f, bm + f, eps);
    pt.emplace_back(gm + f, gm + f, diag_g(f));
  }
  qp.P.resize(nx, nx);
  qp.P.setFromTriplets(pt.begin(), pt.end());
  qp.P.makeCompressed();
  qp.q = Vector::Zero(nx);
  qp.q.head(nd) = 2.0 * st.a1 * (s.v_star - target) + st.a2 * m.cwiseProduct(s.v_star);
  const Vector phip = normal_gap_rate(s, dt);  // (max(φ, 0) + e·min(φ, 0))/Δt
  qp.q.segment(ln, nc) = st.a2 * S.cwiseProduct(phip);
  qp.r = st.a1 * (s.v_star - target).squaredNorm();
  if (center != nullptr) add_center_terms(s, S, st, *center, qp);
  // Momentum: M Δv − Jnᵀ S λ̃n − Jtᵀ S (β̃⁺ − β̃⁻) = 0.
  std::vector<Triplet> at, gt;
  at.reserve(static_cast<std::size_t>(nd + s.Jn.nonZeros() + 2 * s.Jt.nonZeros()));
  gt.reserve(static_cast<std::size_t>(s.Jn.nonZeros() + 2 * s.Jt.nonZeros() + 5 * nf));
  for (Index k = 0; k < nd; ++k) at.emplace_back(k, k, m(k));
  for (Index j = 0; j < nd; ++j) {
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) {
      at.emplace_back(j, ln + it.row(), -it.value() * S(it.row()));
      gt.emplace_back(it.row(), j, it.value());
    }
    for (SparseMatrix::InnerIterator it(s.Jt, j); it; ++it) {
      const Index f = it.row();
      const double sf = S(s.friction_rows[static_cast<std::size_t>(f)]);
      at.emplace_back(j, bp + f, -it.value() * sf);
      at.emplace_back(j, bm + f, it.value() * sf);
      gt.emplace_back(nc + f, j, it.value());
      gt.emplace_back(nc + nf + f, j, -it.value());
    }
  }
  for (Index c = 0; c < s.compliance.size(); ++c)  // w_n's c λn = c S λ̃n
    if (s.compliance(c) != 0.0) gt.emplace_back(c, ln + c, s.compliance(c) * S(c));
  for (Index f = 0; f < nf; ++f) {
    gt.emplace_back(nc + f, gm + f, 1.0);
    gt.emplace_back(nc + nf + f, gm + f, 1.0);
    gt.emplace_back(nc + 2 * nf + f, ln + s.friction_rows[static_cast<std::size_t>(f)], s.mu(f));
    gt.emplace_back(nc + 2 * nf + f, bp + f, -1.0);
    gt.emplace_back(nc + 2 * nf + f, bm + f, -1.0);
  }
  qp.A.resize(nd, nx);
  qp.A.setFromTriplets(at.begin(), at.end());
  qp.A.makeCompressed();
  qp.b = Vector::Zero(nd);
  qp.G.resize(nc + 3 * nf, nx);
  qp.G.setFromTriplets(gt.begin(), gt.end());
  qp.G.makeCompressed();
  const Vector jnv = s.Jn * s.v_star, jtv = s.Jt * s.v_star;
  qp.l.resize(nc + 3 * nf);
  qp.l << -jnv - phip, -jtv, jtv, Vector::Zero(nf);
  qp.u = Vector::Constant(nc + 3 * nf, kInf);
  qp.xl = Vector::Zero(nx);
  qp.xl.head(nd).setConstant(-kInf);
  qp.xu = Vector::Constant(nx, kInf);
  return qp;
}

struct RelaxedStepLossWorkspace::Impl {
  RelaxedStepLossSettings settings;
  QpSolver solver;
  bool ready = false;
  QpResult empty;
  Vector shifts;
  Vector proximal_point;  // [λ̃n; γ] of the last solve
  int setups = 0, updates = 0, proximal_solves = 0;
  explicit Impl(const RelaxedStepLossSettings& s) : settings(s), solver(s.qp) {}
};

RelaxedStepLossWorkspace::RelaxedStepLossWorkspace(RelaxedStepLossSettings settings) {
  if (const std::string e = settings.validation_error(); !e.empty()) throw InputError("RelaxedStepLossSettings: " + e);
  impl_ = std::make_unique<Impl>(settings);
}
RelaxedStepLossWorkspace::~RelaxedStepLossWorkspace() = default;
RelaxedStepLossWorkspace::RelaxedStepLossWorkspace(RelaxedStepLossWorkspace&&) noexcept = default;
RelaxedStepLossWorkspace& RelaxedStepLossWorkspace::operator=(RelaxedStepLossWorkspace&&) noexcept = default;
const RelaxedStepLossSettings& RelaxedStepLossWorkspace::settings() const { return impl_->settings; }
const QpResult& RelaxedStepLossWorkspace::qp_result() const {
  return impl_->ready ? impl_->solver.result() : impl_->empty;
}
const Vector& RelaxedStepLossWorkspace::shifts() const { return impl_->shifts; }
const Vector& RelaxedStepLossWorkspace::proximal_point() const { return impl_->proximal_point; }
int RelaxedStepLossWorkspace::proximal_solves() const { return impl_->proximal_solves; }
int RelaxedStepLossWorkspace::setups() const { return impl_->setups; }
int RelaxedStepLossWorkspace::updates() const { return impl_->updates; }

StepLossResult RelaxedStepLossWorkspace::evaluate(const ContactSystem& s, const Vector& target, double dt,
                                                  const Vector* center, int iterations) {
  if (iterations < 0) throw InputError("relaxed step loss: proximal iterations must be >= 0 (0: the settings')");
  QpProblem qp = relaxed_step_qp(s, target, dt, impl_->settings);  // validates; centre terms added below
  const RelaxedStepLossSettings st = effective_settings(s, impl_->settings);
  Vector c_used = center != nullptr ? *center : Vector();
  bool centered = center != nullptr;
  if (centered) check_center(s, c_used);
  const Vector q_plain = qp.q;
  const double r_plain = qp.r;
  const Index nc = s.num_contacts(), nf = s.num_friction(), nd = s.num_dofs();
  const Index ln = nd, bp = nd + nc, bm = bp + nf, gm = bm + nf;
  StepLossResult r;
  r.grad.set_zero(s);
  const std::vector<std::vector<int>> bodies = contact_bodies(s);
  const Vector S = contact_scales(s, bodies);
  impl_->shifts.resize(nf);
  for (Index f = 0; f < nf; ++f) impl_->shifts(f) = st.a2 * s.mu(f) * S(s.friction_rows[static_cast<std::size_t>(f)]);
  impl_->proximal_point = Vector::Zero(nc + nf);
  if (centered) add_center_terms(s, S, st, c_used, qp);
  if (nc == 0) {  // no contact: ℓ = a1‖v* − v̄‖²
    r.status = ContactStatus::solved;
    r.v_next = s.v_star;
    r.loss = qp.r;
    r.grad.v_star = 2.0 * st.a1 * (s.v_star - target);
    return r;
  }
  // Proximal point iterations (header comment): each solve re-centres the shift at the
  // previous solution; the gradient is the last solve's, at its centre.
  const QpResult* last = nullptr;
  const int max_it = iterations > 0 ? iterations : st.proximal_iterations;
  for (int it = 0; it < max_it; ++it) {
    if (it > 0) {  // only q and r depend on the centre
      qp.q = q_plain;
      qp.r = r_plain;
      add_center_terms(s, S, st, c_used, qp);
    }
    if (impl_->ready && impl_->solver.can_update(qp)) {
      impl_->solver.update(qp);
      ++impl_->updates;
    } else {
      impl_->solver.setup(qp);
      impl_->ready = true;
      ++impl_->setups;
    }
    ++impl_->proximal_solves;
    const QpResult& res = impl_->solver.solve();
    last = &res;
    r.work += res.info.iterations;
    if (!has_solution(res.info.status)) break;
    Vector& xp = impl_->proximal_point;
    xp << res.x.segment(ln, nc), res.x.segment(gm, nf);
    const double moved = centered ? (xp - c_used).lpNorm<Eigen::Infinity>() : kInf;
    if (moved <= st.proximal_tolerance * std::max(1.0, xp.lpNorm<Eigen::Infinity>())) break;
    if (it + 1 < max_it) {
      c_used = xp;
      centered = true;
    }
  }
  const QpResult& res = *last;
  if (!has_solution(res.info.status)) {
    r.status = ContactStatus::failed;
    r.message = std::string("relaxed: qp ") + to_string(res.info.status) + ": " + res.info.message;
    r.loss = std::numeric_limits<double>::quiet_NaN();
    r.v_next = s.v_star;
    return r;
  }
  r.status = res.info.status == QpStatus::solved ? ContactStatus::solved : ContactStatus::solved_inaccurate;
  if (r.status != ContactStatus::solved) r.message = "relaxed: qp solved_inaccurate";
  r.loss = qp.objective(res.x);

  // Envelope theorem (header comment).
  const double a1 = st.a1, a2 = st.a2, t = st.shift_balance;
  const Vector dv = res.x.head(nd), lnt = res.x.segment(ln, nc);
  const Vector bdiff = res.x.segment(bp, nf) - res.x.segment(bm, nf), gam = res.x.segment(gm, nf);
  const Vector m = s.minv.cwiseInverse();
  const Vector& y = res.y;
  const Vector zn = res.z.head(nc), zt = res.z.segment(nc, nf) - res.z.segment(nc + nf, nf);
  const Vector zg = res.z.segment(nc + 2 * nf, nf);
  r.v_next = s.v_star + dv;
  const Vector& vp = r.v_next;
  const Vector lam_n = S.cwiseProduct(lnt);
  Vector lam_t(nf), Sf(nf);
  for (Index f = 0; f < nf; ++f) Sf(f) = S(s.friction_rows[static_cast<std::size_t>(f)]);
  lam_t = Sf.cwiseProduct(bdiff);
  for (Index j = 0; j < nd; ++j) {
    for (SparseMatrix::InnerIterator it(r.grad.Jn, j); it; ++it)
      it.valueRef() = zn(it.row()) * vp(j) - lam_n(it.row()) * y(j);
    for (SparseMatrix::InnerIterator it(r.grad.Jt, j); it; ++it)
      it.valueRef() = zt(it.row()) * vp(j) - lam_t(it.row()) * y(j);
  }
  r.grad.v_star = 2.0 * a1 * (vp - target) + a2 * m.cwiseProduct(dv) + s.Jn.transpose() * zn + s.Jt.transpose() * zt;
  // The normal rows' gap term (max(φ, 0) + e·min(φ, 0))/Δt and compliance c (header comment).
  const Vector rate = normal_gap_rate(s, dt);
  const Vector comp = s.compliance.size() > 0 ? s.compliance : Vector::Zero(nc);
  for (Index c = 0; c < nc; ++c) {
    const double e = s.erp.size() > 0 ? s.erp(c) : 0.0, share = a2 * S(c) * lnt(c) + zn(c);
    r.grad.phi(c) = s.phi(c) > 0.0 ? share / dt : e * share / dt;
    r.grad.erp(c) = share * std::min(s.phi(c), 0.0) / dt;
    r.grad.compliance(c) = share * S(c) * lnt(c);
  }
  const Vector jny = s.Jn * y, jty = s.Jt * y;
  Vector dS = a2 * lnt.cwiseProduct(rate) - jny.cwiseProduct(lnt) +
              (2.0 * a2 * S.cwiseProduct(lnt) + zn).cwiseProduct(comp).cwiseProduct(lnt);
  // C = ∂ℓ/∂a2 (used by normalize_by_mass's chain through σ, header comment).
  double C = m.cwiseProduct(dv).dot(vp) + S.cwiseProduct(lnt).dot(rate) +
             comp.dot(S.cwiseProduct(lnt).cwiseAbs2());
  for (Index f = 0; f < nf; ++f) {
    const Index c = s.friction_rows[static_cast<std::size_t>(f)];
    const double dl = centered ? lnt(c) - c_used(c) : lnt(c), dg = centered ? gam(f) - c_used(nc + f) : gam(f);
    const double sq = centered && !st.centred_shift_in_gradient ? 0.0 : t * dl * dl + dg * dg / t;
    r.grad.mu(f) = a2 * Sf(f) * gam(f) * lnt(c) + 0.5 * a2 * Sf(f) * sq + zg(f) * lnt(c);
    dS(c) += a2 * s.mu(f) * gam(f) * lnt(c) + 0.5 * a2 * s.mu(f) * sq - jty(f) * bdiff(f);
    C += s.mu(f) * Sf(f) * (gam(f) * lnt(c) + 0.5 * sq);
  }
  r.grad.minv = -(m.cwiseProduct(m)).cwiseProduct(a2 * dv.cwiseProduct(vp) + y.cwiseProduct(dv));
  for (Index c = 0; c < nc; ++c)
    for (int b : bodies[static_cast<std::size_t>(c)]) r.grad.minv(3 * b) -= S(c) * S(c) * dS(c);
  if (impl_->settings.normalize_by_mass && a2 > 0.0) {  // the chain through σ (header comment)
    const double total = dynamic_mass_sum(s).first;
    for (Index k = 0; k < nd; k += 3)
      if (s.minv(k) > 0.0) r.grad.minv(k) += C * a2 * m(k) * m(k) / total;
  }
  return r;
}

StepLossResult relaxed_step_loss(const ContactSystem& s, const Vector& target, double dt,
                                 const RelaxedStepLossSettings& settings, const Vector* center) {
  RelaxedStepLossWorkspace ws(settings);
  return ws.evaluate(s, target, dt, center);
}

}  // namespace lcprelax::learn
