// The hard loss of a polygon sample: hard_step_loss (step_loss_hard.hpp) on the sample's
// one-body island, ∂ℓ/∂θ by the cotangent's pullback through the assembly's tangents
// (polygon_solvers.hpp, polygon_losses.hpp).
#include "elapsed.hpp"
#include "polygon_solvers.hpp"

#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/learn/step_loss_hard.hpp>

#include <chrono>

namespace lcprelax::learn {

SampleResult polygon_hard_loss(const PolygonAssembly& a, const Vec3& target, double dt,
                               const PolygonLossSettings& settings, PolygonWarmStart& warm, PolygonLossTimes& times,
                               PolygonSolvers* /*solvers: unused, the step loss keeps none*/) {
  using detail::since;
  SampleResult r;
  auto t0 = std::chrono::steady_clock::now();
  const ContactSystem s = detail::polygon_system(a.value);
  times.assembly += since(t0);

  t0 = std::chrono::steady_clock::now();
  HardStepLossSettings hs;
  hs.lemke = settings.lemke;
  static const std::vector<bool> kNoBasis;
  std::vector<bool> basis;
  const StepLossResult res = hard_step_loss(s, Vector(target), dt, hs, settings.warm_start ? warm.lemke_basis : kNoBasis,
                                            settings.warm_start ? &basis : nullptr);
  times.solve += since(t0);  // Lemke and its backward
  if (res.status == ContactStatus::failed) {
    r.ok = false;
    r.message = "hard: " + res.message;
    r.gradient = Vector::Zero(static_cast<Index>(a.tangent.size()));
    return r;
  }
  if (settings.warm_start) warm.lemke_basis = std::move(basis);
  r.loss = res.loss;
  t0 = std::chrono::steady_clock::now();
  r.gradient = detail::pull_back_to_theta(res.grad, a);
  times.backward += since(t0);
  ++times.samples;
  return r;
}

}  // namespace lcprelax::learn
