#pragma once
// The attempts of the lcp model on one island's Stewart–Trinkle LCP (steps 1–6 of
// contact_step.hpp, cheapest first, each capped), with every LemkeSolver kept alive, so
// that the one whose solution is the answer can differentiate it (LemkeSolver::backward).
// solve_lcp_model (the simulator) and the hard loss (learn/step_loss_hard.hpp) both run
// them: a step that the simulator solves, the hard loss solves with the same basis.
//
// Which LCP `used` solved (LcpModelAttempts::source):
//   exact        (M, q): status solved, residual at Lemke's tolerance;
//   perturbed    (M, q + δu), step 3's fallback: status solved_inaccurate;
//   regularized  (M + εI, q), step 4's fallback: status solved_inaccurate.
// used->backward() differentiates that LCP with δu and ε held fixed.
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/contact_step.hpp>

#include <deque>
#include <memory>
#include <string>
#include <vector>

namespace lcprelax {

enum class LcpModelSource { exact, perturbed, regularized };

struct LcpModelAttempts {
  std::deque<LemkeSolver> solvers;     ///< every attempt in order (a deque: never relocated)
  const LemkeSolver* used = nullptr;   ///< the answer's solver (the last attempt when none solved)
  LcpModelSource source = LcpModelSource::exact;
  ContactStatus status = ContactStatus::unsolved;
  std::string message;                 ///< Lemke's message, or why the answer is inaccurate
  long pivots = 0;                     ///< summed over the attempts
  bool warm_started = false;           ///< step 1: the warm basis solved it in zero pivots

  LcpModelAttempts() = default;
  LcpModelAttempts(const LcpModelAttempts&) = delete;  // `used` points into `solvers`
  LcpModelAttempts& operator=(const LcpModelAttempts&) = delete;
};

/// An island's Stewart–Trinkle LCP for run_lcp_model_attempts: q, and M either given or
/// formed on first use (stewart_trinkle_lcp(s, delassus(s), dt)). With M not yet formed and
/// a lifted form given, step 1 (the warm basis) runs on the lifted form alone
/// (LemkeSolver::setup(lifted, q)), so that an island at rest never forms M: forming it,
/// W = J M⁻¹Jᵀ and its copy into the solver were ~30% of a 500-body pile's step at rest.
class StewartTrinkleLcpSource {
 public:
  /// M given (kept by the caller, who keeps `lcp` alive): every attempt is set up with it.
  explicit StewartTrinkleLcpSource(const StewartTrinkleLcp& lcp) : given_(&lcp) {}
  /// q now (stewart_trinkle_q), M on first use; s is kept by reference.
  StewartTrinkleLcpSource(const ContactSystem& s, double dt);
  const Vector& q() const { return given_ ? given_->q : q_; }
  /// The LCP with M (formed now if it was not).
  const StewartTrinkleLcp& lcp();
  bool formed() const { return given_ != nullptr; }

 private:
  const StewartTrinkleLcp* given_ = nullptr;  // the caller's, or own_ once formed
  const ContactSystem* s_ = nullptr;
  double dt_ = 0.0;
  Vector q_;
  StewartTrinkleLcp own_;
};

/// Runs the attempts on `lcp` (= stewart_trinkle_lcp(s, ...)) into `out` (cleared first).
/// `settings` are the caller's (step 5; the earlier steps run them without Lemke's own
/// retries); `warm` (size nc + 3nf, or empty) is the previous basis. s supplies the
/// contact identities of the perturbation patterns (lcp_perturbation_pattern).
/// `skip_exact_cold`: step 3 (Lemke on q from the all-w basis) is not run when step 1b or 2
/// already gave a perturbed solution, which is then the answer (solved_inaccurate). For a
/// caller that knows step 3 failed on this LCP, or one a little different, before: the hard
/// loss re-solving a transition whose stored basis came from a perturbed answer, where step
/// 3 was 94% of the pivots (300-body pile, bench/results/learn_scene_hard_stored_bases.txt).
/// `warm_factorization`: step 1's solver factorizes the warm basis in it (solve_lcp_model),
/// or, with warm_from_regularized and accept_perturbed (step 1 then skipped), step 1c's first.
/// `accept_perturbed`: when step 1b solves q + δu, that answer is taken without its polish
/// on q and without steps 2–5 (source perturbed, solved_inaccurate), and step 3 is skipped
/// as with skip_exact_cold when step 2 gave a perturbed answer or step 1c a regularized
/// one (whose polish on (M, q) is then skipped as well): for a caller whose previous LCP
/// of this island ended perturbed or regularized after those had failed (a jammed pile at
/// rest; contact_step.hpp kLcpExactRetrySteps).
/// `warm_from_regularized`: `warm` is the basis of a regularized answer (M + εI) or of a
/// failed step's carried entries: step 1c runs first, before step 1b, instead of last.
/// `lifted`: lcp.M's lifted form (stewart_trinkle_lifted_form), given to every attempt's
/// LemkeSolver (the M + εI of step 4 with εI added to its H); nullptr: none.
void run_lcp_model_attempts(const ContactSystem& s, const StewartTrinkleLcp& lcp, const LemkeSettings& settings,
                            const std::vector<bool>& warm, LcpModelAttempts& out, bool skip_exact_cold = false,
                            const std::shared_ptr<LemkeSharedFactorization>& warm_factorization = {},
                            bool accept_perturbed = false, const LcpLiftedForm* lifted = nullptr,
                            bool warm_from_regularized = false);
/// The same on an LCP whose M may be formed on first use (StewartTrinkleLcpSource): with a
/// lifted form, step 1 then does not form it, and the later steps do.
void run_lcp_model_attempts(const ContactSystem& s, StewartTrinkleLcpSource& lcp, const LemkeSettings& settings,
                            const std::vector<bool>& warm, LcpModelAttempts& out, bool skip_exact_cold = false,
                            const std::shared_ptr<LemkeSharedFactorization>& warm_factorization = {},
                            bool accept_perturbed = false, const LcpLiftedForm* lifted = nullptr,
                            bool warm_from_regularized = false);

/// Takes back, in the warm basis `warm` (z_basic of the LCP z = [λn, β⁺, β⁻, γ] of s, size
/// n = nc + 3nf), the contacts that a crash path ending on a ray touched: every contact
/// whose rows a pivot of `trace` (LemkeSolver::set_pivot_trace numbering: w_i = i,
/// z_j = n + j, z₀ = 2n; pairs entering, leaving) exchanged, and the contact of the
/// variable that was to enter next (the complement of the last one to leave), the one
/// whose column has no positive entry. `level` (size nc, zeros at first) escalates per
/// contact: at 1 its friction variables β⁺, β⁻, γ become nonbasic (their w basic: the
/// contact's friction state unknown), at 2 its λn too (the contact as if new). Returns how
/// many contacts went up a level (0: nothing left to take back). Throws InputError on
/// inconsistent sizes.
Index reset_warm_contacts_on_ray(const ContactSystem& s, const std::vector<Index>& trace,
                                 std::vector<signed char>& level, std::vector<bool>& warm);

/// max_i |min(z_i, (M z + q)_i)| on the unperturbed LCP, 0 for an empty one.
double stewart_trinkle_residual(const StewartTrinkleLcp& lcp, const Vector& z);

}  // namespace lcprelax
