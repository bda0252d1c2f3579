// The relaxed loss of a polygon sample: relaxed_lcp.hpp on the Stewart–Trinkle LCP with the
// prediction map v⁺ = P z + p, gradient by the envelope theorem chained through the LCP's
// tangents (polygon_losses.hpp).
#include "elapsed.hpp"

#include <lcprelax/learn/polygon_lcp.hpp>
#include <lcprelax/learn/polygon_losses.hpp>

#include <chrono>

namespace lcprelax::learn {
namespace {

using detail::since;

}  // namespace

SampleResult polygon_relaxed_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                                  const PolygonLossSettings& settings, RelaxedLcpSolver& solver,
                                  PolygonWarmStart& warm, PolygonLossTimes& times) {
  const Index np = static_cast<Index>(a.tangent.size());
  SampleResult r;
  r.gradient = Vector::Zero(np);
  auto t0 = std::chrono::steady_clock::now();
  PolygonLcp lcp, d;
  polygon_lcp(a.value, dt, lcp);
  const Index n = static_cast<Index>(lcp.q.size());
  const double a1 = settings.relaxed.a1;
  if (n == 0) {
    // No contact: the subproblem has no variables, c = a1‖v* − v̄‖².
    const Vector e = lcp.p - Vector(target);
    r.loss = a1 * e.squaredNorm();
    for (Index k = 0; k < np; ++k) r.gradient(k) = 2.0 * a1 * e.dot(a.tangent[static_cast<std::size_t>(k)].v_star);
    times.assembly += since(t0);
    ++times.samples;
    return r;
  }
  // Variables in velocity units: z = S z̃, S = diag(m (impulses λn, β±), 1 (γ)), rows
  // scaled by S too, so that z̃ ⊥ S(M S z̃ + q) is the same LCP and z̃ᵀS(MSz̃ + q) = zᵀ(Mz + q):
  // only the relaxed QP's regularization and shift (ε + δ)/2‖z̃‖² see the scaling, and in
  // these units they neither depend on the mass nor pull it towards zero.
  const double mass = 1.0 / a.value.minv(0);
  Vector S = Vector::Ones(n), Sdot = Vector::Zero(n);  // Sdot = dS/dm
  S.head(3 * (n / 4)).setConstant(mass);
  Sdot.head(3 * (n / 4)).setConstant(1.0);
  const DenseMatrix Ms = S.asDiagonal() * lcp.M * S.asDiagonal();
  const DenseMatrix Ps = lcp.P * S.asDiagonal();
  RelaxedLcpData data;
  data.M = full_pattern(Ms);
  data.q = S.cwiseProduct(lcp.q);
  data.P = full_pattern(Ps);
  data.p = lcp.p;
  data.target = Vector(target);
  times.assembly += since(t0);

  t0 = std::chrono::steady_clock::now();
  if (settings.warm_start && warm.relaxed_valid && warm.relaxed.lambda.size() == n) solver.warm_start(warm.relaxed);
  const RelaxedLcpResult& res = solver.solve(data, true);
  times.solve += res.assembly_seconds + res.solve_seconds;
  if (res.status != RelaxedLcpStatus::solved) {
    r.ok = false;
    r.message = std::string("relaxed: ") + to_string(res.status) + ": " + res.message;
    warm.relaxed_valid = false;
    return r;
  }
  r.loss = res.cost;
  t0 = std::chrono::steady_clock::now();
  const RelaxedLcpGradient& g = res.gradient;
  for (Index k = 0; k < np; ++k) {
    polygon_lcp_tangent(a.value, a.tangent[static_cast<std::size_t>(k)], dt, d);
    DenseMatrix dMs = S.asDiagonal() * d.M * S.asDiagonal();
    Vector dqs = S.cwiseProduct(d.q);
    DenseMatrix dPs = d.P * S.asDiagonal();
    if (k == PolygonLayout::kMass) {  // S depends on the mass
      dMs += Sdot.asDiagonal() * lcp.M * S.asDiagonal() + S.asDiagonal() * lcp.M * Sdot.asDiagonal();
      dqs += Sdot.cwiseProduct(lcp.q);
      dPs += lcp.P * Sdot.asDiagonal();
    }
    r.gradient(k) = pattern_inner(g.dM, dMs) + g.dq.dot(dqs) + pattern_inner(g.dP, dPs) + g.dp.dot(d.p);
  }
  times.backward += res.gradient_seconds + since(t0);
  if (settings.warm_start) {
    warm.relaxed = res;
    warm.relaxed_valid = true;
  }
  ++times.samples;
  return r;
}

}  // namespace lcprelax::learn
