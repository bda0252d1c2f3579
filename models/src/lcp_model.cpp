// The Stewart–Trinkle LCP contact model (contact_step.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <algorithm>
#include <cstdint>
#include <deque>
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

// max|min(z, Mz + q)|, 0 for an empty LCP.
double lcp_residual(const StewartTrinkleLcp& lcp, const Vector& z) {
  if (z.size() == 0) return 0.0;
  const Vector w = lcp.M * z + lcp.q;
  return z.cwiseMin(w).cwiseAbs().maxCoeff();
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
  const Index n = lcp.q.size();
  // A warm basis without a basic z (every contact new, or the first step) is the all-w
  // basis of the cold start: its crash path would repeat step 2's first cold path exactly.
  const bool has_warm =
      static_cast<Index>(warm.size()) == n && std::find(warm.begin(), warm.end(), true) != warm.end();
  // u of each seed (lcp_perturbation_pattern), built on first use: a step that the warm
  // basis solves needs none. The identities are checked up front all the same.
  std::vector<Vector> patterns(static_cast<std::size_t>(kLcpPerturbationSeeds));
  auto pattern = [&](int seed) -> const Vector& {
    Vector& u = patterns[static_cast<std::size_t>(seed)];
    if (u.size() == 0 && n > 0) u = lcp_perturbation_pattern(s, seed);
    return u;
  };
  if (!s.ids.empty() && static_cast<Index>(s.ids.size()) != nc) (void)lcp_perturbation_pattern(s, 0);  // throws
  // Attempts, cheapest first (contact_step.hpp, numbered as there). Lemke's own retries only in the last one;
  // a solver with max_pivots = 1 tries its warm basis only (a cold start stops at once).
  LemkeSettings plain = settings;
  plain.crash_flip_rounds = 0;  // block principal pivoting of crash bases: not measured on piles
  plain.covering_retries = 0;
  plain.regularization_retries = 0;
  LemkeSettings exact = plain;  // attempt 1 fails fast (see kLcpExactPivotsPerUnknown)
  const long exact_cap = kLcpExactPivotsPerUnknown * (n + 1);
  exact.max_pivots = plain.max_pivots > 0 ? std::min(plain.max_pivots, exact_cap) : exact_cap;
  LemkeSettings polish = plain;  // from the perturbed solution's basis: a short crash path
  polish.crash_start = true;
  polish.max_pivots = std::max<long>(1, n / 10);
  polish.crash_cold_fallback = false;  // a cold path capped at n/10 cannot finish (≈ n pivots)
  LemkeSettings warm_only = plain;  // the warm basis if it is feasible; a cold start stops at once
  warm_only.max_pivots = 1;
  // Kept alive: r and inexact point into the results of earlier attempts. A deque never
  // moves its elements on emplace_back, so adding an attempt cannot leave them dangling.
  std::deque<LemkeSolver> solvers;
  long pivots = 0;
  const LcpResult* r = nullptr;
  auto attempt_on = [&](const SparseMatrix& M, const LemkeSettings& ls, const Vector& q,
                        const std::vector<bool>* basis) -> const LcpResult& {
    solvers.emplace_back(ls);
    solvers.back().setup(M, q);
    if (basis) solvers.back().warm_start(*basis);
    const LcpResult& res = solvers.back().solve();
    pivots += res.info.pivots;
    return res;
  };
  auto attempt = [&](const LemkeSettings& ls, const Vector& q, const std::vector<bool>* basis) -> const LcpResult& {
    return attempt_on(lcp.M, ls, q, basis);
  };
  auto solved = [](const LcpResult* x) { return x && has_solution(x->info.status); };
  auto perturbed = [&](double delta, int seed) {
    return Vector(lcp.q + delta * pattern(seed));
  };
  // A solution of a perturbed LCP (q + δu, or M + εI: seed < 0), polished on (M, q) from
  // its basis by a short crash path with the covering vector B·1, and for q + δu where that
  // fails along u (the homotopy from q + θu back to q): r when a polish solves the LCP, else
  // kept as the inexact fallback.
  const LcpResult* inexact = nullptr;
  auto polish_on_q = [&](const LcpResult& rp, int seed) {
    const LcpResult* polished = &attempt(polish, lcp.q, &rp.z_basic);
    if (!solved(polished) && seed >= 0) {  // the homotopy along the perturbation (lcp_types.hpp)
      LemkeSettings along = polish;
      along.crash_covering_from_basis = false;
      along.covering = pattern(seed);
      polished = &attempt(along, lcp.q, &rp.z_basic);
    }
    if (solved(polished)) r = polished;
    else inexact = &rp;
  };
  // 1. The warm basis on q where it is feasible.
  if (has_warm) r = &attempt(warm_only, lcp.q, &warm);
  // 1b. A crash path on the perturbed q from the warm basis, at most
  //    kLcpWarmCrashPivotsPerUnknown pivots per unknown, polished on q. Its perturbed q is
  //    step 2's first one: when the polish fails, its solution is kept as the inexact
  //    fallback and step 2 does not solve the same perturbed LCP again from the all-w basis
  //    (it would end at the same basis and fail the same polish).
  double delta = kLcpPerturbation * lcp.q.lpNorm<Eigen::Infinity>();
  if (has_warm && !solved(r)) {
    LemkeSettings warm_crash = plain;
    warm_crash.crash_start = true;
    warm_crash.crash_cold_fallback = false;  // step 2 is the cold start
    warm_crash.max_pivots = 1 + static_cast<long>(kLcpWarmCrashPivotsPerUnknown * static_cast<double>(n));
    const LcpResult& rc = attempt(warm_crash, perturbed(delta, 0), &warm);
    if (solved(&rc)) polish_on_q(rc, 0);
  }
  // 2. Perturbed q + δu from the all-w basis (capped as step 3), polished on q.
  LemkeSettings cold = plain;
  cold.max_pivots = exact.max_pivots;
  for (int seed = 0; seed < kLcpPerturbationSeeds && !solved(r) && !inexact; ++seed, delta *= 10.0) {
    const LcpResult& rp = attempt(cold, perturbed(delta, seed), nullptr);
    if (solved(&rp)) polish_on_q(rp, seed);
  }
  // 3. Exact from the all-w basis (degenerate piles often end it on a ray or a singular
  //    basis, or cycle: capped), else the perturbed solution.
  bool from_perturbed = false, from_regularized = false;
  if (!solved(r)) r = &attempt(exact, lcp.q, nullptr);
  if (!solved(r) && inexact) {
    r = inexact;
    from_perturbed = true;
  }
  // 4. No perturbed solution: M + εI from the all-w basis (strictly copositive, so its
  //    LCP always has a solution and Lemke's path ends at one in exact arithmetic),
  //    polished on (M, q), else the regularized solution (solved_inaccurate).
  if (!solved(r)) {
    SparseMatrix Me = lcp.M;
    SparseMatrix I(n, n);
    I.setIdentity();
    const double m_norm = (lcp.M.cwiseAbs() * Vector::Ones(n)).maxCoeff();  // ‖M‖∞ (n > 0 here)
    Me += (kLcpRegularization * std::max(1.0, m_norm)) * I;
    LemkeSettings reg = plain;
    const long reg_cap = 1 + static_cast<long>(kLcpRegularizedPivotsPerUnknown * static_cast<double>(n));
    reg.max_pivots = plain.max_pivots > 0 ? std::min(plain.max_pivots, reg_cap) : reg_cap;
    const LcpResult& rr = attempt_on(Me, reg, lcp.q, nullptr);
    if (solved(&rr)) {
      polish_on_q(rr, -1);  // sets r when the polish solves (M, q)
      if (!solved(r) && lcp_residual(lcp, rr.z) <= kLcpRegularizedResidual * lcp.q.lpNorm<Eigen::Infinity>()) {
        r = &rr;
        from_regularized = true;
      }
    }
  }
  // 5. The caller's settings (covering-vector and M + εI retries), each solve capped as
  //    step 3 unless the caller set max_pivots (Lemke's own default of 50 per unknown, with
  //    its 4 retries, would allow about 250 pivots per unknown in this attempt alone).
  LemkeSettings last = settings;
  if (last.max_pivots == 0) last.max_pivots = exact_cap;
  if (!solved(r)) r = &attempt(last, lcp.q, nullptr);

  ContactSolution out;
  const bool inaccurate = from_perturbed || from_regularized;
  out.status = !solved(r) ? ContactStatus::failed : inaccurate ? ContactStatus::solved_inaccurate : ContactStatus::solved;
  out.message = !solved(r)        ? "lcp: " + r->info.message
                : from_perturbed   ? std::string("solved on a perturbed q (polishing on q failed)")
                : from_regularized ? std::string("solved on M + εI (polishing on M failed)")
                                   : r->info.message;
  out.work = pivots;
  out.z_basic = r->z_basic;
  out.warm_started = pivots == 0 && r->info.warm_started;  // attempt 1 from its warm basis
  if (!has_solution(out.status)) {
    out.residual = r->info.complementarity;
    return out;
  }
  // Residual on the unperturbed LCP (a perturbed solution's is about δ·‖q‖∞ there).
  out.residual = lcp_residual(lcp, r->z);
  out.lambda_n = r->z.head(nc);
  out.lambda_t = r->z.segment(nc, nf) - r->z.segment(nc + nf, nf);
  const Vector impulse = s.Jn.transpose() * out.lambda_n + s.Jt.transpose() * out.lambda_t;
  out.v_next = s.v_star + s.minv.cwiseProduct(impulse);
  return out;
}

}  // namespace lcprelax
