// Siconos fc2d writer (siconos_writer.hpp).
#include <lcprelax/io/siconos_writer.hpp>
#include <lcprelax/core/atomic_file.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <ostream>

namespace lcprelax::io {
namespace {

std::string g17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

void write_siconos_fc2d(std::ostream& out, const SparseMatrix& W_in, const Vector& q, const Vector& mu) {
  const Index nc = static_cast<Index>(mu.size());
  if (W_in.rows() != 2 * nc || W_in.cols() != 2 * nc || q.size() != 2 * nc)
    throw InputError("fc2d writer: W must be 2nc×2nc and q of size 2nc for nc = μ's size");
  if (!q.allFinite() || !mu.allFinite() || (nc > 0 && mu.minCoeff() < 0))
    throw InputError("fc2d writer: q and μ must be finite, μ ≥ 0");
  SparseMatrix W = W_in;
  W.makeCompressed();
  double norm1 = 0.0;
  for (Index j = 0; j < W.cols(); ++j) {
    double col = 0.0;
    for (SparseMatrix::InnerIterator it(W, j); it; ++it) {
      if (!std::isfinite(it.value())) throw InputError("fc2d writer: W has a NaN or infinite entry");
      col += std::abs(it.value());
    }
    norm1 = std::max(norm1, col);
  }
  out << "2\n" << nc << "\n2\n" << 2 * nc << "\n" << 2 * nc << "\n2\n";
  out << "CSparse Version 3.1.9 layout (written by lcprelax)\n";
  out << 2 * nc << "-by-" << 2 * nc << ", nzmax: " << W.nonZeros() << " nnz: " << W.nonZeros()
      << ", 1-norm: " << g17(norm1) << "\n";
  for (Index j = 0; j < W.cols(); ++j) {
    const Index a = W.outerIndexPtr()[j], b = W.outerIndexPtr()[j + 1];
    out << "    col " << j << " : locations " << a << " to " << b - 1 << "\n";
    for (Index k = a; k < b; ++k) out << "      " << W.innerIndexPtr()[k] << " : " << g17(W.valuePtr()[k]) << "\n";
  }
  for (Index i = 0; i < q.size(); ++i) out << g17(q(i)) << (i + 1 < q.size() ? " " : "\n");
  for (Index i = 0; i < nc; ++i) out << g17(mu(i)) << (i + 1 < nc ? " " : "\n");
  if (!out) throw InputError("fc2d writer: write failed");
}

// Written whole to memory first, then atomically (core/atomic_file.hpp): a killed run
// never leaves a truncated problem file under `path`.
void write_siconos_fc2d(const std::string& path, const SparseMatrix& W, const Vector& q, const Vector& mu) {
  std::ostringstream out;
  write_siconos_fc2d(out, W, q, mu);
  write_file_atomically(path, out.str());
}

}  // namespace lcprelax::io
