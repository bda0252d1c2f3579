// Builds the internal equilibrated form of a QP (see standard_form.hpp).
// Ruiz, "A scaling algorithm to equilibrate both rows and columns norms in matrices",
// RAL-TR-2001-034, 2001; the cost scaling follows OSQP (Stellato et al. 2020, §5.1).
#include "standard_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::detail {
namespace {

// Keeps scaling factors away from 0 and ∞ for empty or huge rows/columns.
double clamp_norm(double v) { return v < 1e-4 ? 1.0 : std::min(v, 1e4); }

void scale_rows_cols(SparseMatrix& M, const Vector& row, const Vector& col) {
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) it.valueRef() *= row(it.row()) * col(j);
}

// One pass of Ruiz: ∞-norms of the columns of [P; E; G] (P symmetric) and of the rows
// of E and G, then scale by their inverse square roots.
void ruiz_pass(StandardForm& f) {
  Vector cn = Vector::Zero(f.n), en = Vector::Zero(f.me), gn = Vector::Zero(f.mg);
  for (Index j = 0; j < f.n; ++j)
    for (SparseMatrix::InnerIterator it(f.P, j); it; ++it) {
      const double a = std::abs(it.value());
      cn(j) = std::max(cn(j), a);
      cn(it.row()) = std::max(cn(it.row()), a);
    }
  auto rows = [&](const SparseMatrix& M, Vector& rn) {
    for (Index j = 0; j < f.n; ++j)
      for (SparseMatrix::InnerIterator it(M, j); it; ++it) {
        const double a = std::abs(it.value());
        cn(j) = std::max(cn(j), a);
        rn(it.row()) = std::max(rn(it.row()), a);
      }
  };
  rows(f.E, en);
  rows(f.G, gn);
  Vector d = cn.unaryExpr([](double v) { return 1.0 / std::sqrt(clamp_norm(v)); });
  Vector e = en.unaryExpr([](double v) { return 1.0 / std::sqrt(clamp_norm(v)); });
  Vector g = gn.unaryExpr([](double v) { return 1.0 / std::sqrt(clamp_norm(v)); });
  scale_rows_cols(f.P, d, d);
  scale_rows_cols(f.E, e, d);
  scale_rows_cols(f.G, g, d);
  f.Dx.array() *= d.array();
  f.Ee.array() *= e.array();
  f.Eg.array() *= g.array();
}

}  // namespace

