// The Stewart–Trinkle LCP contact model (contact_step.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_step.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <cstdint>
#include <string>

namespace lcprelax {

StewartTrinkleLcp stewart_trinkle_lcp(const ContactSystem& s, const SparseMatrix& W, double dt) {
  if (const std::string e = normal_softness_error(s); !e.empty()) throw InputError("stewart_trinkle_lcp: " + e);
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const Index bp = nc, bm = nc + nf, g = nc + 2 * nf;  // offsets of β⁺, β⁻, γ
  std::vector<Triplet> t;
  t.reserve(static_cast<std::size_t>(4 * W.nonZeros() + 6 * nf));
  // W row/column r of J-space maps to LCP rows: normal r → (r, +); friction f → (β⁺_f, +), (β⁻_f, −).
  auto expand = [&](Index r, auto&& emit) {
    if (r < nc) {
      emit(r, 1.0);
    } else {
      emit(bp + (r - nc), 1.0);
      emit(bm + (r - nc), -1.0);
    }
  };
  for (Index c = 0; c < W.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(W, c); it; ++it)
      expand(it.row(), [&](Index R, double sr) {
        expand(c, [&](Index C, double sc) { t.emplace_back(R, C, sr * sc * it.value()); });
      });
  for (Index c = 0; c < s.compliance.size(); ++c)  // the pairs' normal compliance (world.hpp FrictionTable)
    if (s.compliance(c) != 0.0) t.emplace_back(c, c, s.compliance(c));
  for (Index f = 0; f < nf; ++f) {
    t.emplace_back(bp + f, g + f, 1.0);
    t.emplace_back(bm + f, g + f, 1.0);
    t.emplace_back(g + f, s.friction_rows[f], s.mu(f));
    t.emplace_back(g + f, bp + f, -1.0);
    t.emplace_back(g + f, bm + f, -1.0);
  }
  // The per-contact correction (world.hpp ContactLcpBlock): every entry stored, zeros too.
  std::vector<Index> block_index;
  if (s.lcp_block.enabled) {
    block_index = stewart_trinkle_contact_indices(s);
    for (Index c = 0; c < nc; ++c) {
      const Index* idx = &block_index[static_cast<std::size_t>(4 * c)];
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 4; ++l)
          if (idx[k] >= 0 && idx[l] >= 0) t.emplace_back(idx[k], idx[l], s.lcp_block.M(k, l));
    }
  }
  StewartTrinkleLcp lcp;
  lcp.M.resize(nc + 3 * nf, nc + 3 * nf);
  lcp.M.setFromTriplets(t.begin(), t.end());
  lcp.M.makeCompressed();
  lcp.q = Vector::Zero(nc + 3 * nf);
  // Same expression as without softness (Eigen evaluates it as φ⁺/Δt, then += Jn v*): a rigid
  // system keeps its q bit for bit; the erp term (normal_gap_rate) is added only where set.
  lcp.q.head(nc) = s.Jn * s.v_star + s.phi.cwiseMax(0.0) / dt;
  if (s.erp.size() > 0 && (s.erp.array() != 0.0).any())
    lcp.q.head(nc) += s.erp.cwiseProduct(s.phi.cwiseMin(0.0)) / dt;
  const Vector jt = s.Jt * s.v_star;
  lcp.q.segment(bp, nf) = jt;
  lcp.q.segment(bm, nf) = -jt;
  for (std::size_t i = 0; i < block_index.size(); ++i)
    if (block_index[i] >= 0) lcp.q(block_index[i]) += s.lcp_block.q(static_cast<Index>(i % 4));
  return lcp;
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
                                const std::vector<bool>& warm) {
  const Index nc = s.num_contacts(), nf = s.num_friction();
  const StewartTrinkleLcp lcp = stewart_trinkle_lcp(s, delassus(s), dt);
  LcpModelAttempts a;
  run_lcp_model_attempts(s, lcp, settings, warm, a);
  const LcpResult& r = a.used->result();
  ContactSolution out;
  out.status = a.status;
  out.message = a.message;
  out.work = a.pivots;
  out.z_basic = r.z_basic;
  out.warm_started = a.warm_started;
  if (!has_solution(out.status)) {
    out.residual = r.info.complementarity;
    return out;
  }
  // Residual on the unperturbed LCP (a perturbed solution's is about δ·‖q‖∞ there).
  out.residual = stewart_trinkle_residual(lcp, r.z);
  out.lambda_n = r.z.head(nc);
  out.lambda_t = r.z.segment(nc, nf) - r.z.segment(nc + nf, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
