#pragma once
// ∞-norm of a vector or a lazily evaluated vector expression (no temporary), 0 for an
// empty vector; internal to the interior-point QP (residuals, certificates, polishing).
#include <Eigen/Core>

namespace lcprelax::detail {

template <class V>
double inf_norm(const Eigen::MatrixBase<V>& v) {
  return v.size() ? v.template lpNorm<Eigen::Infinity>() : 0.0;
}

}  // namespace lcprelax::detail
