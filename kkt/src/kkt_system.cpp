// Assembly, factorization and refined solves of the interior-point KKT system
// (see kkt_system.hpp).
#include "kkt_system.hpp"

#include <lcprelax/sparse/petsc_mumps_ldlt.hpp>

#include <lcprelax/sparse/cholmod_ldlt.hpp>
#include <lcprelax/sparse/cholmod_llt.hpp>
#include <lcprelax/sparse/dense_ldlt.hpp>

#include <algorithm>
#include <cmath>

namespace lcprelax::detail {
namespace {

// Slot of entry (row, col) in a compressed matrix with sorted inner indices.
Index find_slot(const SparseMatrix& K, Index row, Index col) {
  const Index* begin = K.innerIndexPtr() + K.outerIndexPtr()[col];
  const Index* end = K.innerIndexPtr() + K.outerIndexPtr()[col + 1];
  const Index* it = std::lower_bound(begin, end, row);
  return static_cast<Index>(it - K.innerIndexPtr());
}

// Largest number of Gᵀ·diag·G product terms the eliminated form may keep.
constexpr long kMaxProductTerms = 20'000'000;

}  // namespace

void KktSystem::build_full_pattern(const StandardForm& f) {
  const Index n = f.n, me = f.me, mg = f.mg, N = n + me + mg;
  std::vector<Triplet> t;
  t.reserve(f.P.nonZeros() + f.E.nonZeros() + f.G.nonZeros() + N);
  for (Index c = 0; c < N; ++c) t.emplace_back(c, c, 1.0);
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(f.P, j); it; ++it)
      if (it.row() != j) t.emplace_back(it.row(), j, 1.0);
  for (Index k = 0; k < me; ++k)
    for (SparseMatrix::InnerIterator it(f.Et, k); it; ++it) t.emplace_back(it.row(), n + k, 1.0);
  for (Index i = 0; i < mg; ++i)
    for (SparseMatrix::InnerIterator it(f.Gt, i); it; ++it) t.emplace_back(it.row(), n + me + i, 1.0);
  K_.resize(N, N);
  K_.setFromTriplets(t.begin(), t.end());
  K_.makeCompressed();

  diag_pos_.resize(N);
  for (Index c = 0; c < N; ++c) diag_pos_[c] = find_slot(K_, c, c);
  p_pos_.assign(f.P.nonZeros(), -1);
  for (Index j = 0; j < n; ++j)
    for (Index k = f.P.outerIndexPtr()[j]; k < f.P.outerIndexPtr()[j + 1]; ++k)
      if (f.P.innerIndexPtr()[k] != j) p_pos_[k] = find_slot(K_, f.P.innerIndexPtr()[k], j);
  e_pos_.resize(f.Et.nonZeros());
  for (Index k = 0; k < me; ++k)
    for (Index s = f.Et.outerIndexPtr()[k]; s < f.Et.outerIndexPtr()[k + 1]; ++s)
      e_pos_[s] = find_slot(K_, f.Et.innerIndexPtr()[s], n + k);
  g_pos_.resize(f.Gt.nonZeros());
  for (Index i = 0; i < mg; ++i)
    for (Index s = f.Gt.outerIndexPtr()[i]; s < f.Gt.outerIndexPtr()[i + 1]; ++s)
      g_pos_[s] = find_slot(K_, f.Gt.innerIndexPtr()[s], n + me + i);
}

