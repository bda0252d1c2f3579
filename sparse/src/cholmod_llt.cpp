// CholmodLlt: the public supernodal LLᵀ factorization for symmetric positive definite
// matrices, a thin pimpl over detail::CholmodEngine (cholmod_engine.cpp has the CHOLMOD
// calls).
#include <lcprelax/sparse/cholmod_llt.hpp>

#include "cholmod_engine.hpp"

namespace lcprelax::sparse {

struct CholmodLlt::Impl {
  std::unique_ptr<detail::CholmodEngine> engine;
};

CholmodLlt::CholmodLlt(CholmodOrdering ordering)
    : impl_(std::make_unique<Impl>(Impl{std::make_unique<detail::CholmodEngine>(
          detail::CholmodKind::supernodal_llt, 0.0, ordering)})) {}

CholmodLlt::~CholmodLlt() = default;
CholmodLlt::CholmodLlt(CholmodLlt&&) noexcept = default;
CholmodLlt& CholmodLlt::operator=(CholmodLlt&&) noexcept = default;

FactorResult CholmodLlt::analyze(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  return impl_->engine->analyze(A);
}

FactorResult CholmodLlt::factorize(const SparseMatrix& A) {
  if (!impl_) return detail::moved_from_result();
  FactorResult r = impl_->engine->factorize(A);
  if (r.ok()) ++numeric_factorizations_;
  return r;
}

FactorResult CholmodLlt::solve(Eigen::Ref<DenseMatrix> B) const {
  if (!impl_) return detail::moved_from_result();
  return impl_->engine->solve(B);
}

long CholmodLlt::factor_nnz() const { return impl_ ? impl_->engine->factor_nnz() : 0; }

double CholmodLlt::factor_flops() const { return impl_ ? impl_->engine->factor_flops() : 0.0; }

const char* CholmodLlt::ordering_name() const { return impl_ ? impl_->engine->ordering_name() : ""; }

Index CholmodLlt::rows() const { return impl_ ? impl_->engine->rows() : 0; }

CholmodLlt CholmodLlt::clone_analysis() const {
  CholmodLlt clone;
  if (impl_) clone.impl_->engine = impl_->engine->clone_analysis();
  return clone;
}

}  // namespace lcprelax::sparse
