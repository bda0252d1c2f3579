// Auxiliary infeasibility LPs (see qp_infeasibility_lp.hpp).
#include "qp_infeasibility_lp.hpp"
#include "vector_norms.hpp"

#include <lcprelax/kkt/qp_solver.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Settings for an auxiliary solve: no recursion into further auxiliary LPs.
QpSettings auxiliary_settings(const QpSettings& s) {
  QpSettings a = s;
  a.infeasibility_lps = false;
  a.verbose = false;
  a.eps_abs = std::min(s.eps_abs, 1e-9);
  return a;
}

bool solved(const QpResult& r) {
  return has_solution(r.info.status);
}

}  // namespace

bool prove_primal_infeasible(const QpProblem& p, const QpSettings& s, QpResult& cert) {
  const Index n = p.num_variables(), ma = p.num_equalities(), mi = p.num_inequalities();
  // Rows of the LP: (kind, original index, upper side?) with kind 0 = A, 1 = G, 2 = bound.
  struct Row {
    int kind;
    Index index;
    bool upper;
  };
  std::vector<Row> rows;
  std::vector<Triplet> t;
  std::vector<double> lo, hi;
  const Eigen::SparseMatrix<double, Eigen::RowMajor, Index> Ar = p.A, Gr = p.G;
  auto add = [&](int kind, Index idx, bool upper, double bound, auto&& emit_row) {
    const Index r = static_cast<Index>(rows.size());
    rows.push_back({kind, idx, upper});
    emit_row(r);
    t.emplace_back(r, n, upper ? -1.0 : 1.0);
    lo.push_back(upper ? -kInf : bound);
    hi.push_back(upper ? bound : kInf);
  };
  for (Index k = 0; k < ma; ++k)
    for (bool upper : {true, false})
      add(0, k, upper, p.b(k), [&](Index r) {
        for (decltype(Ar)::InnerIterator it(Ar, k); it; ++it) t.emplace_back(r, it.col(), it.value());
      });
  for (Index i = 0; i < mi; ++i)
    for (bool upper : {true, false}) {
      const double bound = upper ? p.u(i) : p.l(i);
      if (!std::isfinite(bound)) continue;
      add(1, i, upper, bound, [&](Index r) {
        for (decltype(Gr)::InnerIterator it(Gr, i); it; ++it) t.emplace_back(r, it.col(), it.value());
      });
    }
  for (Index j = 0; j < n; ++j)
    for (bool upper : {true, false}) {
      const double bound = upper ? p.xu(j) : p.xl(j);
      if (!std::isfinite(bound)) continue;
      add(2, j, upper, bound, [&](Index r) { t.emplace_back(r, j, 1.0); });
    }
  QpProblem lp(n + 1);
  lp.q(n) = 1.0;
  lp.xl(n) = 0.0;
  lp.G.resize(static_cast<Index>(rows.size()), n + 1);
  lp.G.setFromTriplets(t.begin(), t.end());
  lp.l = Eigen::Map<const Vector>(lo.data(), static_cast<Index>(lo.size()));
  lp.u = Eigen::Map<const Vector>(hi.data(), static_cast<Index>(hi.size()));
  QpSolver solver(auxiliary_settings(s));
  solver.setup(lp);
  const QpResult& r = solver.solve();
  if (!solved(r) || !(r.x(n) > std::max(1e-6, 1e3 * s.eps_abs))) return false;

  cert.y = Vector::Zero(ma);
  cert.z = Vector::Zero(mi);
  cert.z_bounds = Vector::Zero(n);
  for (size_t k = 0; k < rows.size(); ++k) {
    Vector& target = rows[k].kind == 0 ? cert.y : (rows[k].kind == 1 ? cert.z : cert.z_bounds);
    target(rows[k].index) += r.z(static_cast<Index>(k));
  }
  const double nrm = std::max({inf_norm(cert.y), inf_norm(cert.z), inf_norm(cert.z_bounds)});
  if (!(nrm > 0)) return false;
  cert.y /= nrm;
  cert.z /= nrm;
  cert.z_bounds /= nrm;
  // Verify: Aᵀy + Gᵀz + z_bounds ≈ 0 and bᵀy + Σ u z⁺ + l z⁻ < 0.
  const Vector res = p.A.transpose() * cert.y + p.G.transpose() * cert.z + cert.z_bounds;
  double support = p.b.dot(cert.y);
  auto add_support = [&](double z, double lo_b, double hi_b) {
    if (z > 0) support += std::isfinite(hi_b) ? hi_b * z : kInf;
    if (z < 0) support += std::isfinite(lo_b) ? lo_b * z : kInf;
  };
  for (Index i = 0; i < mi; ++i) add_support(cert.z(i), p.l(i), p.u(i));
  for (Index j = 0; j < n; ++j) add_support(cert.z_bounds(j), p.xl(j), p.xu(j));
  return inf_norm(res) <= 1e-6 && support < 0;
}

bool prove_dual_infeasible(const QpProblem& p, const QpSettings& s, QpResult& cert) {
  const Index n = p.num_variables(), ma = p.num_equalities(), mi = p.num_inequalities();
  const SparseMatrix Pfull = p.P.selfadjointView<Eigen::Upper>();
  QpProblem lp(n);
  lp.q = p.q;
  std::vector<Triplet> t;
  Index r = 0;
  auto append = [&](const SparseMatrix& M) {
    for (Index j = 0; j < M.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) t.emplace_back(r + it.row(), j, it.value());
    r += static_cast<Index>(M.rows());
  };
  append(Pfull);
  append(p.A);
  append(p.G);
  lp.G.resize(r, n);
  lp.G.setFromTriplets(t.begin(), t.end());
  lp.l = Vector::Zero(r);
  lp.u = Vector::Zero(r);
  for (Index i = 0; i < mi; ++i) {
    lp.l(n + ma + i) = std::isfinite(p.l(i)) ? 0.0 : -kInf;
    lp.u(n + ma + i) = std::isfinite(p.u(i)) ? 0.0 : kInf;
  }
  for (Index j = 0; j < n; ++j) {
    lp.xl(j) = std::isfinite(p.xl(j)) ? 0.0 : -1.0;
    lp.xu(j) = std::isfinite(p.xu(j)) ? 0.0 : 1.0;
  }
  QpSolver solver(auxiliary_settings(s));
  solver.setup(lp);
  const QpResult& res = solver.solve();
  if (!solved(res) || !(res.info.objective < -std::max(1e-6, 1e3 * s.eps_abs))) return false;
  const double nrm = inf_norm(res.x);
  if (!(nrm > 0)) return false;
  cert.x = res.x / nrm;
  const double tol = 1e-6;
  if (inf_norm(Pfull * cert.x) > tol || inf_norm(p.A * cert.x) > tol) return false;
  const Vector Gd = p.G * cert.x;
  for (Index i = 0; i < mi; ++i)
    if ((std::isfinite(p.u(i)) && Gd(i) > tol) || (std::isfinite(p.l(i)) && Gd(i) < -tol)) return false;
  return p.q.dot(cert.x) < 0;
}

}  // namespace lcprelax::detail