bool KktSystem::build_eliminated_pattern(const StandardForm& f) {
  const Index n = f.n;
  long terms = 0;
  for (Index i = 0; i < f.mg; ++i) {
    const long c = f.Gt.outerIndexPtr()[i + 1] - f.Gt.outerIndexPtr()[i];
    terms += c * (c + 1) / 2;
  }
  if (terms > kMaxProductTerms) return false;
  std::vector<Triplet> t;
  t.reserve(f.P.nonZeros() + n + terms);
  for (Index c = 0; c < n; ++c) t.emplace_back(c, c, 1.0);
  for (Index j = 0; j < n; ++j)
    for (SparseMatrix::InnerIterator it(f.P, j); it; ++it)
      if (it.row() != j) t.emplace_back(it.row(), j, 1.0);
  const Index* gi = f.Gt.innerIndexPtr();
  for (Index i = 0; i < f.mg; ++i)
    for (Index a = f.Gt.outerIndexPtr()[i]; a < f.Gt.outerIndexPtr()[i + 1]; ++a)
      for (Index b = a; b < f.Gt.outerIndexPtr()[i + 1]; ++b) t.emplace_back(gi[a], gi[b], 1.0);
  K_.resize(n, n);
  K_.setFromTriplets(t.begin(), t.end());
  K_.makeCompressed();

  diag_pos_.resize(n);
  for (Index c = 0; c < n; ++c) diag_pos_[c] = find_slot(K_, c, c);
  p_pos_.assign(f.P.nonZeros(), -1);
  for (Index j = 0; j < n; ++j)
    for (Index k = f.P.outerIndexPtr()[j]; k < f.P.outerIndexPtr()[j + 1]; ++k)
      if (f.P.innerIndexPtr()[k] != j) p_pos_[k] = find_slot(K_, f.P.innerIndexPtr()[k], j);
  products_.clear();
  products_.reserve(terms);
  for (Index i = 0; i < f.mg; ++i)
    for (Index a = f.Gt.outerIndexPtr()[i]; a < f.Gt.outerIndexPtr()[i + 1]; ++a)
      for (Index b = a; b < f.Gt.outerIndexPtr()[i + 1]; ++b)
        products_.push_back({find_slot(K_, gi[a], gi[b]), i, a, b});
  return true;
}

KktBackend KktSystem::resolve_backend(KktBackend requested, const StandardForm& f, int dense_max_kkt) {
  if (requested != KktBackend::automatic) return requested;
  return static_cast<long>(f.n) + f.me + f.mg <= dense_max_kkt ? KktBackend::dense : KktBackend::cholmod;
}

bool KktSystem::setup(const StandardForm& f, KktForm requested, KktBackend backend, std::string& message,
                      KktOrdering ordering) {
  const sparse::CholmodOrdering cholmod_ordering =
      ordering == KktOrdering::amd ? sparse::CholmodOrdering::amd : sparse::CholmodOrdering::best;
  if (backend == KktBackend::automatic) backend = KktBackend::cholmod;  // callers resolve it first
  const bool dense = backend == KktBackend::dense;
  KktForm form = requested;
  if (f.me > 0) form = KktForm::full;  // the eliminated form has no equality block
  if (uses_petsc(backend)) form = KktForm::full;  // MUMPS: the quasi-definite LDLᵀ
  std::unique_ptr<sparse::Factorization> full, elim;
  SparseMatrix full_K;
  if (form != KktForm::eliminated) {
    build_full_pattern(f);
    if (backend == KktBackend::cholmod)
      full = std::make_unique<sparse::CholmodLdlt>(0.0, cholmod_ordering);
    else if (dense)
      full = std::make_unique<sparse::DenseLdlt>();
    else
      full = std::make_unique<sparse::PetscMumpsLdlt>(backend == KktBackend::mumps_distributed, /*pivoting=*/false);
    if (auto r = full->analyze(K_); !r.ok()) {
      message = "KKT analysis failed: " + r.message;
      return false;
    }
    full_K = K_;
  }
  if (form != KktForm::full) {
    if (!build_eliminated_pattern(f)) {
      if (form == KktForm::eliminated) {
        message = "eliminated KKT form refused: Gᵀ·G has too many product terms";
        return false;
      }
    } else {
      if (dense)
        elim = std::make_unique<sparse::DenseLdlt>();
      else
        elim = std::make_unique<sparse::CholmodLlt>(cholmod_ordering);
      if (auto r = elim->analyze(K_); !r.ok()) {
        message = "KKT analysis failed: " + r.message;
        return false;
      }
    }
  }
  if (elim && (!full || elim->factor_nnz() < full->factor_nnz())) {
    form_ = KktForm::eliminated;
    factor_ = std::move(elim);
  } else {
    form_ = KktForm::full;
    factor_ = std::move(full);
    if (elim) build_full_pattern(f);  // restore the full pattern's maps
  }
  // Solve and refinement scratch, sized once here (solve() then allocates nothing).
  work_.setZero(K_.rows());
  for (Vector* v : {&ox_, &cx_, &nx_}) v->setZero(f.n);
  for (Vector* v : {&oy_, &cy_, &ny_}) v->setZero(form_ == KktForm::full ? f.me : 0);
  for (Vector* v : {&oz_, &cz_, &nz_, &wr_, &rzw_}) v->setZero(f.mg);
  Db_.setZero(f.n);
  Dg_.setZero(f.mg);
  backend_ = backend;
  return true;
}

