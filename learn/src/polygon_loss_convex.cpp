// The convex two-phase loss of a polygon sample: convex_step_loss (step_loss_convex.hpp) on
// the sample's one-body island in the dual formulation, ∂ℓ/∂θ by the cotangent's pullback
// through the assembly's tangents (polygon_solvers.hpp, polygon_losses.hpp).
#include "polygon_solvers.hpp"

#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/learn/step_loss_convex.hpp>

namespace lcprelax::learn {

SampleResult polygon_convex_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                                 const PolygonLossSettings& settings, PolygonWarmStart& /*warm: no warm start*/,
                                 PolygonLossTimes& times, PolygonSolvers* /*solvers: unused*/) {
  SampleResult r;
  const ContactSystem s = detail::polygon_system(a.value);
  ConvexStepLossSettings cs;
  cs.qp = settings.qp;
  cs.rho = settings.convex_rho;
  cs.deviation = settings.convex_deviation;
  cs.phase1_deviation = true;  // the polygon's (and the seeds') formulation
  cs.formulation = ConvexFormulation::dual;  // W of 2 to 8 rows: the dense dual QPs
  cs.phase1_regularization = 0.0;            // the library's convex model exactly
  ConvexStepLossTimes t;
  const StepLossResult res = convex_step_loss(s, Vector(target), dt, cs, &t);
  times.assembly += t.assembly;
  times.solve += t.solve;
  times.backward += t.backward;
  if (res.status == ContactStatus::failed) {
    r.ok = false;
    r.message = res.message;  // names the phase ("convex phase 1: ...")
    r.gradient = Vector::Zero(static_cast<Index>(a.tangent.size()));
    return r;
  }
  r.loss = res.loss;
  r.gradient = detail::pull_back_to_theta(res.grad, a);
  ++times.samples;
  return r;
}

}  // namespace lcprelax::learn
