// The convex two-phase loss of a polygon sample, with the deviation penalty, gradient by
// QpSolver::backward through both phases (polygon_losses.hpp).
#include "elapsed.hpp"
#include "polygon_solvers.hpp"

#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/learn/polygon_losses.hpp>

#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

namespace lcprelax::learn {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kKappaSlack[] = {1e-6, 1e-4, 1e-2};  // as convex_model.cpp

using detail::since;


// Upper triangle of a dense symmetric matrix, every entry stored.
SparseMatrix upper_full(const DenseMatrix& A) {
  std::vector<Triplet> t;
  for (Index j = 0; j < A.cols(); ++j)
    for (Index i = 0; i <= j; ++i) t.emplace_back(i, j, A(i, j));
  SparseMatrix S(static_cast<Index>(A.rows()), static_cast<Index>(A.cols()));
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

// The data of both phases (value or tangent; the tangent has zero constant blocks).
struct ConvexQps {
  DenseMatrix P1, G1, P2, G2;  // G1 = Wnn; G2: Wn rows, eᵀ row, friction rows
  Vector q1, l1, q2, l2;       // l1 = −bn; l2: only the −bn rows vary
};

// Builds the QP data from contact data d (value) or its tangent dd (derivative, when
// `tangent` is given): everything is bilinear in (J, D, v*, φ, μ) except exp(φ).
void build(const PolygonContactData& d, const PolygonContactData* dd, const Vector& target, double dt, double w,
           double rho, ConvexQps& out) {
  const Index nc = d.num_contacts(), n = 2 * nc;
  DenseMatrix J(n, 3), dJ = DenseMatrix::Zero(n, 3);
  J << d.Jn, d.Jt;
  if (dd) dJ << dd->Jn, dd->Jt;
  const DenseMatrix W = J * d.minv.asDiagonal() * J.transpose();
  const Vector e = d.v_star - target;
  DenseMatrix Wv;
  Vector bn, Jv, Je, gap_term(nc);
  if (!dd) {
    Wv = W;
    for (Index k = 0; k < nc; ++k) gap_term(k) = std::max(d.phi(k), 0.0) / dt;
    Jv = J * d.v_star;
    Je = J * e;
  } else {
    Wv = dJ * d.minv.asDiagonal() * J.transpose() + J * dd->minv.asDiagonal() * J.transpose() +
         J * d.minv.asDiagonal() * dJ.transpose();
    for (Index k = 0; k < nc; ++k) gap_term(k) = d.phi(k) > 0 ? dd->phi(k) / dt : 0.0;
    Jv = dJ * d.v_star + J * dd->v_star;
    Je = dJ * e + J * dd->v_star;
  }
  bn = Jv.head(nc) + gap_term;
  out.P1 = (1.0 + w) * Wv.topLeftCorner(nc, nc);
  out.q1 = bn + w * Je.head(nc);
  out.G1 = Wv.topLeftCorner(nc, nc);
  out.l1 = -bn;
  out.P2 = (1.0 + w) * Wv;
  for (Index k = 0; k < nc; ++k) {
    const double ex = std::exp(d.phi(k));
    out.P2(k, k) += !dd ? 2.0 * rho * ex * W(k, k) : 2.0 * rho * ex * (dd->phi(k) * W(k, k) + Wv(k, k));
  }
  out.q2 = Jv + w * Je;
  const Index m = nc + 1 + 2 * nc;
  out.G2.setZero(m, n);
  out.G2.topRows(nc) = Wv.topRows(nc);
  for (Index k = 0; k < nc; ++k) {
    const double mu = dd ? dd->mu(k) : d.mu(k);
    if (!dd) out.G2(nc, k) = 1.0;
    if (!dd) out.G2(nc + 1 + 2 * k, nc + k) = 1.0;
    out.G2(nc + 1 + 2 * k, k) = -mu;
    if (!dd) out.G2(nc + 2 + 2 * k, nc + k) = 1.0;
    out.G2(nc + 2 + 2 * k, k) = mu;
  }
  out.l2 = Vector::Zero(m);
  out.l2.head(nc) = -bn;
}

void store(const QpResult& r, Vector& x, Vector& y, Vector& z, Vector& zb) {
  x = r.x, y = r.y, z = r.z, zb = r.z_bounds;
}

}  // namespace

SampleResult polygon_convex_loss(const PolygonAssembly& a, const Vec3& target_v, double dt,
                                 const PolygonLossSettings& settings, PolygonWarmStart& warm, PolygonLossTimes& times,
                                 PolygonSolvers* solvers) {
  const Index np = static_cast<Index>(a.tangent.size()), nc = a.value.num_contacts();
  const Vector target(target_v);
  const double w = settings.convex_deviation, rho = settings.convex_rho;
  SampleResult r;
  r.gradient = Vector::Zero(np);
  auto t0 = std::chrono::steady_clock::now();
  ConvexQps qp, dqp;
  const PolygonContactData& v = a.value;
  if (nc > 0) build(v, nullptr, target, dt, w, rho, qp);
  // No contact, or none approaching in either phase-1 term: λ = 0 (locally constant).
  if (nc == 0 || qp.q1.minCoeff() >= 0.0) {
    const Vector e = v.v_star - target;
    r.loss = e.squaredNorm();
    for (Index k = 0; k < np; ++k) r.gradient(k) = 2.0 * e.dot(a.tangent[static_cast<std::size_t>(k)].v_star);
    times.assembly += since(t0);
    ++times.samples;
    return r;
  }
  const Index n = 2 * nc;
  QpProblem p1(nc);
  p1.P = upper_full(qp.P1);
  p1.q = qp.q1;
  p1.xl.setZero();
  p1.G = full_pattern(qp.G1);  // Wnn λn + bn ≥ 0: with w > 0 the objective alone does not imply it
  p1.l = qp.l1;
  p1.u = Vector::Constant(nc, kInf);
  QpProblem p2(n);
  p2.P = upper_full(qp.P2);
  p2.q = qp.q2;
  p2.G = full_pattern(qp.G2);
  const Index m = qp.G2.rows();
  p2.l = Vector::Constant(m, -kInf);
  p2.u = Vector::Constant(m, kInf);
  p2.l.head(nc) = qp.l2.head(nc);
  for (Index k = 0; k < nc; ++k) p2.u(nc + 1 + 2 * k) = 0.0, p2.l(nc + 2 + 2 * k) = 0.0;
  p2.xl.head(nc).setZero();
  times.assembly += since(t0);

  t0 = std::chrono::steady_clock::now();
  std::unique_ptr<PolygonSolvers> local;
  if (!solvers) local = std::make_unique<PolygonSolvers>(settings);
  QpSolver& s1 = solvers ? solvers->phase1 : local->phase1;
  QpSolver& s2 = solvers ? solvers->phase2 : local->phase2;
  setup_or_update(s1, p1);
  if (settings.warm_start && warm.x1.size() == nc) s1.warm_start(warm.x1, warm.y1, warm.z1, warm.zb1);
  const QpResult& r1 = s1.solve();
  if (!has_solution(r1.info.status)) {
    r.ok = false;
    r.message = std::string("convex phase 1: ") + to_string(r1.info.status) + ": " + r1.info.message;
    times.solve += since(t0);
    return r;
  }
  const double kappa = r1.x.cwiseMax(0.0).sum();
  double slack_used = 0.0;
  bool ok2 = false;
  for (double slack : kKappaSlack) {
    p2.u(nc) = kappa * (1.0 + slack) + 1e-12;
    setup_or_update(s2, p2);
    if (settings.warm_start && warm.x2.size() == n && slack == kKappaSlack[0])
      s2.warm_start(warm.x2, warm.y2, warm.z2, warm.zb2);
    if (has_solution(s2.solve().info.status)) {
      ok2 = true;
      slack_used = slack;
      break;
    }
  }
  const QpResult& r2 = s2.result();
  if (!ok2) {
    r.ok = false;
    r.message = std::string("convex phase 2: ") + to_string(r2.info.status) + ": " + r2.info.message;
    times.solve += since(t0);
    return r;
  }
  if (settings.warm_start) {
    store(r1, warm.x1, warm.y1, warm.z1, warm.zb1);
    store(r2, warm.x2, warm.y2, warm.z2, warm.zb2);
  }
  DenseMatrix J(n, 3);
  J << v.Jn, v.Jt;
  const Vector lambda = r2.x;
  const Vector impulse = J.transpose() * lambda;
  const Vector v_next = v.v_star + v.minv.cwiseProduct(impulse);
  const Vector g = 2.0 * (v_next - target);
  r.loss = (v_next - target).squaredNorm();
  times.solve += since(t0);

  // Backward: phase 2, then phase 1 through κ.
  t0 = std::chrono::steady_clock::now();
  const QpGradient g2 = s2.backward(J * v.minv.cwiseProduct(g));
  const double dl_dkappa = g2.du(nc) * (1.0 + slack_used);
  Vector dl_dx1 = Vector::Zero(nc);
  for (Index k = 0; k < nc; ++k) dl_dx1(k) = r1.x(k) > 0 ? dl_dkappa : 0.0;
  const QpGradient g1 = s1.backward(dl_dx1);
  for (Index k = 0; k < np; ++k) {
    const PolygonContactData& t = a.tangent[static_cast<std::size_t>(k)];
    build(v, &t, target, dt, w, rho, dqp);
    DenseMatrix dJ(n, 3);
    dJ << t.Jn, t.Jt;
    const Vector dv_next = t.v_star + t.minv.cwiseProduct(impulse) + v.minv.cwiseProduct(dJ.transpose() * lambda);
    double s = g.dot(dv_next);
    s += pattern_inner(g1.dP, dqp.P1) + g1.dq.dot(dqp.q1) + pattern_inner(g1.dG, dqp.G1) + g1.dl.dot(dqp.l1);
    s += pattern_inner(g2.dP, dqp.P2) + g2.dq.dot(dqp.q2) + pattern_inner(g2.dG, dqp.G2) + g2.dl.dot(dqp.l2);
    r.gradient(k) = s;
  }
  times.backward += since(t0);
  ++times.samples;
  return r;
}

}  // namespace lcprelax::learn