sparse::FactorResult KktSystem::factorize(const StandardForm& f, const Vector& Db, const Vector& Dg, double rho,
                                          double delta, double delta_rows) {
  Db_ = Db;
  Dg_ = Dg;
  rho_ = rho;
  delta_ = delta;
  delta_rows_ = delta_rows;
  double* val = K_.valuePtr();
  std::fill(val, val + K_.nonZeros(), 0.0);
  for (Index j = 0; j < f.n; ++j)
    for (Index k = f.P.outerIndexPtr()[j]; k < f.P.outerIndexPtr()[j + 1]; ++k)
      val[p_pos_[k] >= 0 ? p_pos_[k] : diag_pos_[j]] += f.P.valuePtr()[k];
  for (Index j = 0; j < f.n; ++j) val[diag_pos_[j]] += Db(j) + rho;
  if (form_ == KktForm::full) {
    for (Index s = 0; s < f.Et.nonZeros(); ++s) val[e_pos_[s]] = f.Et.valuePtr()[s];
    for (Index k = 0; k < f.me; ++k) val[diag_pos_[f.n + k]] = -delta;
    for (Index s = 0; s < f.Gt.nonZeros(); ++s) val[g_pos_[s]] = f.Gt.valuePtr()[s];
    for (Index i = 0; i < f.mg; ++i) val[diag_pos_[f.n + f.me + i]] = -(1.0 / Dg(i) + delta_rows_);
  } else {
    const double* gv = f.Gt.valuePtr();
    for (const ProductTerm& t : products_) {
      const double w = Dg(t.row) / (1.0 + delta_rows_ * Dg(t.row));
      val[t.pos] += w * gv[t.a] * gv[t.b];
    }
  }
  // Every LDLᵀ reports its inertia: the full form must have n positive pivots (the primal
  // block) and the rest negative; the dense eliminated form (size n) must be SPD, i.e. n
  // positive. CHOLMOD's supernodal LLᵀ of the eliminated form fails by itself when it is
  // not SPD.
  const auto wrong_inertia = [&](const sparse::FactorResult& r) {
    return r.ok() && factor_->reports_inertia() && factor_->inertia().positive != f.n;
  };
  sparse::FactorResult r = factor_->factorize(K_);
  // A static-order factor (MUMPS without pivoting) with the wrong inertia: roundoff can flip
  // a pivot's sign in an order that CHOLMOD's does not meet (LISWET1 near its optimum with
  // δ dropped on the inequality block: 10,001 negative pivots for 10,000 rows, so δ was put
  // back and the solve stalled). The matrix is factorized once more with threshold pivoting,
  // whose inertia is that of a nearby matrix, before the wrong inertia is reported (and the
  // QP solver regularizes more). On LISWET1: 3 of its 97 KKT factorizations, the
  // pivoted ones with 10,000 negative pivots; solved in 95 iterations (CHOLMOD: 92).
  if (wrong_inertia(r) && factor_->can_refactorize_pivoted()) r = factor_->refactorize_pivoted();
  if (wrong_inertia(r)) {
    r.status = sparse::FactorStatus::zero_pivot;
    r.message = "KKT factor has " + std::to_string(factor_->inertia().positive) + " positive pivots, expected " +
                std::to_string(f.n) +
                (form_ == KktForm::full ? " (not quasi-definite)" : " (not positive definite)");
  }
  return r;
}

