// Builds the internal equilibrated form of a QP and refreshes its values in place (see
// standard_form.hpp). Ruiz, "A scaling algorithm to equilibrate both rows and columns
// norms in matrices", RAL-TR-2001-034, 2001; the cost scaling follows OSQP (Stellato et
// al. 2020, §5.1).
#include "standard_form.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcprelax::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Keeps scaling factors away from 0 and ∞ for empty or huge rows/columns.
double clamp_norm(double v) { return v < 1e-4 ? 1.0 : std::min(v, 1e4); }

// Classification of a pair of bounds (see StandardForm::signature).
char classify(double lo, double hi) {
  const bool l = std::isfinite(lo), u = std::isfinite(hi);
  if (l && u && lo == hi) return 'e';
  return l && u ? 'b' : (l ? 'l' : (u ? 'u' : 'f'));
}

// One stored value of a matrix under construction: (row, col) and where its value comes from.
struct Entry {
  Index row, col, src;
};

// Compressed rows×cols matrix with the entries `e` (no duplicates), rows sorted within each
// column (the pattern Eigen's setFromTriplets gives); src[slot] = e.src of that value.
void compress(Index rows, Index cols, const std::vector<Entry>& e, SparseMatrix& M, std::vector<Index>& src) {
  M.resize(rows, cols);
  M.resizeNonZeros(static_cast<Index>(e.size()));
  Index* outer = M.outerIndexPtr();
  std::fill(outer, outer + cols + 1, 0);
  for (const Entry& x : e) ++outer[x.col + 1];
  for (Index j = 0; j < cols; ++j) outer[j + 1] += outer[j];
  std::vector<Index> next(outer, outer + cols);
  src.assign(e.size(), -1);
  // Stable in the order of e: callers list entries by increasing row within a column.
  for (const Entry& x : e) {
    const Index s = next[x.col]++;
    M.innerIndexPtr()[s] = x.row;
    src[s] = x.src;
  }
  std::fill(M.valuePtr(), M.valuePtr() + M.nonZeros(), 0.0);
}

// Entries of a compressed matrix by rows: for row i, (col, slot) pairs start[i] … start[i+1],
// columns increasing.
struct RowIndex {
  std::vector<Index> start, col, slot;
};

RowIndex row_index(const SparseMatrix& M) {
  RowIndex r;
  r.start.assign(M.rows() + 1, 0);
  const Index nnz = M.nonZeros();
  for (Index k = 0; k < nnz; ++k) ++r.start[M.innerIndexPtr()[k] + 1];
  for (Index i = 0; i < M.rows(); ++i) r.start[i + 1] += r.start[i];
  r.col.resize(nnz);
  r.slot.resize(nnz);
  std::vector<Index> next(r.start.begin(), r.start.end() - 1);
  for (Index j = 0; j < M.cols(); ++j)
    for (Index k = M.outerIndexPtr()[j]; k < M.outerIndexPtr()[j + 1]; ++k) {
      const Index i = M.innerIndexPtr()[k];
      r.col[next[i]] = j;
      r.slot[next[i]++] = k;
    }
  return r;
}

// The transpose's pattern of a compressed matrix, with src = slot in M.
void transpose_pattern(const SparseMatrix& M, SparseMatrix& T, std::vector<Index>& src) {
  std::vector<Entry> e;
  e.reserve(M.nonZeros());
  for (Index j = 0; j < M.cols(); ++j)
    for (Index k = M.outerIndexPtr()[j]; k < M.outerIndexPtr()[j + 1]; ++k) e.push_back({j, M.innerIndexPtr()[k], k});
  compress(M.cols(), M.rows(), e, T, src);
}

void scale_rows_cols(SparseMatrix& M, const Vector& row, const Vector& col) {
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(M, j); it; ++it) it.valueRef() *= row(it.row()) * col(j);
}

