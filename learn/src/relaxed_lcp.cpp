// The relaxed (soft-LCP) loss of one sample and its envelope/adjoint gradients
// (learn/relaxed_lcp.hpp).
#include "elapsed.hpp"

#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/kkt/qp_solver.hpp>
#include <lcprelax/core/errors.hpp>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace lcprelax::learn {

const char* to_string(MaxDissipation m) {
  switch (m) {
    case MaxDissipation::none: return "none";
    case MaxDissipation::qp: return "qp";
    case MaxDissipation::ext: return "ext";
  }
  return "unknown";
}

MaxDissipation parse_max_dissipation(const std::string& s) {
  if (s == "none") return MaxDissipation::none;
  if (s == "qp") return MaxDissipation::qp;
  if (s == "ext") return MaxDissipation::ext;
  throw InputError("unknown max-dissipation mode '" + s + "' (none, qp or ext)");
}

const char* to_string(RelaxedLcpStatus s) {
  switch (s) {
    case RelaxedLcpStatus::solved: return "solved";
    case RelaxedLcpStatus::nonconvex: return "nonconvex";
    case RelaxedLcpStatus::qp_failed: return "qp_failed";
  }
  return "unknown";
}

std::string RelaxedLcpSettings::validation_error() const {
  const double w[] = {a1, a2, a3, a4, a5, regularization};
  const char* names[] = {"a1", "a2", "a3", "a4", "a5", "regularization"};
  for (int i = 0; i < 6; ++i)
    if (!std::isfinite(w[i]) || w[i] < 0.0) return std::string(names[i]) + " must be finite and ≥ 0";
  if (!(a1 > 0.0)) return "a1 must be positive";
  return {};
}

void RelaxedLcpData::validate(const RelaxedLcpSettings& settings) const {
  auto fail = [](const std::string& m) { throw InputError("relaxed LCP data: " + m); };
  const Index n = M.rows();
  if (M.cols() != n || n == 0) fail("M must be square and non-empty");
  if (q.size() != n) fail("q has length " + std::to_string(q.size()) + ", expected " + std::to_string(n));
  if (P.cols() != n) fail("P must have " + std::to_string(n) + " columns");
  if (p.size() != P.rows() || target.size() != P.rows()) fail("p and the target must have P's row count");
  const bool md = settings.max_dissipation != MaxDissipation::none;
  if (md && (E.cols() != n || e.size() != E.rows())) fail("E must have n columns and e E's row count");
  auto finite = [](const SparseMatrix& A) {
    for (Index k = 0; k < A.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(A, k); it; ++it)
        if (!std::isfinite(it.value())) return false;
    return true;
  };
  if (!finite(M)) fail("M has a non-finite entry");
  if (!finite(P)) fail("P has a non-finite entry");
  if (!q.allFinite()) fail("q has a non-finite entry");
  if (!p.allFinite()) fail("p has a non-finite entry");
  if (!target.allFinite()) fail("the target has a non-finite entry");
  if (md && (!finite(E) || !e.allFinite())) fail("E or e has a non-finite entry");
}

namespace {

using detail::Clock;
using detail::since;

// A matrix with A's pattern and values f(row, col).
template <class F>
SparseMatrix on_pattern(const SparseMatrix& A, F f) {
  SparseMatrix out = A;
  for (Index k = 0; k < out.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(out, k); it; ++it) it.valueRef() = f(it.row(), it.col());
  return out;
}

}  // namespace

namespace detail {
// Where each assembled entry goes in a compressed matrix: entry k (in emission order) at
// position (row[k], col[k]) is stored in valuePtr()[slot[k]]; first[k] marks the first
// entry of its slot (assigned; later ones are added). Not in the anonymous namespace: a
// member of RelaxedLcpSolver::Impl, which has external linkage (-Wsubobject-linkage).
struct RelaxedLcpEntryMap {
  std::vector<Index> row, col, slot;
  std::vector<char> first;
};
}  // namespace detail
using EntryMap = detail::RelaxedLcpEntryMap;

