// The Stewart–Trinkle LCP contact model (contact_step.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace lcprelax {

// M is written column by column in CSC, rows sorted, from W's columns (no triplets and no
// sort): column r of W (a normal) gives M's column r; friction column nc + f gives β⁺_f's
// column and, negated, β⁻_f's. Within a column the rows of W map to [normals | β⁺ rows |
// β⁻ rows] in that order, then the γ rows follow. The entries, their values and the
// order of the sums (W, then compliance, then the contact block) are those of a triplet
// assembly (bench/lcp_assembly_reference.hpp; equal bits, tests/models_stewart_trinkle_matrix_test.cpp),
// which takes 2.5–4× longer on pile islands of 200 and 1,000 bodies (bench/results/lcp_assembly.txt).
StewartTrinkleLcp stewart_trinkle_lcp(const ContactSystem& s, const SparseMatrix& W, double dt) {
  if (const std::string e = normal_softness_error(s); !e.empty()) throw InputError("stewart_trinkle_lcp: " + e);
  const Index nc = s.num_contacts(), nf = s.num_friction(), n = nc + 3 * nf;
  if (W.rows() != nc + nf || W.cols() != nc + nf)
    throw InputError("stewart_trinkle_lcp: W must be (contacts + friction rows) square");
  if (s.mu.size() != nf) throw InputError("stewart_trinkle_lcp: mu must have one entry per friction row");
  for (Index f = 0; f < nf; ++f)
    if (s.friction_rows[f] < 0 || s.friction_rows[f] >= nc)
      throw InputError("stewart_trinkle_lcp: friction row " + std::to_string(f) + " names no contact");
  const Index bp = nc, bm = nc + nf, g = nc + 2 * nf;  // offsets of β⁺, β⁻, γ
  // Friction rows of each contact (their γ rows in a normal column), in increasing f.
  std::vector<Index> first(static_cast<std::size_t>(nc) + 1, 0), rows_of(static_cast<std::size_t>(nf));
  for (Index f = 0; f < nf; ++f) ++first[static_cast<std::size_t>(s.friction_rows[f]) + 1];
  for (Index c = 0; c < nc; ++c) first[static_cast<std::size_t>(c) + 1] += first[static_cast<std::size_t>(c)];
  {
    std::vector<Index> fill(first.begin(), first.end() - 1);
    for (Index f = 0; f < nf; ++f) rows_of[static_cast<std::size_t>(fill[static_cast<std::size_t>(s.friction_rows[f])]++)] = f;
  }
  const bool soft = s.compliance.size() > 0;
  StewartTrinkleLcp lcp;
  lcp.M.resize(n, n);
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
  std::vector<double> values;
  inner.reserve(static_cast<std::size_t>(4 * W.nonZeros() + 6 * nf + nc));
  values.reserve(inner.capacity());
  auto put = [&](Index row, double value) {
    inner.push_back(static_cast<int>(row));
    values.push_back(value);
  };
  // M's rows from W's column w, scaled by the column's sign sc; `diag` (or −1) is the
  // normal row whose entry gets the compliance added (inserted when W has no entry there).
  auto from_w = [&](Index w, double sc, Index diag) {
    bool diag_done = diag < 0;
    for (SparseMatrix::InnerIterator it(W, w); it; ++it) {
      if (it.row() >= nc) break;
      if (!diag_done && it.row() > diag) {
        put(diag, s.compliance(diag));
        diag_done = true;
      }
      double v = 1.0 * sc * it.value();
      if (it.row() == diag) {
        v += s.compliance(diag);
        diag_done = true;
      }
      put(it.row(), v);
    }
    if (!diag_done) put(diag, s.compliance(diag));
    for (const double sr : {1.0, -1.0})
      for (SparseMatrix::InnerIterator it(W, w); it; ++it)
        if (it.row() >= nc) put((sr > 0 ? bp : bm) + (it.row() - nc), sr * sc * it.value());
  };
  for (Index c = 0; c < nc; ++c) {
    from_w(c, 1.0, soft && s.compliance(c) != 0.0 ? c : -1);
    for (Index k = first[static_cast<std::size_t>(c)]; k < first[static_cast<std::size_t>(c) + 1]; ++k) {
      const Index f = rows_of[static_cast<std::size_t>(k)];
      put(g + f, s.mu(f));
    }
    outer[static_cast<std::size_t>(c) + 1] = static_cast<int>(inner.size());
  }
  for (Index f = 0; f < nf; ++f) {  // β⁺ columns
    from_w(nc + f, 1.0, -1);
    put(g + f, -1.0);
    outer[static_cast<std::size_t>(bp + f) + 1] = static_cast<int>(inner.size());
  }
  for (Index f = 0; f < nf; ++f) {  // β⁻ columns
    from_w(nc + f, -1.0, -1);
    put(g + f, -1.0);
    outer[static_cast<std::size_t>(bm + f) + 1] = static_cast<int>(inner.size());
  }
  for (Index f = 0; f < nf; ++f) {  // γ columns
    put(bp + f, 1.0);
    put(bm + f, 1.0);
    outer[static_cast<std::size_t>(g + f) + 1] = static_cast<int>(inner.size());
  }
  lcp.M.resizeNonZeros(static_cast<Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), lcp.M.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), lcp.M.innerIndexPtr());
  std::copy(values.begin(), values.end(), lcp.M.valuePtr());
  // The per-contact correction (world.hpp ContactLcpBlock): every entry stored, zeros too.
  std::vector<Index> block_index;
  if (s.lcp_block.enabled) {
    block_index = stewart_trinkle_contact_indices(s);
    std::vector<Triplet> t;
    for (Index c = 0; c < nc; ++c) {
      const Index* idx = &block_index[static_cast<std::size_t>(4 * c)];
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          if (idx[k] >= 0 && idx[l] >= 0) t.emplace_back(idx[k], idx[l], s.lcp_block.M(k, l));
    }
    SparseMatrix block(n, n);
    block.setFromTriplets(t.begin(), t.end());
    lcp.M = SparseMatrix(lcp.M + block);
  }
  lcp.M.makeCompressed();
  lcp.q = stewart_trinkle_q(s, dt);
  return lcp;
}

