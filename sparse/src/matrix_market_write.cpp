// Matrix Market writer: "coordinate real general" for sparse matrices and "array real
// general" for vectors, with 17 significant digits so that reading back is exact.
// Non-finite values are refused (the reader would reject the file).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/sparse/matrix_market.hpp>

#include <cmath>
#include <fstream>
#include <string>

namespace lcprelax::sparse {
namespace {

std::ofstream open_for_writing(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw InputError(path + ": cannot open file for writing");
  out.precision(17);
  return out;
}

void finish(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw InputError(path + ": write failed");
}

}  // namespace

void write_matrix_market(const std::string& path, const SparseMatrix& A) {
  for (Index j = 0; j < A.outerSize(); ++j) {  // validate before creating the file
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      if (!std::isfinite(it.value())) {
        throw InputError(path + ": cannot write non-finite value at (" +
                         std::to_string(it.row()) + ", " + std::to_string(it.col()) + ")");
      }
    }
  }
  std::ofstream out = open_for_writing(path);
  out << "%%MatrixMarket matrix coordinate real general\n"
      << "% written by lcprelax\n"
      << A.rows() << ' ' << A.cols() << ' ' << A.nonZeros() << '\n';
  for (Index j = 0; j < A.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      out << it.row() + 1 << ' ' << it.col() + 1 << ' ' << it.value() << '\n';
    }
  }
  finish(out, path);
}

void write_matrix_market(const std::string& path, const Vector& v) {
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw InputError(path + ": cannot write non-finite value at row " + std::to_string(i));
    }
  }
  std::ofstream out = open_for_writing(path);
  out << "%%MatrixMarket matrix array real general\n"
      << "% written by lcprelax\n"
      << v.size() << " 1\n";
  for (Eigen::Index i = 0; i < v.size(); ++i) out << v[i] << '\n';
  finish(out, path);
}

}  // namespace lcprelax::sparse