struct RelaxedLcpSolver::Impl {
  RelaxedLcpSettings opt;
  QpSolver qp;
  bool qp_ready = false;
  QpProblem prob;
  EntryMap h_map, g_map;     // entry maps of prob.P and prob.G
  bool pattern_ready = false;
  // The convexity test only needs to know whether LLᵀ exists: Eigen's simplicial LLᵀ (no
  // OpenMP, no BLAS, no synchronization between threads; these matrices are tiny).
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Upper> llt;
  SparseMatrix llt_matrix;   // H + τI (storage reused between samples)
  SparseMatrix llt_pattern;  // pattern of the last analysis
  bool llt_ready = false;
  RelaxedLcpData data;  // copy of the last sample (for the adjoint check)
  RelaxedLcpResult res;
  Index n = 0, ns = 0, nt = 0;
  Vector warm_x, warm_y, warm_z, warm_zb;

  bool qp_term() const { return opt.max_dissipation == MaxDissipation::qp; }
  bool ext_term() const { return opt.max_dissipation == MaxDissipation::ext; }

  // The entries of H (upper triangle) in a fixed order, as sink(row, col, value); entries
  // at the same position are summed in this order. The sequence of positions depends only
  // on the sparsity patterns of M, P, E and on the settings.
  template <class Sink>
  void hessian_entries(double shift, Sink&& sink) const {
    const RelaxedLcpSettings& o = opt;
    for (Index k = 0; k < data.M.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(data.M, k); it; ++it) {
        const Index i = it.row(), j = it.col();
        sink(std::min(i, j), std::max(i, j), (i == j ? 2.0 : 1.0) * o.a2 * it.value());
      }
    auto add_gram = [&sink](const SparseMatrix& A, double w) {
      const SparseMatrix AtA = SparseMatrix(A.transpose()) * A;
      for (Index k = 0; k < AtA.outerSize(); ++k)
        for (SparseMatrix::InnerIterator it(AtA, k); it; ++it)
          if (it.row() <= it.col()) sink(it.row(), it.col(), w * it.value());
    };
    add_gram(data.P, 2.0 * o.a1);
    if (qp_term()) add_gram(data.E, 2.0 * o.a5);
    for (Index i = 0; i < n; ++i) sink(i, i, o.regularization + shift);
    const double ws = o.l1_softness ? 0.0 : o.a3, wt = o.l1_softness ? 0.0 : o.a4;
    for (Index i = 0; i < ns; ++i) sink(n + i, n + i, ws + o.regularization);
    for (Index i = 0; i < nt; ++i) sink(n + ns + i, n + ns + i, wt + o.regularization);
  }

  // The entries of the rows: M λ (+ s) ≥ −q; with soft λ also λ + t ≥ 0.
  template <class Sink>
  void row_entries(Sink&& sink) const {
    for (Index k = 0; k < data.M.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(data.M, k); it; ++it) sink(it.row(), it.col(), it.value());
    for (Index i = 0; i < ns; ++i) sink(i, n + i, 1.0);
    for (Index i = 0; i < nt; ++i) {
      sink(n + i, i, 1.0);
      sink(n + i, n + ns + i, 1.0);
    }
  }

