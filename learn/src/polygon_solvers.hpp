#pragma once
// The polygon losses as instances of the island step losses (polygon_losses.hpp), internal:
// the sample's data as a ContactSystem and the pullback of a ContactSystemCotangent to θ.
//
// A polygon sample is one body on one half-plane: one ContactSystem with 3 dofs (vx, vy, ω),
// one Jn row and one Jt row per contact (friction row f belongs to contact f). Every entry
// of Jn and Jt is STORED, zeros included (to_contact_system's sparseView drops zeros, e.g.
// n_x = 0 on a level ground, and a step loss's cotangent only holds entries on the
// system's pattern, while a tangent such as ∂Jn/∂α = (t, (Rb)×t) fills them). Then
//     ∂ℓ/∂θ_k = ⟨∂ℓ/∂Jn, dJn_k⟩ + ⟨∂ℓ/∂Jt, dJt_k⟩ + ∂ℓ/∂φ·dφ_k + ∂ℓ/∂μ·dμ_k
//             + ∂ℓ/∂M⁻¹·dM⁻¹_k + ∂ℓ/∂v*·dv*_k,
// with d(·)_k = PolygonAssembly::tangent[k] (the chain rule through the data).
//
// PolygonSolvers: the per-thread workspace PolygonObjective passes to the hard and convex
// losses. Those step losses keep no solver between calls, so it holds nothing; the type
// stays because it is part of the losses' signatures.
#include <lcprelax/learn/polygon_losses.hpp>
#include <lcprelax/learn/step_loss.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/contact_system_gradient.hpp>

#include <vector>

namespace lcprelax::learn {

struct PolygonSolvers {
  explicit PolygonSolvers(const PolygonLossSettings& /*settings*/) {}
};

namespace detail {

// Dense n×3 matrix as a sparse one with every entry stored (explicit zeros kept).
inline SparseMatrix all_entries(const DenseMatrix& A) {
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(A.size()));
  for (Index j = 0; j < A.cols(); ++j)
    for (Index i = 0; i < A.rows(); ++i) t.emplace_back(i, j, A(i, j));
  SparseMatrix S(A.rows(), A.cols());
  S.setFromTriplets(t.begin(), t.end());  // keeps zero values: setFromTriplets does not prune
  S.makeCompressed();
  return S;
}

/// The sample's data as the island of one body (to_contact_system) with full Jn, Jt patterns.
inline ContactSystem polygon_system(const PolygonContactData& d) {
  ContactSystem s = to_contact_system(d);
  s.Jn = all_entries(d.Jn);
  s.Jt = all_entries(d.Jt);
  return s;
}

/// ⟨ct, t⟩ over every entry of Jn and Jt, φ, μ, M⁻¹ and v*.
inline double cotangent_inner(const ContactSystemCotangent& ct, const PolygonContactData& t) {
  auto entries = [](const SparseMatrix& G, const DenseMatrix& T) {
    double s = 0.0;
    for (Index j = 0; j < G.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(G, j); it; ++it) s += it.value() * T(it.row(), j);
    return s;
  };
  return entries(ct.Jn, t.Jn) + entries(ct.Jt, t.Jt) + ct.phi.dot(t.phi) + ct.mu.dot(t.mu) + ct.minv.dot(t.minv) +
         ct.v_star.dot(t.v_star);
}

/// ∂ℓ/∂θ_k = ⟨ct, a.tangent[k]⟩ for every parameter k.
inline Vector pull_back_to_theta(const ContactSystemCotangent& ct, const PolygonAssembly& a) {
  Vector g(static_cast<Index>(a.tangent.size()));
  for (std::size_t k = 0; k < a.tangent.size(); ++k) g(static_cast<Index>(k)) = cotangent_inner(ct, a.tangent[k]);
  return g;
}

}  // namespace detail
}  // namespace lcprelax::learn
