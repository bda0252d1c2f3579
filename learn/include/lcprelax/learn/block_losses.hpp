#pragma once
// Per-sample losses of the 1-D frictional block (models/block1d.hpp) and their gradients
// ∂ℓ/∂θ, as learn::Objective (trainer.hpp), for the three methods (hard, relaxed, convex)
// of Parmar, Halm & Posa, "Fundamental Challenges in Deep Learning for Stiff Contact
// Dynamics", IROS 2021. Transition i = (v, u, v̄) (learn/block_dataset.hpp).
//
// Parameters θ (by name in the ParameterSet; any other name gets a zero gradient):
//   "mu"   friction coefficient (required);
//   "mass" m, kg, and "mg" the weight impulse, N·s (optional; when absent the dataset's
//          fixed values are used). μ and mg enter only as the product μ·mg.
// block_parameters() makes the usual set: all log-transformed, mass and mg with
// learn = false unless asked.
//
// hard:    ℓ = (v⁺(λ) − v̄)², z = (λ⁺, λ⁻, γ) from Lemke on the block's LCP, λ = λ⁺ − λ⁻;
//          ∂ℓ/∂z = 2(v⁺ − v̄)(1/m, −1/m, 0) → LemkeSolver::backward → ∂ℓ/∂(M, q) →
//          θ through ∂q₃/∂μ = mg, ∂q₃/∂mg = μ, ∂M/∂m, ∂q/∂m (+ the explicit ∂v⁺/∂m).
//          Where the prediction sticks (|v*| < μmg/m) the slack w₃ = μmg − |λ| > 0 is basic,
//          so ∂ℓ/∂q₃ = 0 and ∂ℓ/∂μ is exactly 0.0 — whatever the data say. A too-high μ prior
//          that makes every sample stick therefore gets no gradient at all (the seeds'
//          point; tests/learn_block_zero_gradient_test.cpp).
// relaxed: ℓ = c of learn/relaxed_lcp.hpp with M, q of the LCP, P = (1/m, −1/m, 0),
//          p = v* = v + u/m, x̄ = v̄, and for max dissipation E = (1, 1, 0), e = μ·mg;
//          ∂ℓ/∂θ by the envelope theorem, chained through ∂(M, q, P, p, e)/∂θ.
// convex:  the convex block model with the L2 penalty ρ (models/block1d.hpp),
//          min ½(1+ρ)λ²/m + λv* s.t. |λ| ≤ μmg, by the interior point; ℓ = (v⁺(λ) − v̄)²,
//          gradient through QpSolver::backward (∂ℓ/∂bounds → μ, mg; ∂ℓ/∂(P, q) → m).
//          The bound is inactive where the prediction sticks, so this loss has the same
//          zero gradient in μ there as the hard one.
//
// Workspaces: one solver per thread (prepare() sizes the list; each is made by the thread
// that uses it, on its first sample, so that its memory comes from that thread's malloc
// arena and never shares a cache line with another thread's solver), so symbolic analyses
// are done once per thread; per-sample warm starts (Lemke basis; QP solution only if asked,
// see BlockLossSettings) from the previous evaluation of the same sample. Evaluation of a
// sample does not depend on which thread runs it, so 1 and N threads give
// bitwise-identical results (batch.hpp). The warm starts are saved in training checkpoints
// (Objective::save_state, checkpoint.hpp), so a resumed run continues bit for bit.
#include <lcprelax/kkt/qp_settings.hpp>
#include <lcprelax/lcp/lcp_types.hpp>
#include <lcprelax/learn/block_dataset.hpp>
#include <lcprelax/learn/relaxed_lcp.hpp>
#include <lcprelax/learn/trainer.hpp>

#include <memory>
#include <string>
#include <vector>

namespace lcprelax::learn {

enum class BlockMethod { hard, relaxed, convex };
const char* to_string(BlockMethod m);
/// "hard", "relaxed" or "convex"; throws InputError otherwise.
BlockMethod parse_block_method(const std::string& s);

struct BlockLossSettings {
  RelaxedLcpSettings relaxed;  ///< settings and weights of the relaxed loss
  double convex_rho = 0.0;     ///< ρ of the convex model (≥ 0; 0 = maximum dissipation)
  LemkeSettings lemke;         ///< hard
  QpSettings qp;               ///< relaxed and convex
  /// Per-sample warm starts: Lemke from the sample's last basis (hard), on by default; the
  /// interior point from the sample's last solution (relaxed, convex), off by default:
  /// warm-started QpSolver solves meet the tolerances but can end on iterates whose bound
  /// ratios s/z give adjoint gradients off by up to 1% (tests/learn_block_gradient_test
  /// with warm_start_qp on), against 1e-5 from a cold start.
  bool warm_start_lemke = true;
  bool warm_start_qp = false;
};

/// θ = {mu, mass, mg}, log-transformed, bounds [1e-8, 1e8]; mass and mg learned only if asked.
ParameterSet block_parameters(double mu, double mass, double mg, bool learn_mass = false, bool learn_mg = false);

/// Accumulated wall time of the three phases (summed over threads), seconds.
struct BlockLossTimings {
  double assembly = 0.0, solve = 0.0, backward = 0.0;
  long evaluations = 0;
};

class BlockObjective : public Objective {
 public:
  BlockObjective(const BlockDataset& data, const BlockLossSettings& settings);
  ~BlockObjective() override;
  Index num_samples() const override;
  void prepare(const ParameterSet& theta, int threads) override;
  BlockLossTimings timings() const;
  void reset_timings();
  const BlockDataset& data() const { return data_; }
  const BlockLossSettings& settings() const { return settings_; }
  virtual BlockMethod method() const = 0;

 protected:
  struct Theta {
    double mu = 0.0, mass = 1.0, mg = 1.0;
    Index i_mu = -1, i_mass = -1, i_mg = -1;
  };
  Theta read_theta(const ParameterSet& theta) const;
  /// ∂ℓ/∂θ in the ParameterSet's order from the partials with respect to μ, m and mg.
  static Vector gradient_vector(Index size, const Theta& t, double dmu, double dmass, double dmg);
  /// Workspace count; subclasses (re)build their per-thread solvers in make_workspaces().
  virtual void make_workspaces(int threads) = 0;
  BlockLossTimings& timing(int thread) { return timings_[static_cast<std::size_t>(thread)].t; }

  BlockDataset data_;
  BlockLossSettings settings_;
  /// One cache line per thread: the slots are written several times per sample, and
  /// adjacent unpadded slots would be shared between threads' caches (false sharing).
  struct alignas(64) ThreadTimings {
    BlockLossTimings t;
  };
  std::vector<ThreadTimings> timings_;
};

/// The objective of `method` on `data` (the data are copied). Throws InputError on invalid
/// settings (relaxed options, ρ, Lemke or QP settings).
std::unique_ptr<BlockObjective> make_block_objective(BlockMethod method, const BlockDataset& data,
                                                     const BlockLossSettings& settings = {});
std::unique_ptr<BlockObjective> make_block_hard_objective(const BlockDataset& data, const BlockLossSettings& settings);
std::unique_ptr<BlockObjective> make_block_relaxed_objective(const BlockDataset& data, const BlockLossSettings& settings);
std::unique_ptr<BlockObjective> make_block_convex_objective(const BlockDataset& data, const BlockLossSettings& settings);

}  // namespace lcprelax::learn