  // H (upper), h, r, rows and bounds of the relaxed QP; `shift` adds δI to H_λλ. When the
  // entry positions repeat those of the previous call, the values are written in place into
  // prob.P and prob.G through the entry maps; otherwise both matrices are rebuilt from
  // triplets and the maps made again. Both ways give the same values bit for bit (an entry
  // is its first contribution plus the later ones in order, as setFromTriplets sums them).
  void assemble(double shift) {
    const RelaxedLcpSettings& o = opt;
    n = data.M.rows();
    ns = o.soft_nonnegativity ? n : 0;
    nt = o.soft_lambdas ? n : 0;
    const Index nv = n + ns + nt;
    const Index mi = n + nt;
    const double inf = std::numeric_limits<double>::infinity();
    const bool sizes_match = pattern_ready && prob.num_variables() == nv && prob.num_inequalities() == mi;
    if (!(sizes_match && write_in_place(h_map, prob.P, [&](auto&& sink) { hessian_entries(shift, sink); }) &&
          write_in_place(g_map, prob.G, [&](auto&& sink) { row_entries(sink); }))) {
      prob = QpProblem(nv);
      build(h_map, prob.P, nv, nv, [&](auto&& sink) { hessian_entries(shift, sink); });
      build(g_map, prob.G, mi, nv, [&](auto&& sink) { row_entries(sink); });
      pattern_ready = true;
    }

    const Vector res0 = data.p - data.target;
    prob.q = Vector::Zero(nv);
    prob.q.head(n) = 2.0 * o.a1 * (data.P.transpose() * res0) + o.a2 * data.q;
    prob.r = o.a1 * res0.squaredNorm();
    if (qp_term()) {
      prob.q.head(n) -= 2.0 * o.a5 * (data.E.transpose() * data.e);
      prob.r += o.a5 * data.e.squaredNorm();
    }
    if (o.l1_softness) {
      prob.q.segment(n, ns).setConstant(o.a3);
      prob.q.tail(nt).setConstant(o.a4);
    }
    prob.l = Vector::Zero(mi);
    prob.l.head(n) = -data.q;
    prob.u = Vector::Constant(mi, inf);
    prob.xl = Vector::Zero(nv);
    if (o.soft_lambdas) prob.xl.head(n).setConstant(-inf);
    prob.xu = Vector::Constant(nv, inf);
  }

  // Builds `A` (rows × cols, compressed) from the entries that `emit` produces and records
  // where each entry went.
  template <class Emit>
  static void build(EntryMap& map, SparseMatrix& A, Index rows, Index cols, Emit&& emit) {
    std::vector<Triplet> t;
    map.row.clear();
    map.col.clear();
    emit([&](Index i, Index j, double v) {
      t.emplace_back(i, j, v);
      map.row.push_back(i);
      map.col.push_back(j);
    });
    A.resize(rows, cols);
    A.setFromTriplets(t.begin(), t.end());
    A.makeCompressed();
    const std::size_t count = t.size();
    map.slot.resize(count);
    map.first.assign(count, 0);
    std::vector<char> seen(static_cast<std::size_t>(A.nonZeros()), 0);
    const Index* outer = A.outerIndexPtr();
    const Index* inner = A.innerIndexPtr();
    for (std::size_t k = 0; k < count; ++k) {
      const Index* b = inner + outer[map.col[k]];
      const Index* e = inner + outer[map.col[k] + 1];
      const Index s = static_cast<Index>(std::lower_bound(b, e, map.row[k]) - inner);
      map.slot[k] = s;
      map.first[k] = seen[static_cast<std::size_t>(s)] ? 0 : 1;
      seen[static_cast<std::size_t>(s)] = 1;
    }
  }

  // Writes the values that `emit` produces into A's value array by the map; false (A then
  // partly written) when the entries' positions differ from the map's.
  template <class Emit>
  static bool write_in_place(const EntryMap& map, SparseMatrix& A, Emit&& emit) {
    double* value = A.valuePtr();
    const std::size_t count = map.slot.size();
    std::size_t k = 0;
    bool same = true;
    emit([&](Index i, Index j, double v) {
      if (!same) return;
      if (k == count || map.row[k] != i || map.col[k] != j) {
        same = false;
        return;
      }
      double& dst = value[map.slot[k]];
      if (map.first[k])
        dst = v;
      else
        dst += v;
      ++k;
    });
    return same && k == count;
  }

  // LLᵀ of H + τI (τ tiny: a PSD but singular H passes); true if it succeeds.
  bool positive_definite() {
    llt_matrix = prob.P;
    SparseMatrix& H = llt_matrix;
    const double tau = 1e-10 * std::max(1.0, hessian_norm());
    for (Index i = 0; i < H.rows(); ++i) H.coeffRef(i, i) += tau;
    if (!llt_ready || llt_pattern.rows() != H.rows() || llt_pattern.nonZeros() != H.nonZeros() ||
        !std::equal(H.innerIndexPtr(), H.innerIndexPtr() + H.nonZeros(), llt_pattern.innerIndexPtr()) ||
        !std::equal(H.outerIndexPtr(), H.outerIndexPtr() + H.cols() + 1, llt_pattern.outerIndexPtr())) {
      llt.analyzePattern(H);
      if (llt.info() != Eigen::Success) return false;
      llt_pattern = H;
      llt_ready = true;
    }
    llt.factorize(H);
    return llt.info() == Eigen::Success;  // NumericalIssue: a pivot ≤ 0
  }