Vector stewart_trinkle_q(const ContactSystem& s, double dt) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), bp = nc, bm = nc + nf;
  Vector q = Vector::Zero(nc + 3 * nf);
  // Same expression as without softness (Eigen evaluates it as φ⁺/Δt, then += Jn v*): a rigid
  // system keeps its q bit for bit; the erp term (normal_gap_rate) is added only where set.
  q.head(nc) = s.Jn * s.v_star + s.phi.cwiseMax(0.0) / dt;
  if (s.erp.size() > 0 && (s.erp.array() != 0.0).any()) q.head(nc) += s.erp.cwiseProduct(s.phi.cwiseMin(0.0)) / dt;
  const Vector jt = s.Jt * s.v_star;
  q.segment(bp, nf) = jt;
  q.segment(bm, nf) = -jt;
  if (s.lcp_block.enabled) {
    const std::vector<Index> block_index = stewart_trinkle_contact_indices(s);
    for (std::size_t i = 0; i < block_index.size(); ++i)
      if (block_index[i] >= 0) q(block_index[i]) += s.lcp_block.q(static_cast<Index>(i % 4));
  }
  return q;
}

// J's columns written directly in CSC: per velocity column, the Jn rows, then the Jt rows at
// nc + f and negated at nc + nf + f (increasing rows); H is the matrix stewart_trinkle_lcp
// assembles from a zero W (its compliance, μ, ±1 and lcp_block entries).
LcpLiftedForm stewart_trinkle_lifted_form(const ContactSystem& s, double dt) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), n = nc + 3 * nf, m = s.num_dofs();
  if (s.Jn.rows() != nc || s.Jt.rows() != nf || s.Jn.cols() != m || s.Jt.cols() != m || s.minv.size() != m)
    throw InputError("stewart_trinkle_lifted_form: Jn, Jt and minv do not match the contacts, friction rows and 3·bodies");
  LcpLiftedForm f;
  f.H = stewart_trinkle_lcp(s, SparseMatrix(nc + nf, nc + nf), dt).M;
  f.d = s.minv;
  f.J.resize(n, m);
  f.J.resizeNonZeros(s.Jn.nonZeros() + 2 * s.Jt.nonZeros());
  int* outer = f.J.outerIndexPtr();
  int* inner = f.J.innerIndexPtr();
  double* values = f.J.valuePtr();
  int p = 0;
  for (Index k = 0; k < m; ++k) {
    outer[k] = p;
    for (SparseMatrix::InnerIterator it(s.Jn, k); it; ++it) inner[p] = static_cast<int>(it.row()), values[p++] = it.value();
    for (const double sign : {1.0, -1.0})
      for (SparseMatrix::InnerIterator it(s.Jt, k); it; ++it)
        inner[p] = static_cast<int>((sign > 0 ? nc : nc + nf) + it.row()), values[p++] = sign * it.value();
  }
  outer[m] = p;
  return f;
}

