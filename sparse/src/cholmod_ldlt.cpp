// CholmodLdlt: the public simplicial LDLᵀ factorization for quasi-definite KKT matrices,
// a thin pimpl over detail::CholmodEngine (see cholmod_engine.cpp for the CHOLMOD calls).
#include <lcprelax/sparse/cholmod_ldlt.hpp>

#include "cholmod_engine.hpp"

namespace lcprelax::sparse {

struct CholmodLdlt::Impl {
  std::unique_ptr<detail::CholmodEngine> engine;
};

CholmodLdlt::CholmodLdlt(double dynamic_regularization, CholmodOrdering ordering)
    : impl_(std::make_unique<Impl>(Impl{std::make_unique<detail::CholmodEngine>(
          detail::CholmodKind::simplicial_ldlt, dynamic_regularization, ordering)})) {}

CholmodLdlt::~CholmodLdlt() = default;
CholmodLdlt::CholmodLdlt(CholmodLdlt&&) noexcept = default;
CholmodLdlt& CholmodLdlt::operator=(CholmodLdlt&&) noexcept = default;

FactorResult CholmodLdlt::analyze(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  return impl_->engine->analyze(A);
}

FactorResult CholmodLdlt::factorize(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  FactorResult r = impl_->engine->factorize(A);
  if (r.ok()) ++numeric_factorizations_;
  return r;
}

FactorResult CholmodLdlt::solve(Eigen::Ref<DenseMatrix> B) const {
  if (!impl_) return detail::moved_from_result();
  return impl_->engine->solve(B);
}

long CholmodLdlt::factor_nnz() const { return impl_ ? impl_->engine->factor_nnz() : 0; }

double CholmodLdlt::factor_flops() const { return impl_ ? impl_->engine->factor_flops() : 0.0; }

const char* CholmodLdlt::ordering_name() const { return impl_ ? impl_->engine->ordering_name() : ""; }

Index CholmodLdlt::rows() const { return impl_ ? impl_->engine->rows() : 0; }

Inertia CholmodLdlt::inertia() const { return impl_ ? impl_->engine->inertia() : Inertia{}; }

CholmodLdlt CholmodLdlt::clone_analysis() const {
  CholmodLdlt clone;
  if (impl_) clone.impl_->engine = impl_->engine->clone_analysis();
  return clone;
}

}  // namespace lcprelax::sparse