  double hessian_norm() const {
    double m = 0.0;
    Vector rows = Vector::Zero(prob.P.rows());
    for (Index k = 0; k < prob.P.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(prob.P, k); it; ++it) {
        rows(it.row()) += std::abs(it.value());
        if (it.row() != it.col()) rows(it.col()) += std::abs(it.value());
      }
    if (rows.size() > 0) m = rows.maxCoeff();
    return m;
  }

  double objective(const Vector& x) const {
    double quad = 0.0;
    for (Index k = 0; k < prob.P.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(prob.P, k); it; ++it)
        quad += (it.row() == it.col() ? 0.5 : 1.0) * it.value() * x(it.row()) * x(it.col());
    return quad + prob.q.dot(x) + prob.r;
  }

  // ∂/∂data of the assembly: maps a gradient on (H upper, h, r, G, l) to the data.
  RelaxedLcpGradient chain(const SparseMatrix& gH, const Vector& gh, double gr, const SparseMatrix& gG,
                           const Vector& gl) const {
    const RelaxedLcpSettings& o = opt;
    // Ĝ: the symmetric gradient on the full λλ block.
    std::vector<Triplet> tsym;
    for (Index k = 0; k < gH.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(gH, k); it; ++it) {
        if (it.row() >= n || it.col() >= n) continue;
        if (it.row() == it.col()) {
          tsym.emplace_back(it.row(), it.col(), it.value());
        } else {
          tsym.emplace_back(it.row(), it.col(), 0.5 * it.value());
          tsym.emplace_back(it.col(), it.row(), 0.5 * it.value());
        }
      }
    SparseMatrix Gs(n, n);
    Gs.setFromTriplets(tsym.begin(), tsym.end());
    const Vector ghl = gh.head(n);
    const Vector res0 = data.p - data.target;
    const SparseMatrix PG = data.P * Gs;
    RelaxedLcpGradient g;
    g.dM = on_pattern(data.M, [&](Index i, Index j) { return 2.0 * o.a2 * Gs.coeff(i, j) + gG.coeff(i, j); });
    g.dq = o.a2 * ghl - gl.head(n);
    g.dP = on_pattern(data.P, [&](Index k, Index j) { return 4.0 * o.a1 * PG.coeff(k, j) + 2.0 * o.a1 * res0(k) * ghl(j); });
    const Vector Pgh = data.P * ghl;
    g.dp = 2.0 * o.a1 * Pgh + 2.0 * o.a1 * gr * res0;
    g.dtarget = -g.dp;
    g.dE = on_pattern(data.E, [](Index, Index) { return 0.0; });
    g.de = Vector::Zero(data.e.size());
    if (qp_term()) {
      const SparseMatrix EG = data.E * Gs;
      g.dE = on_pattern(data.E, [&](Index k, Index j) { return 4.0 * o.a5 * EG.coeff(k, j) - 2.0 * o.a5 * data.e(k) * ghl(j); });
      g.de = -2.0 * o.a5 * (data.E * ghl) + 2.0 * o.a5 * gr * data.e;
    }
    return g;
  }

  static void accumulate(RelaxedLcpGradient& a, const RelaxedLcpGradient& b) {
    a.dM += b.dM;
    a.dq += b.dq;
    a.dP += b.dP;
    a.dp += b.dp;
    a.dtarget += b.dtarget;
    a.dE += b.dE;
    a.de += b.de;
  }

  // ∂/∂data of the ext term a5‖Eλ − e‖² at fixed λ, and its ∂/∂x.
  void ext_partials(RelaxedLcpGradient& g, Vector& dl_dx) const {
    const Vector lam = res.lambda;
    const Vector sigma = data.E * lam - data.e;
    g.dE += on_pattern(data.E, [&](Index k, Index j) { return 2.0 * opt.a5 * sigma(k) * lam(j); });
    g.de += -2.0 * opt.a5 * sigma;
    dl_dx.head(n) += 2.0 * opt.a5 * (data.E.transpose() * sigma);
  }