std::vector<Index> stewart_trinkle_contact_indices(const ContactSystem& s) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  std::vector<Index> idx(static_cast<std::size_t>(4 * nc), -1);
  for (Index c = 0; c < nc; ++c) idx[static_cast<std::size_t>(4 * c)] = c;
  for (Index f = 0; f < nf; ++f) {
    Index* i = &idx[static_cast<std::size_t>(4 * s.friction_rows[f])];
    i[1] = nc + f, i[2] = nc + nf + f, i[3] = nc + 2 * nf + f;
  }
  return idx;
}

namespace {

// Deterministic pseudo-random u ∈ [½, 1) for row key i and pattern `seed` (splitmix64):
// distinct, and the same for every run and thread count.
double perturbation_weight(std::uint64_t i, int seed) {
  std::uint64_t x = i + 0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(seed + 1);
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  x ^= x >> 31;
  return 0.5 + 0.5 * static_cast<double>(x >> 11) * 0x1.0p-53;
}

}  // namespace

Vector lcp_perturbation_pattern(const ContactSystem& s, int seed) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const std::vector<std::uint64_t>& ids = s.ids;
  if (!ids.empty() && static_cast<Index>(ids.size()) != nc)
    throw InputError("lcp model: ContactSystem::ids has " + std::to_string(ids.size()) + " entries for " +
                     std::to_string(nc) + " contacts (one per contact, or none)");
  if (seed < 0) throw InputError("lcp_perturbation_pattern: seed must be >= 0");
  // Row key: 4·(contact key) + kind (0 λn, 1 β⁺, 2 β⁻, 3 γ); unsigned arithmetic wraps.
  auto key = [&](Index c) {
    return 4 * (ids.empty() ? static_cast<std::uint64_t>(c) : ids[static_cast<std::size_t>(c)]);
  };
  Vector u(nc + 3 * nf);
  for (Index c = 0; c < nc; ++c) u(c) = perturbation_weight(key(c), seed);
  for (Index f = 0; f < nf; ++f) {
    const std::uint64_t k = key(s.friction_rows[f]);
    u(nc + f) = perturbation_weight(k + 1, seed);
    u(nc + nf + f) = perturbation_weight(k + 2, seed);
    u(nc + 2 * nf + f) = perturbation_weight(k + 3, seed);
  }
  return u;
}

ContactSolution solve_lcp_model(const ContactSystem& s, double dt, const LemkeSettings& settings,
                                const std::vector<bool>& warm,
                                const std::shared_ptr<LemkeSharedFactorization>& warm_factorization,
                                bool accept_perturbed, bool warm_from_regularized) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  // M is formed only when step 1 (the warm basis, on the lifted form) does not solve.
  StewartTrinkleLcpSource lcp(s, dt);
  const LcpLiftedForm lifted = stewart_trinkle_lifted_form(s, dt);
  LcpModelAttempts a;
  run_lcp_model_attempts(s, lcp, settings, warm, a, /*skip_exact_cold=*/false, warm_factorization, accept_perturbed,
                         &lifted, warm_from_regularized);
  const LcpResult& r = a.used->result();
  ContactSolution out;
  out.status = a.status;
  out.message = a.message;
  out.work = a.pivots;
  out.z_basic = r.z_basic;
  out.warm_started = a.warm_started;
  out.perturbed = has_solution(a.status) && a.source == LcpModelSource::perturbed;
  out.regularized = has_solution(a.status) && a.source == LcpModelSource::regularized;
  if (!has_solution(out.status)) {
    out.residual = r.info.complementarity;
    return out;
  }
  // Residual on the unperturbed LCP (a perturbed solution's is about δ·‖q‖∞ there). M not
  // formed: step 1 solved (q itself), and Lemke's own residual, from w = J(d∘Jᵀz) + Hz + q, is it.
  out.residual = lcp.formed() ? stewart_trinkle_residual(lcp.lcp(), r.z) : r.info.complementarity;
  out.lambda_n = r.z.head(nc);
  out.lambda_t = r.z.segment(nc, nf) - r.z.segment(nc + nf, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
