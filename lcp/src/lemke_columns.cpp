// The columns of Lemke's tableau and of the lifted basis matrix (lemke_basis.hpp).
#include "lemke_basis.hpp"

namespace lcprelax::detail {

void LemkeColumns::dense(Index var, Eigen::Ref<Vector> out) const {
  if (var < n) {
    out.setZero();
    out(var) = 1.0;
  } else if (var < 2 * n) {
    out.setZero();
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it) out(it.row()) = -it.value();
  } else {
    out = -*d;
  }
}

void LemkeColumns::add_to(Index var, double alpha, Vector& y) const {
  if (alpha == 0.0) return;
  if (var < n) {
    y(var) += alpha;
  } else if (var < 2 * n) {
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it) y(it.row()) -= alpha * it.value();
  } else {
    y -= alpha * *d;
  }
}

Index LemkeColumns::write_column(Index var, int* rows, double* values) const {
  Index c = 0;
  if (var < n) {
    rows[0] = static_cast<int>(var);
    values[0] = 1.0;
    c = 1;
  } else if (var < 2 * n) {
    for (SparseMatrix::InnerIterator it(*M, var - n); it; ++it)
      if (it.value() != 0.0) {
        rows[c] = static_cast<int>(it.row());
        values[c++] = -it.value();
      }
  } else {
    for (Index i = 0; i < n; ++i) {
      rows[i] = static_cast<int>(i);
      values[i] = -(*d)(i);
    }
    c = n;
  }
  return c;
}

// Column `pos` of K (lemke_basis.hpp): for a basic z_j, −(H + shift·I)'s column j over the
// top rows, then −Ĵ's row j over the rows n + k; other variables as in B.
Index LemkeColumns::write_lifted_column(Index var, int* rows, double* values) const {
  if (var < n || var >= 2 * n) return write_column(var, rows, values);
  const Index j = var - n;
  const double s = shift ? *shift : 0.0;
  Index c = 0;
  bool diag_done = s == 0.0;
  for (SparseMatrix::InnerIterator it(*H, j); it; ++it) {
    if (!diag_done && it.row() > j) {
      rows[c] = static_cast<int>(j);
      values[c++] = -s;
      diag_done = true;
    }
    double v = it.value();
    if (it.row() == j && !diag_done) {
      v += s;
      diag_done = true;
    }
    if (v != 0.0) {
      rows[c] = static_cast<int>(it.row());
      values[c++] = -v;
    }
  }
  if (!diag_done) {
    rows[c] = static_cast<int>(j);
    values[c++] = -s;
  }
  for (SparseMatrix::InnerIterator it(*JT, j); it; ++it)
    if (it.value() != 0.0) {
      rows[c] = static_cast<int>(n + it.row());
      values[c++] = -it.value();
    }
  return c;
}

// Column n + k of K: −Ĵ's column k over the top rows, the mass 1/d_k at row n + k.
Index LemkeColumns::write_dof_column(Index k, int* rows, double* values) const {
  Index c = 0;
  for (SparseMatrix::InnerIterator it(*J, k); it; ++it)
    if (it.value() != 0.0) {
      rows[c] = static_cast<int>(it.row());
      values[c++] = -it.value();
    }
  rows[c] = static_cast<int>(n + k);
  values[c++] = 1.0 / (*dof_inverse_mass)(k);
  return c;
}

}  // namespace lcprelax::detail