StandardForm build_standard_form(const QpProblem& p, int ruiz_iterations) {
  StandardForm f;
  f.n = p.num_variables();
  const Index ma = p.num_equalities(), mi = p.num_inequalities();
  f.g_eq_row.assign(mi, -1);
  f.fixed_eq_row.assign(f.n, -1);
  f.signature.reserve(mi + f.n);

  // Classify rows of G and variable bounds.
  for (Index k = 0; k < ma; ++k) {
    f.eq_source.push_back(EqSource::a_row);
    f.eq_index.push_back(k);
  }
  for (Index i = 0; i < mi; ++i) {
    const bool lo = std::isfinite(p.l(i)), hi = std::isfinite(p.u(i));
    if (lo && hi && p.l(i) == p.u(i)) {
      f.g_eq_row[i] = static_cast<Index>(f.eq_source.size());
      f.eq_source.push_back(EqSource::g_row);
      f.eq_index.push_back(i);
      f.signature.push_back('e');
    } else if (lo || hi) {
      f.g_index.push_back(i);
      f.signature.push_back(lo && hi ? 'b' : (lo ? 'l' : 'u'));
    } else {
      f.signature.push_back('f');
    }
  }
  for (Index j = 0; j < f.n; ++j) {
    const bool lo = std::isfinite(p.xl(j)), hi = std::isfinite(p.xu(j));
    if (lo && hi && p.xl(j) == p.xu(j)) {
      f.fixed_eq_row[j] = static_cast<Index>(f.eq_source.size());
      f.eq_source.push_back(EqSource::fixed_variable);
      f.eq_index.push_back(j);
      f.signature.push_back('e');
    } else {
      f.signature.push_back(lo && hi ? 'b' : (lo ? 'l' : (hi ? 'u' : 'f')));
    }
  }
  f.me = static_cast<Index>(f.eq_source.size());
  f.mg = static_cast<Index>(f.g_index.size());

  // Unscaled internal matrices. Rows of G are picked through a row-major copy.
  const Eigen::SparseMatrix<double, Eigen::RowMajor, Index> Gr = p.G;
  const Eigen::SparseMatrix<double, Eigen::RowMajor, Index> Ar = p.A;
  std::vector<Triplet> te, tg;
  te.reserve(p.A.nonZeros() + p.G.nonZeros() + f.n);
  tg.reserve(p.G.nonZeros());
  f.be.resize(f.me);
  for (Index k = 0; k < f.me; ++k) {
    const Index src = f.eq_index[k];
    switch (f.eq_source[k]) {
      case EqSource::a_row:
        for (decltype(Ar)::InnerIterator it(Ar, src); it; ++it) te.emplace_back(k, it.col(), it.value());
        f.be(k) = p.b(src);
        break;
      case EqSource::g_row:
        for (decltype(Gr)::InnerIterator it(Gr, src); it; ++it) te.emplace_back(k, it.col(), it.value());
        f.be(k) = p.u(src);
        break;
      case EqSource::fixed_variable:
        te.emplace_back(k, src, 1.0);
        f.be(k) = p.xl(src);
        break;
    }
  }
  f.gl.resize(f.mg);
  f.gu.resize(f.mg);
  for (Index k = 0; k < f.mg; ++k) {
    const Index src = f.g_index[k];
    for (decltype(Gr)::InnerIterator it(Gr, src); it; ++it) tg.emplace_back(k, it.col(), it.value());
    f.gl(k) = p.l(src);
    f.gu(k) = p.u(src);
  }
  f.E.resize(f.me, f.n);
  f.E.setFromTriplets(te.begin(), te.end());
  f.G.resize(f.mg, f.n);
  f.G.setFromTriplets(tg.begin(), tg.end());
  f.P = p.P;
  f.P.makeCompressed();
  f.q = p.q;
  f.xl = p.xl;
  f.xu = p.xu;
  for (Index j = 0; j < f.n; ++j)
    if (f.fixed_eq_row[j] >= 0) {
      f.xl(j) = -std::numeric_limits<double>::infinity();
      f.xu(j) = std::numeric_limits<double>::infinity();
    }

  // Equilibrate.
  f.Dx = Vector::Ones(f.n);
  f.Ee = Vector::Ones(f.me);
  f.Eg = Vector::Ones(f.mg);
  for (int it = 0; it < ruiz_iterations; ++it) ruiz_pass(f);
  f.q.array() *= f.Dx.array();
  f.be.array() *= f.Ee.array();
  f.gl.array() *= f.Eg.array();
  f.gu.array() *= f.Eg.array();
  f.xl.array() /= f.Dx.array();
  f.xu.array() /= f.Dx.array();
  if (ruiz_iterations > 0) {
    double pmean = 0.0;
    for (Index j = 0; j < f.n; ++j) {
      double cmax = 0.0;
      for (SparseMatrix::InnerIterator it(f.P, j); it; ++it) cmax = std::max(cmax, std::abs(it.value()));
      pmean += cmax;
    }
    pmean = f.n > 0 ? pmean / f.n : 0.0;
    const double qn = f.q.size() > 0 ? f.q.lpNorm<Eigen::Infinity>() : 0.0;
    f.c = 1.0 / clamp_norm(std::max(pmean, qn));
    f.P *= f.c;
    f.q *= f.c;
  }
  f.Et = f.E.transpose();
  f.Gt = f.G.transpose();
  f.E.makeCompressed();
  f.G.makeCompressed();
  return f;
}

}  // namespace lcprelax::detail
