// Siconos-compatible LCP and fc2d errors; the formulas and their sources are documented in
// lcprelax/io/siconos_errors.hpp.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <lcprelax/io/siconos_errors.hpp>
#include <lcprelax/core/errors.hpp>
#include <string>

namespace lcprelax::io {
namespace {

void check_size(long actual, long expected, const char* what) {
  if (actual != expected)
    throw InputError(std::string(what) + " has size " + std::to_string(actual) + ", expected " +
                     std::to_string(expected));
}

double sign(double x) { return x < 0.0 ? -1.0 : (x > 0.0 ? 1.0 : 0.0); }

}  // namespace

double lcp_error(const SparseMatrix& M, const Vector& q, const Vector& z) {
  check_size(M.cols(), M.rows(), "lcp_error: M (columns)");
  check_size(q.size(), M.rows(), "lcp_error: q");
  check_size(z.size(), M.rows(), "lcp_error: z");
  const Vector w = M * z + q;
  double sum = 0.0;
  for (Index i = 0; i < z.size(); ++i) {
    const double d = z[i] - std::max(0.0, z[i] - w[i]);
    sum += d * d;
  }
  double error = std::sqrt(sum);
  const double norm_q = q.norm();
  if (std::fabs(norm_q) > DBL_EPSILON) error /= norm_q;
  return error;
}

double fc2d_error(const Fc2dData& problem, const Vector& r, const Vector& u) {
  const long n = 2L * problem.contacts;
  check_size(problem.W.rows(), n, "fc2d_error: W (rows)");
  check_size(problem.W.cols(), n, "fc2d_error: W (columns)");
  check_size(problem.q.size(), n, "fc2d_error: q");
  check_size(problem.mu.size(), problem.contacts, "fc2d_error: mu");
  check_size(r.size(), n, "fc2d_error: r");
  check_size(u.size(), n, "fc2d_error: u");
  double sum = 0.0;
  for (Index c = 0; c < problem.contacts; ++c) {
    const double mu = problem.mu[c];
    const double rN = r[2 * c], rT = r[2 * c + 1];
    const double uN = u[2 * c], uT = u[2 * c + 1];
    double vN = rN - uN - mu * std::fabs(uT);  // modified velocity, rho = 1
    double vT = rT - uT;
    const double normT = std::fabs(vT);
    if (mu * normT <= -vN) {  // in the polar cone: projects to 0
      vN = 0.0;
      vT = 0.0;
    } else if (normT > mu * vN) {  // outside both cones: onto the boundary ray
      vN = (mu * normT + vN) / (mu * mu + 1.0);
      vT = mu * vN * sign(vT);
    }
    const double eN = rN - vN, eT = rT - vT;
    sum += eN * eN + eT * eT;
  }
  double error = std::sqrt(sum);
  const double scale = std::max(r.norm(), std::max(u.norm(), problem.q.norm()));
  if (std::fabs(scale) > DBL_EPSILON) error /= scale;
  return error;
}

double fc2d_error(const Fc2dData& problem, const Vector& r) {
  check_size(r.size(), problem.W.cols(), "fc2d_error: r");
  check_size(problem.q.size(), problem.W.rows(), "fc2d_error: q");
  const Vector u = problem.W * r + problem.q;
  return fc2d_error(problem, r, u);
}

}  // namespace lcprelax::io
