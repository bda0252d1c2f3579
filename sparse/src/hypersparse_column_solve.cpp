// Hypersparse solves with KLU's factors: the reach of the right-hand side in the graph of
// L, U and F, then the numeric (scatter) solve in its topological order
// (hypersparse_column_solve.hpp).
#include <lcprelax/sparse/hypersparse_column_solve.hpp>

namespace lcprelax::sparse {

void HypersparseColumnSolver::reserve(const KluLu& klu) {
  Index lnz = 0, unz = 0, fnz = 0;
  klu.factor_counts(lnz, unz, fnz);
  const std::size_t n = static_cast<std::size_t>(klu.rows()), two_n = 2 * n;
  for (auto* v : {&f_.Lp, &f_.Up, &f_.Fp}) v->reserve(n + 1);
  for (auto* v : {&f_.P, &f_.Q, &pinv_}) v->reserve(n);
  f_.R.reserve(n + 1);
  for (auto* v : {&f_.Rs, &udiag_, &dense_}) v->reserve(n);
  f_.Li.reserve(static_cast<std::size_t>(lnz));
  f_.Lx.reserve(static_cast<std::size_t>(lnz));
  f_.Ui.reserve(static_cast<std::size_t>(unz));
  f_.Ux.reserve(static_cast<std::size_t>(unz));
  f_.Fi.reserve(static_cast<std::size_t>(fnz));
  f_.Fx.reserve(static_cast<std::size_t>(fnz));
  work_.reserve(two_n);
}

bool HypersparseColumnSolver::build(const KluLu& klu) {
  built_ = false;
  if (!klu.extract(f_)) return false;
  const int n = static_cast<int>(f_.n);
  n_ = n;
  udiag_.assign(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j)
    for (int k = f_.Up[static_cast<std::size_t>(j)]; k < f_.Up[static_cast<std::size_t>(j) + 1]; ++k)
      if (f_.Ui[static_cast<std::size_t>(k)] == j) udiag_[static_cast<std::size_t>(j)] = f_.Ux[static_cast<std::size_t>(k)];
  pinv_.resize(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) pinv_[static_cast<std::size_t>(f_.P[static_cast<std::size_t>(k)])] = k;
  work_.reset(2 * static_cast<std::size_t>(n));
  dense_.assign(static_cast<std::size_t>(n), 0.0);
  built_ = true;
  return true;
}

// Edges of the reach graph: node p < n is v_p, with edges to the v nodes of column p of L
// (below the diagonal) and then to u_p (edge number nnz(L column p)); node n + p is u_p,
// with edges to the u nodes of column p of U (above the diagonal) and then to the v nodes
// of column p of F.
int HypersparseColumnSolver::next_child(int j, int& e) const {
  if (j < n_) {
    const std::size_t p = static_cast<std::size_t>(j);
    const int b = f_.Lp[p], nl = f_.Lp[p + 1] - b;
    while (e < nl) {
      const std::size_t at = static_cast<std::size_t>(b + e++);
      if (f_.Li[at] != j && f_.Lx[at] != 0.0) return f_.Li[at];
    }
    if (e == nl) {
      ++e;
      return n_ + j;
    }
    return -1;
  }
  const std::size_t p = static_cast<std::size_t>(j - n_);
  const int ub = f_.Up[p], nu = f_.Up[p + 1] - ub, fb = f_.Fp[p], nf = f_.Fp[p + 1] - fb;
  while (e < nu + nf) {
    const int k = e++;
    if (k < nu) {
      const std::size_t at = static_cast<std::size_t>(ub + k);
      if (f_.Ui[at] != static_cast<int>(p) && f_.Ux[at] != 0.0) return n_ + f_.Ui[at];
    } else {
      const std::size_t at = static_cast<std::size_t>(fb + k - nu);
      if (f_.Fx[at] != 0.0) return f_.Fi[at];
    }
  }
  return -1;
}

void HypersparseColumnSolver::solve(int nb, const int* b_index, const double* b_value, std::vector<int>& x_index,
                                    std::vector<double>& x_value) {
  x_index.clear();
  x_value.clear();
  const int end = 2 * n_;
  int top = end;
  for (int k = 0; k < nb; ++k) {
    const int p = pinv_[static_cast<std::size_t>(b_index[k])];
    if (!work_.mark[static_cast<std::size_t>(p)]) top = work_.dfs(p, top, [this](int j, int& e) { return next_child(j, e); });
  }
  for (int k = 0; k < nb; ++k) {
    const std::size_t p = static_cast<std::size_t>(pinv_[static_cast<std::size_t>(b_index[k])]);
    work_.x[p] += b_value[k] / f_.Rs[p];
  }
  std::vector<double>& x = work_.x;
  for (int t = top; t < end; ++t) {
    const int j = work_.reach[static_cast<std::size_t>(t)];
    if (j < n_) {  // v_p final (L unit diagonal): scatter column p of L, then into u_p
      const std::size_t p = static_cast<std::size_t>(j);
      const double v = x[p];
      if (v == 0.0) continue;
      for (int k = f_.Lp[p]; k < f_.Lp[p + 1]; ++k) {
        const int r = f_.Li[static_cast<std::size_t>(k)];
        if (r != j) x[static_cast<std::size_t>(r)] -= f_.Lx[static_cast<std::size_t>(k)] * v;
      }
      x[p + static_cast<std::size_t>(n_)] += v;
    } else {  // u_p = (v_p − Σ U_pq u_q) / U_pp, then scatter columns p of U and F
      const std::size_t p = static_cast<std::size_t>(j - n_);
      const double u = (x[static_cast<std::size_t>(j)] /= udiag_[p]);
      x_index.push_back(f_.Q[p]);
      x_value.push_back(u);
      if (u == 0.0) continue;
      for (int k = f_.Up[p]; k < f_.Up[p + 1]; ++k) {
        const int r = f_.Ui[static_cast<std::size_t>(k)];
        if (r != static_cast<int>(p)) x[static_cast<std::size_t>(n_ + r)] -= f_.Ux[static_cast<std::size_t>(k)] * u;
      }
      for (int k = f_.Fp[p]; k < f_.Fp[p + 1]; ++k)
        x[static_cast<std::size_t>(f_.Fi[static_cast<std::size_t>(k)])] -= f_.Fx[static_cast<std::size_t>(k)] * u;
    }
  }
  work_.clear(top, end);
  last_reach_ = end - top;
}

// Block b holds positions R[b]..R[b + 1) − 1; its L and U columns stay inside the block,
// its F columns lead to earlier blocks, so the blocks run from the last one. Each block's
// F columns are applied after its U solve in increasing order, as klu_solve does: the same
// sums in the same order.
Index HypersparseColumnSolver::solve_dense(int nb, const int* b_index, const double* b_value, Eigen::Ref<Vector> x) {
  double* y = dense_.data();
  for (int k = 0; k < nb; ++k) {
    const std::size_t p = static_cast<std::size_t>(pinv_[static_cast<std::size_t>(b_index[k])]);
    y[p] += b_value[k] / f_.Rs[p];
  }
  const int* Lp = f_.Lp.data();
  const int* Li = f_.Li.data();
  const double* Lx = f_.Lx.data();
  const int* Up = f_.Up.data();
  const int* Ui = f_.Ui.data();
  const double* Ux = f_.Ux.data();
  const int* Fp = f_.Fp.data();
  const int* Fi = f_.Fi.data();
  const double* Fx = f_.Fx.data();
  for (std::size_t b = f_.R.size() - 1; b-- > 0;) {
    const int k1 = f_.R[b], k2 = f_.R[b + 1];
    if (k2 - k1 > 1)
      for (int p = k1; p < k2; ++p) {  // L v = y (unit diagonal, stored)
        const double v = y[p];
        if (v == 0.0) continue;
        for (int k = Lp[p]; k < Lp[p + 1]; ++k)
          if (Li[k] != p) y[Li[k]] -= Lx[k] * v;
      }
    for (int p = k2 - 1; p >= k1; --p) {  // U u = v
      const double u = (y[p] /= udiag_[static_cast<std::size_t>(p)]);
      if (u == 0.0 || k2 - k1 == 1) continue;
      for (int k = Up[p]; k < Up[p + 1]; ++k)
        if (Ui[k] != p) y[Ui[k]] -= Ux[k] * u;
    }
    for (int p = k1; p < k2; ++p) {  // F's columns into earlier blocks, in klu_solve's order
      const double u = y[p];
      if (u == 0.0) continue;
      for (int k = Fp[p]; k < Fp[p + 1]; ++k) y[Fi[k]] -= Fx[k] * u;
    }
  }
  Index nonzeros = 0;
  for (int k = 0; k < n_; ++k) {
    x(f_.Q[static_cast<std::size_t>(k)]) = y[k];
    nonzeros += y[k] != 0.0;
    y[k] = 0.0;
  }
  return nonzeros;
}

}  // namespace lcprelax::sparse
