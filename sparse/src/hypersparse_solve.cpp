// Hypersparse transposed solves with KLU's factors: the reach of the right-hand side in the
// graph of U, L and F, then the numeric solve in its topological order
// (hypersparse_solve.hpp).
#include <lcprelax/sparse/hypersparse_solve.hpp>

namespace lcprelax::sparse {

void HypersparseTransposedSolver::transpose_strict(const std::vector<int>& p, const std::vector<int>& i,
                                                   const std::vector<double>& x, RowWise& out,
                                                   std::vector<double>* diag) {
  const int n = n_;
  out.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int j = 0; j < n; ++j)
    for (int k = p[j]; k < p[j + 1]; ++k)
      if (i[k] != j && x[k] != 0.0) ++out.start[static_cast<std::size_t>(i[k]) + 1];
  for (int r = 0; r < n; ++r) out.start[r + 1] += out.start[r];
  out.col.resize(static_cast<std::size_t>(out.start[n]));
  out.val.resize(static_cast<std::size_t>(out.start[n]));
  next_.assign(out.start.begin(), out.start.end() - 1);
  for (int j = 0; j < n; ++j)
    for (int k = p[j]; k < p[j + 1]; ++k) {
      if (i[k] == j) {
        if (diag) (*diag)[static_cast<std::size_t>(j)] = x[k];
        continue;
      }
      if (x[k] == 0.0) continue;
      const int at = next_[static_cast<std::size_t>(i[k])]++;
      out.col[static_cast<std::size_t>(at)] = j;
      out.val[static_cast<std::size_t>(at)] = x[k];
    }
}

void HypersparseTransposedSolver::reserve(const KluLu& klu) {
  Index lnz = 0, unz = 0, fnz = 0;
  klu.factor_counts(lnz, unz, fnz);
  const std::size_t n = static_cast<std::size_t>(klu.rows()), two_n = 2 * n;
  KluLu::Factors& f = factors_;
  for (auto* v : {&f.Lp, &f.Up, &f.Fp, &f.R, &U_.start, &L_.start, &F_.start, &next_}) v->reserve(n + 1);
  for (auto* v : {&f.P, &f.Q, &p_, &qinv_}) v->reserve(n);
  for (auto* v : {&f.Rs, &udiag_, &rs_}) v->reserve(n);
  f.Li.reserve(static_cast<std::size_t>(lnz));
  f.Lx.reserve(static_cast<std::size_t>(lnz));
  f.Ui.reserve(static_cast<std::size_t>(unz));
  f.Ux.reserve(static_cast<std::size_t>(unz));
  f.Fi.reserve(static_cast<std::size_t>(fnz));
  f.Fx.reserve(static_cast<std::size_t>(fnz));
  L_.col.reserve(static_cast<std::size_t>(lnz));
  L_.val.reserve(static_cast<std::size_t>(lnz));
  U_.col.reserve(static_cast<std::size_t>(unz));
  U_.val.reserve(static_cast<std::size_t>(unz));
  F_.col.reserve(static_cast<std::size_t>(fnz));
  F_.val.reserve(static_cast<std::size_t>(fnz));
  work_.reserve(two_n);
}

bool HypersparseTransposedSolver::build(const KluLu& klu) {
  built_ = false;
  if (!klu.extract(factors_)) return false;
  const KluLu::Factors& f = factors_;
  const int n = static_cast<int>(f.n);
  n_ = n;
  udiag_.assign(static_cast<std::size_t>(n), 0.0);
  transpose_strict(f.Up, f.Ui, f.Ux, U_, &udiag_);
  transpose_strict(f.Lp, f.Li, f.Lx, L_, nullptr);  // unit diagonal
  transpose_strict(f.Fp, f.Fi, f.Fx, F_, nullptr);  // no diagonal entries
  p_.assign(f.P.begin(), f.P.begin() + n);
  rs_.assign(f.Rs.begin(), f.Rs.begin() + n);
  qinv_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) qinv_[static_cast<std::size_t>(f.Q[static_cast<std::size_t>(k)])] = k;
  work_.reset(2 * static_cast<std::size_t>(n));
  built_ = true;
  return true;
}

// Edges of the reach graph: node j < n is v_j, with edges to the v nodes of row j of U
// and then to u_j (edge number nnz(U row j)); node n + p is u_p, with edges to the u nodes
// of row p of L and then to the v nodes of row p of F.
int HypersparseTransposedSolver::next_child(int j, int& e) const {
  if (j < n_) {
    const int b = U_.start[static_cast<std::size_t>(j)], nu = U_.start[static_cast<std::size_t>(j) + 1] - b;
    if (e < nu) return U_.col[static_cast<std::size_t>(b + e++)];
    if (e == nu) {
      ++e;
      return n_ + j;
    }
    return -1;
  }
  const std::size_t p = static_cast<std::size_t>(j - n_);
  const int lb = L_.start[p], nl = L_.start[p + 1] - lb, fb = F_.start[p], nf = F_.start[p + 1] - fb;
  if (e >= nl + nf) return -1;
  const int k = e++;
  return k < nl ? n_ + L_.col[static_cast<std::size_t>(lb + k)] : F_.col[static_cast<std::size_t>(fb + k - nl)];
}

void HypersparseTransposedSolver::solve(int nb, const int* b_index, const double* b_value, std::vector<int>& y_index,
                                        std::vector<double>& y_value) {
  y_index.clear();
  y_value.clear();
  const int end = 2 * n_;
  int top = end;
  for (int k = 0; k < nb; ++k) {
    const int l = qinv_[static_cast<std::size_t>(b_index[k])];
    if (!work_.mark[static_cast<std::size_t>(l)]) top = work_.dfs(l, top, [this](int j, int& e) { return next_child(j, e); });
  }
  std::vector<double>& x = work_.x;
  for (int k = 0; k < nb; ++k) x[static_cast<std::size_t>(qinv_[static_cast<std::size_t>(b_index[k])])] += b_value[k];
  for (int t = top; t < end; ++t) {
    const int j = work_.reach[static_cast<std::size_t>(t)];
    if (j < n_) {  // v_j: Uᵀv = b̃ − Fᵀu, column j of U scattered along row j
      const std::size_t p = static_cast<std::size_t>(j);
      const double v = (x[p] /= udiag_[p]);
      if (v == 0.0) continue;
      for (int k = U_.start[p]; k < U_.start[p + 1]; ++k)
        x[static_cast<std::size_t>(U_.col[static_cast<std::size_t>(k)])] -= U_.val[static_cast<std::size_t>(k)] * v;
      x[p + static_cast<std::size_t>(n_)] += v;
    } else {  // u_p: Lᵀu = v, then the Fᵀu terms of later blocks
      const std::size_t p = static_cast<std::size_t>(j - n_);
      const double u = x[static_cast<std::size_t>(j)];
      const int row = p_[p];
      y_index.push_back(row);
      y_value.push_back(u / rs_[p]);
      if (u == 0.0) continue;
      for (int k = L_.start[p]; k < L_.start[p + 1]; ++k)
        x[static_cast<std::size_t>(n_ + L_.col[static_cast<std::size_t>(k)])] -= L_.val[static_cast<std::size_t>(k)] * u;
      for (int k = F_.start[p]; k < F_.start[p + 1]; ++k)
        x[static_cast<std::size_t>(F_.col[static_cast<std::size_t>(k)])] -= F_.val[static_cast<std::size_t>(k)] * u;
    }
  }
  work_.clear(top, end);
  last_reach_ = end - top;
}

}  // namespace lcprelax::sparse
