// The hard loss of a polygon sample: Lemke on the Stewart–Trinkle LCP, gradient by
// LemkeSolver::backward chained through the LCP's tangents (polygon_losses.hpp).
#include "elapsed.hpp"
#include "polygon_solvers.hpp"

#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/lcp/lemke.hpp>

#include <chrono>
#include <memory>

namespace lcprelax::learn {
namespace {

using detail::since;

}  // namespace

SampleResult polygon_hard_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                               const PolygonLossSettings& settings, PolygonWarmStart& warm, PolygonLossTimes& times,
                               PolygonSolvers* solvers) {
  const Index np = static_cast<Index>(a.tangent.size());
  SampleResult r;
  r.gradient = Vector::Zero(np);
  auto t0 = std::chrono::steady_clock::now();
  PolygonLcp lcp, d;
  polygon_lcp(a.value, dt, lcp);
  const Index n = static_cast<Index>(lcp.q.size());
  Vector z = Vector::Zero(n);
  std::unique_ptr<LemkeSolver> local;
  if (!solvers) local = std::make_unique<LemkeSolver>(settings.lemke);
  LemkeSolver& solver = solvers ? solvers->lemke : *local;
  times.assembly += since(t0);
  t0 = std::chrono::steady_clock::now();
  if (n > 0) {
    solver.setup(full_pattern(lcp.M), lcp.q);
    if (settings.warm_start && static_cast<Index>(warm.lemke_basis.size()) == n) solver.warm_start(warm.lemke_basis);
    const LcpResult& res = solver.solve();
    if (!has_solution(res.info.status)) {
      r.ok = false;
      r.message = std::string("hard: Lemke ") + to_string(res.info.status) + ": " + res.info.message;
      times.solve += since(t0);
      return r;
    }
    z = res.z;
    if (settings.warm_start) warm.lemke_basis = res.z_basic;
  }
  const Vector v_next = lcp.P * z + lcp.p;
  const Vector g = 2.0 * (v_next - Vector(target));
  r.loss = (v_next - Vector(target)).squaredNorm();
  times.solve += since(t0);

  t0 = std::chrono::steady_clock::now();
  LcpGradient back;
  if (n > 0) back = solver.backward(lcp.P.transpose() * g);
  const DenseMatrix dl_dP = g * z.transpose();
  for (Index k = 0; k < np; ++k) {
    polygon_lcp_tangent(a.value, a.tangent[static_cast<std::size_t>(k)], dt, d);
    double s = g.dot(d.p);
    if (n > 0) s += pattern_inner(back.dM, d.M) + back.dq.dot(d.q) + (dl_dP.cwiseProduct(d.P)).sum();
    r.gradient(k) = s;
  }
  times.backward += since(t0);
  ++times.samples;
  return r;
}

}  // namespace lcprelax::learn