// One pass of Ruiz: ∞-norms of the columns of [P; E; G] (P symmetric) and of the rows
// of E and G, then scale by their inverse square roots.
void ruiz_pass(StandardForm& f) {
  Vector &cn = f.ruiz_col, &en = f.ruiz_e, &gn = f.ruiz_g;
  cn.setZero();
  en.setZero();
  gn.setZero();
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
  const auto inv_sqrt = [](double v) { return 1.0 / std::sqrt(clamp_norm(v)); };
  cn = cn.unaryExpr(inv_sqrt);
  en = en.unaryExpr(inv_sqrt);
  gn = gn.unaryExpr(inv_sqrt);
  scale_rows_cols(f.P, cn, cn);
  scale_rows_cols(f.E, en, cn);
  scale_rows_cols(f.G, gn, cn);
  f.Dx.array() *= cn.array();
  f.Ee.array() *= en.array();
  f.Eg.array() *= gn.array();
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
    const char c = classify(p.l(i), p.u(i));
    if (c == 'e') {
      f.g_eq_row[i] = static_cast<Index>(f.eq_source.size());
      f.eq_source.push_back(EqSource::g_row);
      f.eq_index.push_back(i);
    } else if (c != 'f') {
      f.g_index.push_back(i);
    }
    f.signature.push_back(c);
  }
  for (Index j = 0; j < f.n; ++j) {
    const char c = classify(p.xl(j), p.xu(j));
    if (c == 'e') {
      f.fixed_eq_row[j] = static_cast<Index>(f.eq_source.size());
      f.eq_source.push_back(EqSource::fixed_variable);
      f.eq_index.push_back(j);
    }
    f.signature.push_back(c);
  }
  f.me = static_cast<Index>(f.eq_source.size());
  f.mg = static_cast<Index>(f.g_index.size());

  // Patterns and value maps. E's rows are picked from A and G by rows.
  const RowIndex ar = row_index(p.A), gr = row_index(p.G);
  std::vector<Entry> te, tg;
  std::vector<char> from_g;
  te.reserve(p.A.nonZeros() + p.G.nonZeros() + f.n);
  tg.reserve(p.G.nonZeros());
  for (Index k = 0; k < f.me; ++k) {
    const Index src = f.eq_index[k];
    switch (f.eq_source[k]) {
      case EqSource::a_row:
        for (Index t = ar.start[src]; t < ar.start[src + 1]; ++t) te.push_back({k, ar.col[t], ar.slot[t]});
        break;
      case EqSource::g_row:
        // Marked by an offset past A's slots, split into e_src/e_from_g below.
        for (Index t = gr.start[src]; t < gr.start[src + 1]; ++t)
          te.push_back({k, gr.col[t], static_cast<Index>(p.A.nonZeros()) + gr.slot[t]});
        break;
      case EqSource::fixed_variable: te.push_back({k, src, -1}); break;
    }
  }
  for (Index k = 0; k < f.mg; ++k) {
    const Index src = f.g_index[k];
    for (Index t = gr.start[src]; t < gr.start[src + 1]; ++t) tg.push_back({k, gr.col[t], gr.slot[t]});
  }
  compress(f.me, f.n, te, f.E, f.e_src);
  f.e_from_g.assign(f.e_src.size(), 0);
  for (std::size_t s = 0; s < f.e_src.size(); ++s)
    if (f.e_src[s] >= p.A.nonZeros()) {
      f.e_src[s] -= p.A.nonZeros();
      f.e_from_g[s] = 1;
    }
  compress(f.mg, f.n, tg, f.G, f.g_src);
  transpose_pattern(f.E, f.Et, f.et_src);
  transpose_pattern(f.G, f.Gt, f.gt_src);
  f.P = p.P;

  // Values (sized here once; refresh_standard_form does not resize).
  f.q.resize(f.n);
  f.be.resize(f.me);
  f.gl.resize(f.mg);
  f.gu.resize(f.mg);
  f.xl.resize(f.n);
  f.xu.resize(f.n);
  f.Dx.resize(f.n);
  f.Ee.resize(f.me);
  f.Eg.resize(f.mg);
  f.ruiz_col.resize(f.n);
  f.ruiz_e.resize(f.me);
  f.ruiz_g.resize(f.mg);
  refresh_standard_form(f, p, ruiz_iterations);
  return f;
}

bool same_signature(const StandardForm& f, const QpProblem& p) {
  const Index mi = p.num_inequalities(), n = p.num_variables();
  if (static_cast<Index>(f.signature.size()) != mi + n) return false;
  for (Index i = 0; i < mi; ++i)
    if (classify(p.l(i), p.u(i)) != f.signature[i]) return false;
  for (Index j = 0; j < n; ++j)
    if (classify(p.xl(j), p.xu(j)) != f.signature[mi + j]) return false;
  return true;
}

void refresh_standard_form(StandardForm& f, const QpProblem& p, int ruiz_iterations) {
  // Unscaled values.
  std::copy(p.P.valuePtr(), p.P.valuePtr() + p.P.nonZeros(), f.P.valuePtr());
  const double* av = p.A.valuePtr();
  const double* gv = p.G.valuePtr();
  double* ev = f.E.valuePtr();
  for (std::size_t s = 0; s < f.e_src.size(); ++s)
    ev[s] = f.e_src[s] < 0 ? 1.0 : (f.e_from_g[s] ? gv[f.e_src[s]] : av[f.e_src[s]]);
  double* gtv = f.G.valuePtr();
  for (std::size_t s = 0; s < f.g_src.size(); ++s) gtv[s] = gv[f.g_src[s]];
  for (Index k = 0; k < f.me; ++k) {
    const Index src = f.eq_index[k];
    switch (f.eq_source[k]) {
      case EqSource::a_row: f.be(k) = p.b(src); break;
      case EqSource::g_row: f.be(k) = p.u(src); break;
      case EqSource::fixed_variable: f.be(k) = p.xl(src); break;
    }
  }
  for (Index k = 0; k < f.mg; ++k) {
    f.gl(k) = p.l(f.g_index[k]);
    f.gu(k) = p.u(f.g_index[k]);
  }
  f.q = p.q;
  f.xl = p.xl;
  f.xu = p.xu;
  for (Index j = 0; j < f.n; ++j)
    if (f.fixed_eq_row[j] >= 0) {
      f.xl(j) = -kInf;
      f.xu(j) = kInf;
    }

  // Equilibrate.
  f.Dx.setOnes();
  f.Ee.setOnes();
  f.Eg.setOnes();
  f.c = 1.0;
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
  const double* es = f.E.valuePtr();
  double* etv = f.Et.valuePtr();
  for (std::size_t s = 0; s < f.et_src.size(); ++s) etv[s] = es[f.et_src[s]];
  const double* gs = f.G.valuePtr();
  double* gtt = f.Gt.valuePtr();
  for (std::size_t s = 0; s < f.gt_src.size(); ++s) gtt[s] = gs[f.gt_src[s]];
}

}  // namespace lcprelax::detail
