#pragma once
// Least-squares samples for Gauss–Newton training (OptimizerKind::lm, optimizer.hpp).
//
// An objective whose per-sample loss is a sum of squares, ℓᵢ(θ) = ‖rᵢ(θ)‖², can give the
// residual rᵢ and its Jacobian Jᵢ = ∂rᵢ/∂θ (Objective::evaluate_residuals, trainer.hpp). The
// Levenberg–Marquardt iteration then models the mean loss C(ξ) = (1/N) Σᵢ ‖rᵢ‖² near ξ₀ by
//   C(ξ₀ + δ) ≈ C + 2δᵀb + δᵀAδ,   A = (1/N) Σᵢ J̃ᵢᵀJ̃ᵢ,  b = (1/N) Σᵢ J̃ᵢᵀrᵢ,
// with J̃ᵢ = Jᵢ·diag(dθ/dξ) the Jacobian in the free coordinates (parameters.hpp; zero
// columns for parameters held fixed). Unlike a gradient method it sees the curvature of
// the whole parameter set at once, which is what directions that the data identify only
// weakly (e.g. a common scale of all masses, seen only through applied pushes) need.
// Each sample's J̃ᵢᵀJ̃ᵢ and J̃ᵢᵀrᵢ are reduced in sample order (batch.hpp), so A and b are
// bitwise the same for every thread count and MPI rank count.
#include <lcprelax/sparse/types.hpp>

#include <string>

namespace lcprelax::learn {

struct ResidualResult {
  bool ok = true;
  std::string message;   ///< why it failed when !ok
  Vector residual;       ///< rᵢ (ℓᵢ = ‖rᵢ‖²)
  DenseMatrix jacobian;  ///< ∂rᵢ/∂θ: residual.size() rows, one column per parameter of θ
};

}  // namespace lcprelax::learn
