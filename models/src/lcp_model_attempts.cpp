// The lcp model's attempts on one island's LCP (lcp_model_attempts.hpp; the steps, their
// caps and why: contact_step.hpp).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/models/contact_system.hpp>
#include <lcprelax/models/lcp_model_attempts.hpp>

#include <algorithm>

namespace lcprelax {

Index reset_warm_contacts_on_ray(const ContactSystem& s, const std::vector<Index>& trace,
                                 std::vector<signed char>& level, std::vector<bool>& warm) {
  const Index nc = s.num_contacts(), nf = s.num_friction(), n = nc + 3 * nf;
  if (static_cast<Index>(level.size()) != nc || static_cast<Index>(warm.size()) != n)
    throw InputError("reset_warm_contacts_on_ray: level needs nc and warm nc + 3nf entries");
  // The contact of LCP row i (z = [λn (nc), β⁺, β⁻, γ (nf each)]).
  auto contact_of = [&](Index i) { return i < nc ? i : static_cast<Index>(s.friction_rows[(i - nc) % nf]); };
  std::vector<char> touched(static_cast<std::size_t>(nc), 0);
  auto mark = [&](Index var) {
    if (var >= 0 && var < 2 * n) touched[static_cast<std::size_t>(contact_of(var % n))] = 1;
  };
  for (Index v : trace) mark(v);
  if (!trace.empty() && trace.back() < 2 * n) mark(trace.back() < n ? trace.back() + n : trace.back() - n);
  Index raised = 0;
  for (Index c = 0; c < nc; ++c)
    if (touched[static_cast<std::size_t>(c)] && level[static_cast<std::size_t>(c)] < 2) {
      ++level[static_cast<std::size_t>(c)];
      ++raised;
      if (level[static_cast<std::size_t>(c)] == 2) warm[static_cast<std::size_t>(c)] = false;
    }
  for (Index f = 0; f < nf; ++f)
    if (level[static_cast<std::size_t>(s.friction_rows[static_cast<std::size_t>(f)])] > 0)
      for (Index k = 0; k < 3; ++k) warm[static_cast<std::size_t>(nc + k * nf + f)] = false;
  return raised;
}

double stewart_trinkle_residual(const StewartTrinkleLcp& lcp, const Vector& z) {
  if (z.size() == 0) return 0.0;
  const Vector w = lcp.M * z + lcp.q;
  return z.cwiseMin(w).cwiseAbs().maxCoeff();
}

StewartTrinkleLcpSource::StewartTrinkleLcpSource(const ContactSystem& s, double dt)
    : s_(&s), dt_(dt), q_(stewart_trinkle_q(s, dt)) {}

const StewartTrinkleLcp& StewartTrinkleLcpSource::lcp() {
  if (!given_) {
    own_ = stewart_trinkle_lcp(*s_, delassus(*s_), dt_);
    given_ = &own_;
  }
  return *given_;
}

void run_lcp_model_attempts(const ContactSystem& s, const StewartTrinkleLcp& lcp, const LemkeSettings& settings,
                            const std::vector<bool>& warm, LcpModelAttempts& out, bool skip_exact_cold,
                            const std::shared_ptr<LemkeSharedFactorization>& warm_factorization,
                            bool accept_perturbed, const LcpLiftedForm* lifted, bool warm_from_regularized) {
  StewartTrinkleLcpSource source(lcp);
  run_lcp_model_attempts(s, source, settings, warm, out, skip_exact_cold, warm_factorization, accept_perturbed, lifted,
                         warm_from_regularized);
}

void run_lcp_model_attempts(const ContactSystem& s, StewartTrinkleLcpSource& lcp, const LemkeSettings& settings,
                            const std::vector<bool>& warm, LcpModelAttempts& out, bool skip_exact_cold,
                            const std::shared_ptr<LemkeSharedFactorization>& warm_factorization,
                            bool accept_perturbed, const LcpLiftedForm* lifted, bool warm_from_regularized) {
  out.solvers.clear();
  out.used = nullptr;
  out.source = LcpModelSource::exact;
  out.status = ContactStatus::unsolved;
  out.message.clear();
  out.pivots = 0;
  out.warm_started = false;
  const Vector& q = lcp.q();
  const Index nc = s.num_contacts(), n = q.size();
  if ((lcp.formed() && (lcp.lcp().M.rows() != n || lcp.lcp().M.cols() != n)) || n != nc + 3 * s.num_friction())
    throw InputError("lcp model: the LCP's size does not match the contact system's nc + 3nf");
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
  plain.crash_flip_rounds = 0;  // block principal pivoting of the warm basis: no pivot saved on a 300-body pile
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
  // r and inexact point into out.solvers (a deque never relocates its elements).
  const LemkeSolver* r = nullptr;
  // `lu`: the factorization to factorize in (step 1's warm_factorization), or none.
  // `trace`: the first trace_pivots pivots are recorded there (step 1b's restarts).
  // `form`: M's lifted form (null: none); M null: the lifted form alone (setup(form, q)).
  auto attempt_on = [&](const SparseMatrix* M, const LcpLiftedForm* form, const LemkeSettings& ls, const Vector& rhs,
                        const std::vector<bool>* basis, const std::shared_ptr<LemkeSharedFactorization>& lu = nullptr,
                        std::vector<Index>* trace = nullptr, long trace_pivots = -1) -> const LemkeSolver& {
    LemkeSolver& solver = out.solvers.emplace_back(ls);
    if (lu) solver.share_factorization(lu);
    if (trace) solver.set_pivot_trace(trace, trace_pivots);
    if (!M) solver.setup(*form, rhs);
    else if (form) solver.setup(*M, rhs, *form);
    else solver.setup(*M, rhs);
    if (basis) solver.warm_start(*basis);
    out.pivots += solver.solve().info.pivots;
    return solver;
  };
  auto attempt = [&](const LemkeSettings& ls, const Vector& rhs, const std::vector<bool>* basis,
                     const std::shared_ptr<LemkeSharedFactorization>& lu = nullptr, std::vector<Index>* trace = nullptr,
                     long trace_pivots = -1) -> const LemkeSolver& {
    return attempt_on(&lcp.lcp().M, lifted, ls, rhs, basis, lu, trace, trace_pivots);
  };
  auto solved = [](const LemkeSolver* x) { return x && has_solution(x->result().info.status); };
  auto perturbed = [&](double delta, int seed) { return Vector(q + delta * pattern(seed)); };
  // A solution of a perturbed LCP (q + δu, or M + εI: seed < 0), polished on (M, q) from
  // its basis by a short crash path with the covering vector B·1, and for q + δu where that
  // fails along u (the homotopy from q + θu back to q): r when a polish solves the LCP, else
  // kept as the inexact fallback.
  const LemkeSolver* inexact = nullptr;
  // The polished solver when a polish solves (M, q), else nullptr.
  auto polished_on_q = [&](const LemkeSolver& rp, int seed) -> const LemkeSolver* {
    const LemkeSolver* polished = &attempt(polish, q, &rp.result().z_basic);
    if (!solved(polished) && seed >= 0) {  // the homotopy along the perturbation (lcp_types.hpp)
      LemkeSettings along = polish;
      along.crash_covering_from_basis = false;
      along.covering = pattern(seed);
      polished = &attempt(along, q, &rp.result().z_basic);
    }
    return solved(polished) ? polished : nullptr;
  };
  auto polish_on_q = [&](const LemkeSolver& rp, int seed) {
    if (const LemkeSolver* polished = polished_on_q(rp, seed)) r = polished;
    else inexact = &rp;
  };
  // A regularized island between its exact retries (warm_from_regularized with
  // accept_perturbed): step 1 is skipped, as its basis is one of M + εI (on a settled
  // 1,000-body pile step 1 never solved from it), and step 1c starts in warm_factorization
  // instead, so that its symbolic analysis is reused while the basis pattern repeats.
  const bool regularized_rest = has_warm && warm_from_regularized && accept_perturbed;
  // 1. The warm basis on q where it is feasible (on the lifted form alone while M is not formed).
  if (!regularized_rest && has_warm && lifted && !lcp.formed())
    r = &attempt_on(nullptr, lifted, warm_only, q, &warm, warm_factorization);
  else if (!regularized_rest && has_warm)
    r = &attempt(warm_only, q, &warm, warm_factorization);
  // 1b. A crash path on the perturbed q from the warm basis, at most
  //    kLcpWarmCrashPivotsPerUnknown pivots per unknown, polished on q. Its perturbed q is
  //    step 2's first one: when the polish fails, its solution is kept as the inexact
  //    fallback and step 2 does not solve the same perturbed LCP again from the all-w basis
  //    (it would end at the same basis and fail the same polish).
  double delta = kLcpPerturbation * q.lpNorm<Eigen::Infinity>();
  // The crash path from the warm basis on (M, rhs) (M null: lcp's M), capped at
  // kLcpWarmCrashPivotsPerUnknown pivots per unknown. An early ray: the contacts its pivots
  // touched are taken back in the warm basis and the path runs again (kLcpWarmRayRestarts;
  // reset_warm_contacts_on_ray). Returns the last path's solver.
  LemkeSettings warm_crash = plain;
  warm_crash.crash_start = true;
  warm_crash.crash_cold_fallback = false;  // the cold starts are later steps
  warm_crash.max_pivots = 1 + static_cast<long>(kLcpWarmCrashPivotsPerUnknown * static_cast<double>(n));
  const long ray_pivots = static_cast<long>(kLcpWarmRayPivotsPerUnknown * static_cast<double>(n));
  std::vector<Index> trace;
  auto warm_crash_path = [&](const SparseMatrix* M, const LcpLiftedForm* form, const Vector& rhs,
                             const std::shared_ptr<LemkeSharedFactorization>& lu = nullptr) {
    if (!M) M = &lcp.lcp().M;
    trace.clear();
    trace.reserve(static_cast<std::size_t>(2 * ray_pivots + 2));
    std::vector<bool> start = warm;
    std::vector<signed char> level;
    const LemkeSolver* rc = &attempt_on(M, form, warm_crash, rhs, &start, lu, &trace, ray_pivots);
    long rayed = 0;  // pivots of the paths that ended on an early ray
    for (int k = 0;; ++k) {
      const LcpInfo& info = rc->result().info;
      if (info.status != LcpStatus::ray_termination || info.pivots > ray_pivots) break;
      rayed += info.pivots;
      if (!lcp_warm_ray_restart_allowed(k, rayed, n)) break;
      if (level.empty()) level.assign(static_cast<std::size_t>(nc), 0);
      if (reset_warm_contacts_on_ray(s, trace, level, start) == 0) break;
      if (std::find(start.begin(), start.end(), true) == start.end()) break;  // all-w: a cold start
      trace.clear();
      rc = &attempt_on(M, form, warm_crash, rhs, &start, nullptr, &trace, ray_pivots);
    }
    return rc;
  };
  // M + εI (and its lifted form, εI added to H), built on first use: steps 1c and 4.
  SparseMatrix Me;
  LcpLiftedForm lifted_e;
  auto regularized = [&]() -> const SparseMatrix& {
    if (Me.rows() == n) return Me;
    const SparseMatrix& M = lcp.lcp().M;
    Me = M;
    SparseMatrix I(n, n);
    I.setIdentity();
    const double m_norm = (M.cwiseAbs() * Vector::Ones(n)).maxCoeff();  // ‖M‖∞ (n > 0 here)
    const double eps = kLcpRegularization * std::max(1.0, m_norm);
    Me += eps * I;
    if (lifted) {
      lifted_e = *lifted;
      lifted_e.H += eps * I;
    }
    return Me;
  };
  // A solution of M + εI that no polish turned into one of (M, q), kept when its residual
  // on (M, q) is small enough (source regularized).
  auto regularized_answer = [&](const LemkeSolver& rr) {
    return stewart_trinkle_residual(lcp.lcp(), rr.result().z) <= kLcpRegularizedResidual * q.lpNorm<Eigen::Infinity>();
  };
  const LemkeSolver* regularized_fallback = nullptr;  // step 1c's
  // 1c. M + εI from the warm basis: the crash path of step 1b (with its ray restarts) on
  //     M + εI, then as step 4 (polish on (M, q), else the regularized fallback). First, before
  //     step 1b, for a warm basis that solved M + εI (or belongs to a failed step): such a
  //     basis is often singular in M (a settled pile loads more contacts than its bodies have
  //     degrees of freedom), or near it, so step 1b cannot start from it or wanders from it
  //     (a 1,000-body pile: 61,101 pivots to its cap, a refactorization every 3, 240 s),
  //     while on M + εI, the LCP it solved, it is a short path from this step's solution.
  //     Else last, when every other attempt failed.
  //     With accept_perturbed (an island whose last answers were inexact, between the steps
  //     where lcp_retry_exact runs every attempt) the polish is skipped, as step 1b's is: on
  //     a settled 1,000-body pile it failed on every such step ("crash basis is singular")
  //     and took two thirds of a resting step's solve time (48 of 74 ms).
  bool warm_regularized_tried = false;
  auto warm_regularized = [&] {
    warm_regularized_tried = true;
    const LemkeSolver* rr = warm_crash_path(&regularized(), lifted ? &lifted_e : nullptr, q,
                                            regularized_rest ? warm_factorization : nullptr);
    if (!solved(rr)) return;
    if (const LemkeSolver* polished = accept_perturbed ? nullptr : polished_on_q(*rr, -1)) r = polished;
    else if (regularized_answer(*rr)) regularized_fallback = rr;
  };
  if (has_warm && warm_from_regularized && !solved(r)) warm_regularized();
  // 1b (after 1c where 1c runs first).
  if (has_warm && !solved(r) && !regularized_fallback) {
    const LemkeSolver* rc = warm_crash_path(nullptr, lifted, perturbed(delta, 0));
    if (solved(rc) && accept_perturbed)
      inexact = rc;  // kept as it is: steps 2 and 3 are skipped below
    else if (solved(rc))
      polish_on_q(*rc, 0);
  }
  // 2. Perturbed q + δu from the all-w basis (capped as step 3), polished on q. Skipped
  //    after step 1b's or 1c's inexact answer (as step 1b's: its paths would end there too).
  LemkeSettings cold = plain;
  cold.max_pivots = exact.max_pivots;
  for (int seed = 0; seed < kLcpPerturbationSeeds && !solved(r) && !inexact && !regularized_fallback;
       ++seed, delta *= 10.0) {
    const LemkeSolver& rp = attempt(cold, perturbed(delta, seed), nullptr);
    if (solved(&rp)) polish_on_q(rp, seed);
    // A path that ran to its cap ends step 2: a larger δ breaks ties and turns rays, but does
    // not shorten a long path (on 1,000-body drops the next seeds ran to the same cap).
    else if (rp.result().info.status == LcpStatus::pivot_limit) break;
  }
  // 3. Exact from the all-w basis (degenerate piles often end it on a ray or a singular
  //    basis, or cycle: capped), else the perturbed solution. Not run at the caller's
  //    request when there is a perturbed solution (skip_exact_cold, accept_perturbed).
  //    On an exact retry of an island whose answer step 1c regularized, with the caller's
  //    covering-vector retries (Lemke's own: each path capped alike).
  if (!solved(r) && !((skip_exact_cold || accept_perturbed) && (inexact || regularized_fallback))) {
    LemkeSettings exact_retry = exact;
    if (regularized_fallback) exact_retry.covering_retries = settings.covering_retries;
    r = &attempt(exact_retry, q, nullptr);
  }
  if (!solved(r) && inexact) {
    r = inexact;
    out.source = LcpModelSource::perturbed;
  }
  if (!solved(r) && regularized_fallback) {
    r = regularized_fallback;
    out.source = LcpModelSource::regularized;
  }
  // 4. No perturbed solution: M + εI from the all-w basis (strictly copositive, so its
  //    LCP always has a solution and Lemke's path ends at one in exact arithmetic),
  //    polished on (M, q), else the regularized solution (solved_inaccurate).
  if (!solved(r)) {
    LemkeSettings reg = plain;
    const long reg_cap = 1 + static_cast<long>(kLcpRegularizedPivotsPerUnknown * static_cast<double>(n));
    reg.max_pivots = plain.max_pivots > 0 ? std::min(plain.max_pivots, reg_cap) : reg_cap;
    const LemkeSolver& rr = attempt_on(&regularized(), lifted ? &lifted_e : nullptr, reg, q, nullptr);
    if (solved(&rr)) {
      if (const LemkeSolver* polished = polished_on_q(rr, -1)) r = polished;
      else if (regularized_answer(rr)) {
        r = &rr;
        out.source = LcpModelSource::regularized;
      }
    }
  }
  // 5. The caller's settings (covering-vector and M + εI retries), each solve capped as
  //    step 3 unless the caller set max_pivots (Lemke's own default of 50 per unknown, with
  //    its 4 retries, would allow about 250 pivots per unknown in this attempt alone).
  LemkeSettings last = settings;
  if (last.max_pivots == 0) last.max_pivots = exact_cap;
  if (!solved(r)) r = &attempt(last, q, nullptr);
  // 1c as the last resort (not run early).
  if (!solved(r) && has_warm && !warm_regularized_tried) {
    const LemkeSolver* failed = r;
    warm_regularized();
    if (!solved(r) && regularized_fallback) {
      r = regularized_fallback;
      out.source = LcpModelSource::regularized;
    }
    if (!solved(r)) r = failed;  // the failure reported is step 5's
  }

  out.used = r;
  const LcpInfo& info = r->result().info;
  const bool inaccurate = out.source != LcpModelSource::exact;
  out.status = !solved(r) ? ContactStatus::failed : inaccurate ? ContactStatus::solved_inaccurate : ContactStatus::solved;
  out.message = !solved(r) ? "lcp: " + info.message
                : out.source == LcpModelSource::perturbed   ? std::string("solved on a perturbed q (polishing on q failed)")
                : out.source == LcpModelSource::regularized ? std::string("solved on M + εI (polishing on M failed)")
                                                            : info.message;
  out.warm_started = out.pivots == 0 && info.warm_started;  // attempt 1 from its warm basis
}

}  // namespace lcprelax