  void envelope() {
    const RelaxedLcpSettings& o = opt;
    const Vector& lam = res.lambda;
    const Vector& z = res.multipliers;
    const Vector rho = data.P * lam + data.p - data.target;
    RelaxedLcpGradient& g = res.gradient;
    g.dM = on_pattern(data.M, [&](Index i, Index j) { return o.a2 * lam(i) * lam(j) + z(i) * lam(j); });
    g.dq = o.a2 * lam + z;
    g.dP = on_pattern(data.P, [&](Index k, Index j) { return 2.0 * o.a1 * rho(k) * lam(j); });
    g.dp = 2.0 * o.a1 * rho;
    g.dtarget = -g.dp;
    g.dE = on_pattern(data.E, [](Index, Index) { return 0.0; });
    g.de = Vector::Zero(data.e.size());
    if (qp_term()) {
      const Vector sigma = data.E * lam - data.e;
      g.dE = on_pattern(data.E, [&](Index k, Index j) { return 2.0 * o.a5 * sigma(k) * lam(j); });
      g.de = -2.0 * o.a5 * sigma;
    }
    if (ext_term()) {  // λ*(data) enters the ext term: one adjoint solve
      Vector dl_dx = Vector::Zero(prob.num_variables());
      ext_partials(g, dl_dx);
      const QpGradient b = qp.backward(dl_dx);
      accumulate(g, chain(b.dP, b.dq, 0.0, b.dG, b.dl));
    }
  }
};

RelaxedLcpSolver::RelaxedLcpSolver(RelaxedLcpSettings settings, QpSettings qp_settings)
    : impl_(std::make_unique<Impl>()) {
  const std::string error = settings.validation_error();
  if (!error.empty()) throw InputError("relaxed LCP settings: " + error);
  impl_->opt = settings;
  impl_->qp.set_settings(qp_settings);
}
RelaxedLcpSolver::~RelaxedLcpSolver() = default;
RelaxedLcpSolver::RelaxedLcpSolver(RelaxedLcpSolver&&) noexcept = default;
RelaxedLcpSolver& RelaxedLcpSolver::operator=(RelaxedLcpSolver&&) noexcept = default;

const RelaxedLcpSettings& RelaxedLcpSolver::settings() const { return impl_->opt; }

void RelaxedLcpSolver::warm_start(const RelaxedLcpResult& previous) {
  impl_->warm_x = previous.qp_x;
  impl_->warm_z = previous.qp_z;
  impl_->warm_zb = previous.qp_z_bounds;
}

