// QpProblem: construction, validation and small helpers (see qp_problem.hpp).
#include <lcprelax/kkt/qp_problem.hpp>
#include <lcprelax/core/errors.hpp>

#include <cmath>
#include <limits>
#include <sstream>

namespace lcprelax {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool all_finite(const SparseMatrix& M) {
  for (Index k = 0; k < M.nonZeros(); ++k)
    if (!std::isfinite(M.valuePtr()[k])) return false;
  return true;
}

std::string first_nonfinite(const char* name, const Vector& v) {
  for (Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v(i))) {
      std::ostringstream os;
      os << name << "(" << i << ") is " << v(i) << " (must be finite)";
      return os.str();
    }
  return {};
}

std::string size_error(const char* name, Index got_rows, Index got_cols, Index rows, Index cols) {
  std::ostringstream os;
  os << name << " is " << got_rows << "x" << got_cols << ", expected " << rows << "x" << cols;
  return os.str();
}

std::string bound_error(const char* lname, const char* uname, const Vector& lo, const Vector& hi) {
  for (Index i = 0; i < lo.size(); ++i) {
    const bool bad_lo = std::isnan(lo(i)) || lo(i) == kInf, bad_hi = std::isnan(hi(i)) || hi(i) == -kInf;
    if (!bad_lo && !bad_hi && !(lo(i) > hi(i))) continue;  // the common case builds no stream
    std::ostringstream os;
    if (bad_lo) os << lname << "(" << i << ") is " << lo(i);
    else if (bad_hi) os << uname << "(" << i << ") is " << hi(i);
    else os << lname << "(" << i << ") = " << lo(i) << " > " << uname << "(" << i << ") = " << hi(i);
    return os.str();
  }
  return {};
}

bool same_structure(const SparseMatrix& a, const SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  if (!a.isCompressed() || !b.isCompressed()) {
    SparseMatrix ca = a, cb = b;
    ca.makeCompressed();
    cb.makeCompressed();
    return same_structure(ca, cb);
  }
  for (Index j = 0; j <= a.cols(); ++j)
    if (a.outerIndexPtr()[j] != b.outerIndexPtr()[j]) return false;
  for (Index k = 0; k < a.nonZeros(); ++k)
    if (a.innerIndexPtr()[k] != b.innerIndexPtr()[k]) return false;
  return true;
}

}  // namespace

QpProblem::QpProblem(Index n)
    : P(n, n), q(Vector::Zero(n)), A(0, n), b(0), G(0, n), l(0), u(0),
      xl(Vector::Constant(n, -kInf)), xu(Vector::Constant(n, kInf)) {}

std::string QpProblem::validation_error() const {
  const Index n = num_variables();
  if (P.rows() != n || P.cols() != n) return size_error("P", P.rows(), P.cols(), n, n);
  if (A.cols() != n) return size_error("A", A.rows(), A.cols(), A.rows(), n);
  if (b.size() != A.rows()) return size_error("b", b.size(), 1, A.rows(), 1);
  if (G.cols() != n) return size_error("G", G.rows(), G.cols(), G.rows(), n);
  if (l.size() != G.rows()) return size_error("l", l.size(), 1, G.rows(), 1);
  if (u.size() != G.rows()) return size_error("u", u.size(), 1, G.rows(), 1);
  if (xl.size() != n) return size_error("xl", xl.size(), 1, n, 1);
  if (xu.size() != n) return size_error("xu", xu.size(), 1, n, 1);
  if (!all_finite(P)) return "P has a NaN or infinite entry";
  if (!all_finite(A)) return "A has a NaN or infinite entry";
  if (!all_finite(G)) return "G has a NaN or infinite entry";
  for (Index j = 0; j < P.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(P, j); it; ++it)
      if (it.row() > j) {
        std::ostringstream os;
        os << "P has an entry below the diagonal at (" << it.row() << ", " << j
           << "); give the upper triangle only";
        return os.str();
      } else if (it.row() == j && it.value() < 0) {
        std::ostringstream os;
        os << "P(" << j << ", " << j << ") = " << it.value() << " < 0: P is not positive semidefinite";
        return os.str();
      }
  if (auto e = first_nonfinite("q", q); !e.empty()) return e;
  if (!std::isfinite(r)) return "r is not finite";
  if (auto e = first_nonfinite("b", b); !e.empty()) return e;
  if (auto e = bound_error("l", "u", l, u); !e.empty()) return e;
  if (auto e = bound_error("xl", "xu", xl, xu); !e.empty()) return e;
  return {};
}

void QpProblem::validate() const {
  const std::string e = validation_error();
  if (!e.empty()) throw InputError("invalid QP: " + e);
}

bool QpProblem::same_pattern(const QpProblem& other) const {
  return num_variables() == other.num_variables() && b.size() == other.b.size() &&
         l.size() == other.l.size() && same_structure(P, other.P) && same_structure(A, other.A) &&
         same_structure(G, other.G);
}

double QpProblem::objective(const Vector& x) const {
  const Vector Px = P.selfadjointView<Eigen::Upper>() * x;
  return 0.5 * x.dot(Px) + q.dot(x) + r;
}

}  // namespace lcprelax