void KktSystem::apply_k0(const StandardForm& f, const Vector& dx, const Vector& dy, const Vector& dz, Vector& ox,
                         Vector& oy, Vector& oz) const {
  ox.noalias() = f.P.selfadjointView<Eigen::Upper>() * dx;
  ox.array() += Db_.array() * dx.array();
  if (f.me > 0) ox.noalias() += f.Et * dy;
  if (f.mg > 0) ox.noalias() += f.Gt * dz;
  oy.noalias() = f.E * dx;
  oz.noalias() = f.G * dx;
  oz.array() -= dz.array() / Dg_.array();
  if (refine_regularized_) {
    ox += rho_ * dx;
    if (f.me > 0) oy -= delta_ * dy;
    oz -= delta_rows_ * dz;
  }
}

void KktSystem::approximate_solve(const StandardForm& f, const Vector& rx, const Vector& ry, const Vector& rz,
                                  Vector& dx, Vector& dy, Vector& dz) const {
  if (form_ == KktForm::full) {
    work_.head(f.n) = rx;
    work_.segment(f.n, f.me) = ry;
    work_.tail(f.mg) = rz;
    factor_->solve(work_);
    dx = work_.head(f.n);
    dy = work_.segment(f.n, f.me);
    dz = work_.tail(f.mg);
  } else {
    wr_ = (1.0 / Dg_.array() + delta_rows_).matrix();
    rzw_ = (rz.array() / wr_.array()).matrix();
    work_ = rx;
    if (f.mg > 0) work_.noalias() += f.Gt * rzw_;
    factor_->solve(work_);
    dx = work_;
    dy.resize(0);
    dz.noalias() = f.G * dx;
    dz.array() = (dz.array() - rz.array()) / wr_.array();
  }
}

int KktSystem::solve(const StandardForm& f, const Vector& rx, const Vector& ry, const Vector& rz, Vector& dx,
                     Vector& dy, Vector& dz, int max_refinement) const {
  approximate_solve(f, rx, ry, rz, dx, dy, dz);
  last_relative_residual_ = 0.0;
  if (max_refinement <= 0) return 0;
  const double rhs_norm = std::max({rx.lpNorm<Eigen::Infinity>(), f.me ? ry.lpNorm<Eigen::Infinity>() : 0.0,
                                    f.mg ? rz.lpNorm<Eigen::Infinity>() : 0.0});
  Vector &ox = ox_, &oy = oy_, &oz = oz_, &cx = cx_, &cy = cy_, &cz = cz_;
  auto residual = [&](const Vector& ax, const Vector& ay, const Vector& az) {
    apply_k0(f, ax, ay, az, ox, oy, oz);
    ox = rx - ox;
    oy = ry - oy;
    oz = rz - oz;
    double r = ox.size() ? ox.lpNorm<Eigen::Infinity>() : 0.0;
    if (oy.size()) r = std::max(r, oy.lpNorm<Eigen::Infinity>());
    if (oz.size()) r = std::max(r, oz.lpNorm<Eigen::Infinity>());
    return r;
  };
  double res = residual(dx, dy, dz);
  int steps = 0;
  for (; steps < max_refinement; ++steps) {
    if (!(res > 1e-15 * (1.0 + rhs_norm))) break;
    approximate_solve(f, ox, oy, oz, cx, cy, cz);
    Vector &nx = nx_, &ny = ny_, &nz = nz_;
    nx = dx + cx;
    ny = dy + cy;
    nz = dz + cz;
    const double nres = residual(nx, ny, nz);
    if (!(nres < res)) break;
    dx.swap(nx);
    dy.swap(ny);
    dz.swap(nz);
    const bool slow = nres > res / 5.0;
    res = nres;
    if (slow) break;
  }
  last_relative_residual_ = res / (1.0 + rhs_norm);
  return steps;
}

long KktSystem::factor_nnz() const { return factor_ ? factor_->factor_nnz() : 0; }

double KktSystem::factor_flops() const { return factor_ ? factor_->factor_flops() : 0.0; }

int KktSystem::numeric_factorizations() const { return factor_ ? factor_->numeric_factorizations() : 0; }

}  // namespace lcprelax::detail
