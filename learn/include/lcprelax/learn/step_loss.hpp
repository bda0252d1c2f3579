#pragma once
// The loss of one island of one contact step, whatever the scene: the common result of
// the three methods (step_loss_hard.hpp, step_loss_relaxed.hpp, step_loss_convex.hpp).
//
// Data: the island's ContactSystem s (models/contact_system.hpp: Jn, Jt, φ, μ, M⁻¹, v* in the
// island's local dof order, 3 per body: vx, vy, ω) and the observed next velocity v̄ of the
// same dofs (m/s, m/s, rad/s). The simulator post-stabilizes positions, so the next
// velocity, not the next position, is what a contact solve predicts exactly.
// Output: the loss ℓ (its unit depends on the method: (m/s)² for hard and convex), the
// method's predicted v⁺, and ∂ℓ/∂(Jn, Jt, φ, μ, M⁻¹, v*) as a ContactSystemCotangent, which
// models/contact_system_gradient.hpp pulls back to the world's parameters. A failed solve is
// reported by `status` (loss and gradient are then not meaningful and must not be averaged in).
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>
#include <lcprelax/sparse/types.hpp>

#include <string>
#include <vector>

namespace lcprelax::learn {

/// The three losses of a contact step: `hard` (the exact LCP's prediction error, Lemke),
/// `relaxed` (the seeds' relaxed LCP, interior point) and `convex` (the two-phase convex
/// model with a deviation penalty, interior point).
enum class LossMethod { hard, relaxed, convex };
const char* to_string(LossMethod m);
/// "hard", "relaxed" or "convex"; throws InputError("--method: ...") otherwise.
LossMethod parse_loss_method(const std::string& s);

struct StepLossResult {
  ContactStatus status = ContactStatus::unsolved;
  std::string message;           ///< why, when status is not solved
  double loss = 0.0;
  Vector v_next;                 ///< the method's prediction v⁺ (3 per island body)
  ContactSystemCotangent grad;   ///< ∂ℓ/∂data
  long work = 0;                 ///< pivots or interior-point iterations
  /// Hard loss: the answer solved M + εI, not (M, q) (LcpModelSource::regularized; status
  /// solved_inaccurate); its final basis then warm-starts with warm_from_regularized.
  bool regularized = false;
};

/// The prediction of a step loss of least-squares form, ℓ = ‖v⁺ − v̄‖² (hard, convex), with
/// its Jacobian ∂v⁺/∂data one row per dof, for Gauss–Newton training (least_squares.hpp):
/// rows[k] = ∂v⁺_k/∂(Jn, Jt, φ, μ, M⁻¹, v*), each row the cotangent that the loss's gradient
/// would be for ℓ = v⁺_k. So ∂ℓ/∂data = Σ_k 2(v⁺_k − v̄_k)·rows[k].
struct StepJacobianResult {
  ContactStatus status = ContactStatus::unsolved;
  std::string message;                        ///< why, when status is not solved
  Vector v_next;                              ///< v⁺ (3 per island body)
  std::vector<ContactSystemCotangent> rows;   ///< one per dof of v⁺
  long work = 0;                              ///< pivots or interior-point iterations
};

}  // namespace lcprelax::learn