const RelaxedLcpResult& RelaxedLcpSolver::solve(const RelaxedLcpData& data, bool gradient) {
  Impl& m = *impl_;
  data.validate(m.opt);
  const auto t0 = Clock::now();
  m.data = data;
  m.res = RelaxedLcpResult();
  m.res.cost = std::numeric_limits<double>::quiet_NaN();
  m.assemble(0.0);
  if (!m.positive_definite()) {
    if (m.opt.nonconvex == NonconvexPolicy::report) {
      m.res.status = RelaxedLcpStatus::nonconvex;
      m.res.message = "the relaxed QP's Hessian 2a1·PᵀP + a2(M + Mᵀ) + εI is not positive semidefinite";
      return m.res;
    }
    // δ does not depend on the data (no ‖H‖ factor), so that the envelope gradient, which
    // treats δ as a constant, is exact wherever the same k is chosen.
    const double base = std::max(m.opt.regularization, 1e-8);
    bool ok = false;
    for (int k = 0; k <= 12 && !ok; ++k) {
      m.res.shift = base * std::pow(10.0, k);
      m.assemble(m.res.shift);
      ok = m.positive_definite();
    }
    if (!ok) {
      m.res.status = RelaxedLcpStatus::nonconvex;
      m.res.message = "no diagonal shift up to 1e12 made the relaxed QP convex";
      return m.res;
    }
  }
  m.res.assembly_seconds = since(t0);
  const auto t1 = Clock::now();
  if (m.qp_ready && m.qp.can_update(m.prob)) {
    m.qp.update(m.prob);  // same pattern: ordering and symbolic analysis reused
  } else {
    m.qp.setup(m.prob);
    m.qp_ready = true;
  }
  const Index nv = m.prob.num_variables();
  if (m.warm_x.size() == nv && m.warm_z.size() == m.prob.num_inequalities() && m.warm_zb.size() == nv)
    m.qp.warm_start(m.warm_x, Vector(), m.warm_z, m.warm_zb);
  m.warm_x.resize(0);
  const QpResult& r = m.qp.solve();
  m.res.solve_seconds = since(t1);
  m.res.qp_status = r.info.status;
  m.res.iterations = r.info.iterations;
  if (!has_solution(r.info.status)) {
    m.res.status = RelaxedLcpStatus::qp_failed;
    m.res.message = std::string("relaxed QP: ") + to_string(r.info.status) + " (" + r.info.message + ")";
    return m.res;
  }
  const Index n = m.n;
  m.res.status = RelaxedLcpStatus::solved;
  m.res.qp_x = r.x;
  m.res.qp_z = r.z;
  m.res.qp_z_bounds = r.z_bounds;
  m.res.lambda = r.x.head(n);
  m.res.slack = m.ns > 0 ? Vector(r.x.segment(n, n)) : Vector(Vector::Zero(n));
  m.res.lambda_slack = m.nt > 0 ? Vector(r.x.tail(n)) : Vector(Vector::Zero(n));
  m.res.multipliers = r.z.head(n);
  m.res.cost = m.objective(r.x);
  if (m.ext_term()) m.res.cost += m.opt.a5 * (m.data.E * m.res.lambda - m.data.e).squaredNorm();
  if (gradient) {
    const auto t2 = Clock::now();
    m.envelope();
    m.res.gradient_seconds = since(t2);
  }
  return m.res;
}

RelaxedLcpGradient RelaxedLcpSolver::gradient_adjoint() {
  Impl& m = *impl_;
  if (m.res.status != RelaxedLcpStatus::solved) throw std::logic_error("gradient_adjoint: the last solve failed");
  const Vector& x = m.res.qp_x;
  // ℓ = f(x*(D), D): ∂ℓ/∂x = Hx + h (+ ext), explicit ∂f/∂H = ½xxᵀ, ∂f/∂h = x, ∂f/∂r = 1.
  Vector dl_dx = m.prob.q;
  for (Index k = 0; k < m.prob.P.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(m.prob.P, k); it; ++it) {
      dl_dx(it.row()) += it.value() * x(it.col());
      if (it.row() != it.col()) dl_dx(it.col()) += it.value() * x(it.row());
    }
  RelaxedLcpGradient g;
  g.dE = on_pattern(m.data.E, [](Index, Index) { return 0.0; });
  g.de = Vector::Zero(m.data.e.size());
  g.dM = on_pattern(m.data.M, [](Index, Index) { return 0.0; });
  g.dP = on_pattern(m.data.P, [](Index, Index) { return 0.0; });
  g.dq = Vector::Zero(m.n);
  g.dp = Vector::Zero(m.data.p.size());
  g.dtarget = Vector::Zero(m.data.p.size());
  if (m.ext_term()) m.ext_partials(g, dl_dx);
  const QpGradient b = m.qp.backward(dl_dx);
  SparseMatrix gH = b.dP;
  for (Index k = 0; k < gH.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(gH, k); it; ++it)
      it.valueRef() += (it.row() == it.col() ? 0.5 : 1.0) * x(it.row()) * x(it.col());
  Impl::accumulate(g, m.chain(gH, b.dq + x, 1.0, b.dG, b.dl));
  return g;
}

RelaxedLcpResult relaxed_lcp(const RelaxedLcpData& data, const RelaxedLcpSettings& settings,
                             const QpSettings& qp_settings) {
  RelaxedLcpSolver solver(settings, qp_settings);
  return solver.solve(data, true);
}

}  // namespace lcprelax::learn
