// The dual-form relaxed loss of one island (learn/step_loss_relaxed_dual.hpp):
// (The former check (1) against the polygon's own dense relaxed loss went with that loss:
// the polygon now uses the scene path's lifted relaxed loss, polygon_objective.hpp.)
// (2) central differences of ℓ against every entry of the cotangent (Jn, Jt on their
//     patterns, φ, μ, M⁻¹, v*), both scalings, on a box and two stacked boxes (every entry)
//     and on an 80-contact island of a 20-body learning pile (every 24th entry of each
//     kind; LCPRELAX_FULL_FD=1 checks all), relative error ≤ 1e-5 away from kinks (h and
//     h/2 compared);
// (3) bias: at the true data (target = the lcp model's own v⁺) the dual loss of both
//     scalings against the lifted relaxed_step_loss on the same islands, also at μ ± 25%,
//     with the shift δ chosen (printed).
#include <lcprelax/core/errors.hpp>
#include <lcprelax/learn/scene_dataset.hpp>
#include <lcprelax/learn/step_loss_relaxed.hpp>
#include <lcprelax/learn/step_loss_relaxed_dual.hpp>
#include <lcprelax/lcp/lemke.hpp>
#include <lcprelax/models/simulator.hpp>
#include <lcprelax/scenes/pile_scene.hpp>


#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <functional>
#include <random>

namespace lcprelax::learn {
namespace {

constexpr double kDt = 1e-2;

RelaxedDualStepLossSettings tight(RelaxedDualScaling scaling = RelaxedDualScaling::energy) {
  RelaxedDualStepLossSettings st;
  st.scaling = scaling;
  st.qp.eps_abs = 1e-12;
  return st;
}

ContactSystem largest_island(const World& world, const SimulatorSettings& settings,
                             const std::vector<Vec3>& applied = {}) {
  const StepContacts sc = find_step_contacts(world, settings, applied);
  std::size_t best = 0;
  for (std::size_t i = 1; i < sc.islands.size(); ++i)
    if (sc.islands[i].contacts.size() > sc.islands[best].contacts.size()) best = i;
  EXPECT_FALSE(sc.islands.empty());
  return assemble_contact_system(world, sc.contacts, sc.islands[best], settings.dt, applied);
}

ContactSystem box_stack(int boxes, double mu) {
  const Scene scene = make_box_stack_scene(boxes, 0.2, mu);
  return largest_island(scene.world, scene.settings);
}

// The largest island of the last transition's state of a 20-body learning pile.
const ContactSystem& pile_island() {
  static const ContactSystem s = [] {
    LearningPileOptions po;
    po.bodies = 20;
    po.classes = 4;
    SceneDatasetSettings ds;
    ds.steps = 90;
    ds.drop_without_contact = false;
    const SceneDataset data = generate_scene_dataset(make_learning_pile(po), ds);
    World world = data.scene.world;
    const SceneTransition& t = data.transitions.back();
    for (std::size_t b = 0; b < world.bodies.size(); ++b) {
      world.bodies[b].pose = t.pose[b];
      world.bodies[b].velocity = t.velocity[b];
    }
    return largest_island(world, data.scene.settings, t.applied);
  }();
  return s;
}

Vector lcp_prediction(const ContactSystem& s) {
  const ContactSolution sol = solve_lcp_model(s, kDt, LemkeSettings{});
  EXPECT_TRUE(has_solution(sol.status)) << sol.message;
  return sol.v_next;
}

Vector noisy_target(const ContactSystem& s, std::uint64_t seed, double size) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector t = lcp_prediction(s);
  for (Index k = 0; k < t.size(); ++k) t(k) += size * u(rng);
  return t;
}

// fn(entry of s, the cotangent's entry, kind) for every data entry.
void for_each_entry(ContactSystem& s, const ContactSystemCotangent& g,
                    const std::function<void(double&, double, const char*)>& fn) {
  for (Index j = 0; j < s.Jn.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jn, j); it; ++it) fn(it.valueRef(), g.Jn.coeff(it.row(), j), "Jn");
  for (Index j = 0; j < s.Jt.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(s.Jt, j); it; ++it) fn(it.valueRef(), g.Jt.coeff(it.row(), j), "Jt");
  for (Index c = 0; c < s.phi.size(); ++c) fn(s.phi(c), g.phi(c), "phi");
  for (Index f = 0; f < s.mu.size(); ++f) fn(s.mu(f), g.mu(f), "mu");
  for (Index k = 0; k < s.minv.size(); ++k) fn(s.minv(k), g.minv(k), "minv");
  for (Index k = 0; k < s.v_star.size(); ++k) fn(s.v_star(k), g.v_star(k), "v_star");
}

// Central differences at h against every cotangent entry; where they disagree, again at
// h/2: a kink (active set or shift exponent changing within ±h) shows as fd(h) ≠ fd(h/2)
// beyond the O(h²) truncation, and is counted, not failed (at most 5% of the entries).
// `stride` > 1: per kind, every stride-th entry only (the full check is slow on large
// islands; LCPRELAX_FULL_FD=1 in the environment checks every entry).
void check_gradient(ContactSystem s, const Vector& target, const char* name,
                    RelaxedDualScaling scaling = RelaxedDualScaling::energy, int stride = 1) {
  if (std::getenv("LCPRELAX_FULL_FD")) stride = 1;
  RelaxedDualStepLossWorkspace ws(tight(scaling));
  const StepLossResult r = ws.evaluate(s, target, kDt);
  ASSERT_EQ(r.status, ContactStatus::solved) << r.message;
  RelaxedDualStepLossWorkspace probe(tight(scaling));
  double gmax = 0.0;
  for_each_entry(s, r.grad, [&](double&, double g, const char*) { gmax = std::max(gmax, std::abs(g)); });
  // Error of an entry: |fd − g| / (max(|fd|, |g|) + floor), floor = 1e-6·max|g| + 1e-8(1 + ℓ)/h:
  // the interior point (eps 1e-12) gives ℓ to about 1e-13(1 + ℓ), so a difference quotient
  // carries that roundoff / h, and 1e-5·floor is that level.
  double worst = 0.0;
  int entries = 0, kinks = 0, seen = 0;
  std::string last_kind;
  auto fd_at = [&](double& x, double h) {
    const double x0 = x;
    x = x0 + h;
    const StepLossResult rp = probe.evaluate(s, target, kDt);
    x = x0 - h;
    const StepLossResult rm = probe.evaluate(s, target, kDt);
    x = x0;
    EXPECT_TRUE(has_solution(rp.status) && has_solution(rm.status));
    EXPECT_EQ(probe.last().shift, ws.last().shift);
    return (rp.loss - rm.loss) / (2 * h);
  };
  for_each_entry(s, r.grad, [&](double& x, double g, const char* kind) {
    if (last_kind != kind) last_kind = kind, seen = 0;
    if (seen++ % stride != 0) return;
    ++entries;
    // φ enters as φ/Δt: a step of 1e-7 m (1e-5 m/s in q).
    const double h = std::string(kind) == "phi" ? 1e-7 : 1e-5 * std::max(1.0, std::abs(x));
    const double floor = 1e-6 * gmax + 1e-8 * (1.0 + std::abs(r.loss)) / h;
    const double fd = fd_at(x, h);
    const double err = std::abs(fd - g) / (std::max(std::abs(fd), std::abs(g)) + floor);
    if (err <= 1e-5) {
      worst = std::max(worst, err);
      return;
    }
    const double fd2 = fd_at(x, 0.5 * h);
    const double err2 = std::abs(fd2 - g) / (std::max(std::abs(fd2), std::abs(g)) + floor);
    const double jump = std::abs(fd - fd2) / (std::max(std::abs(fd), std::abs(fd2)) + floor);
    if (jump > 1e-5) {
      ++kinks;
      std::printf("  %s: kink at a %s entry (fd(h) %.9e, fd(h/2) %.9e, cotangent %.9e)\n", name, kind, fd, fd2, g);
      return;
    }
    worst = std::max(worst, err2);
    EXPECT_LE(err2, 1e-5) << name << " " << kind << " value " << x << ": fd " << fd2 << " vs " << g;
  });
  EXPECT_LE(kinks, entries / 20) << name;
  std::printf("%s (%s): %d entries, worst relative error %.2e, %d on kinks, shift %.1e, loss %.6e\n", name, to_string(scaling), entries, worst,
              kinks, ws.last().shift, r.loss);
}

// (2) Central differences.
TEST(StepLossRelaxedDual, TwoStackedBoxesMatchesCentralDifferences) {
  ContactSystem s = box_stack(2, 0.3);
  ASSERT_EQ(s.bodies.size(), 2u);
  s.v_star << 0.2, -0.2, 0.1, 1.0, -0.4, -0.3;
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-3 * (c + 1);
  check_gradient(s, noisy_target(s, 3, 0.1), "two boxes");
  check_gradient(s, noisy_target(s, 3, 0.1), "two boxes", RelaxedDualScaling::velocity);
}

TEST(StepLossRelaxedDual, BoxOnGroundMatchesCentralDifferences) {
  ContactSystem s = box_stack(1, 0.5);
  s.v_star << 0.8, -0.3, 0.4;
  s.phi << 0.002, -0.001;
  check_gradient(s, noisy_target(s, 1, 0.1), "box, sliding");
  check_gradient(s, noisy_target(s, 1, 0.1), "box, sliding", RelaxedDualScaling::velocity);
  s.v_star << 0.05, -0.1, 0.0;  // nearly resting
  check_gradient(s, noisy_target(s, 2, 0.1), "box, nearly resting");
}

TEST(StepLossRelaxedDual, PileIslandMatchesCentralDifferences) {
  ContactSystem s = pile_island();
  ASSERT_GE(s.num_contacts(), 60);
  std::printf("pile island: %zu bodies, %d contacts, %d friction rows\n", s.bodies.size(),
              static_cast<int>(s.num_contacts()), static_cast<int>(s.num_friction()));
  // Gaps moved away from the kink of max(φ, 0) at 0 (a settled pile has φ ≈ 0).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Index c = 0; c < s.num_contacts(); ++c) s.phi(c) = 1e-4 * (1.5 + u(rng));
  // Every 24th entry of each kind (about 50 entries; LCPRELAX_FULL_FD=1: all of them).
  check_gradient(s, noisy_target(s, 4, 0.05), "pile island", RelaxedDualScaling::energy, 24);
  check_gradient(s, noisy_target(s, 4, 0.05), "pile island", RelaxedDualScaling::velocity, 24);
}

// (3) Bias at the true data: the target is the lcp model's own v⁺.
struct Losses {
  double loss, dmu, shift;
};

Losses dual_at(const ContactSystem& s, const Vector& target, RelaxedDualScaling scaling) {
  RelaxedDualStepLossSettings st;
  st.scaling = scaling;
  RelaxedDualStepLossWorkspace ws(st);
  const StepLossResult r = ws.evaluate(s, target, kDt);
  EXPECT_TRUE(has_solution(r.status)) << r.message;
  return {r.loss, r.grad.mu.sum(), ws.last().shift};
}

Losses lifted_at(const ContactSystem& s, const Vector& target) {
  RelaxedStepLossWorkspace ws;
  const StepLossResult r = ws.evaluate(s, target, kDt);
  EXPECT_TRUE(has_solution(r.status)) << r.message;
  return {r.loss, r.grad.mu.sum(), ws.shifts().size() > 0 ? ws.shifts().maxCoeff() : 0.0};
}

ContactSystem scaled_mu(ContactSystem s, double factor) {
  s.mu *= factor;
  return s;
}

TEST(StepLossRelaxedDual, SmallBiasAtTheTruth) {
  ContactSystem box = box_stack(1, 0.5);
  box.v_star << 0.8, -0.3, 0.4;
  box.phi << 0.002, 0.001;
  const std::pair<const char*, ContactSystem> islands[] = {
      {"box sliding", box}, {"two boxes resting", box_stack(2, 0.3)}, {"pile island", pile_island()}};
  for (const auto& [name, s] : islands) {
    const Vector truth = lcp_prediction(s);
    const Losses l = lifted_at(s, truth), lp = lifted_at(scaled_mu(s, 1.25), truth),
                 lm = lifted_at(scaled_mu(s, 0.75), truth);
    std::printf("%s (%d contacts, ‖v̄‖² %.3e): lifted ℓ %.3e (max b_f %.2e, Σ∂ℓ/∂μ %.3e; μ·1.25: %.3e, μ·0.75: %.3e)\n",
                name, static_cast<int>(s.num_contacts()), truth.squaredNorm(), l.loss, l.shift, l.dmu, lp.loss, lm.loss);
    for (RelaxedDualScaling sc : {RelaxedDualScaling::energy, RelaxedDualScaling::velocity}) {
      const Losses d = dual_at(s, truth, sc), dp = dual_at(scaled_mu(s, 1.25), truth, sc),
                   dm = dual_at(scaled_mu(s, 0.75), truth, sc);
      std::printf("    dual %-8s ℓ %.3e (δ %.0e, Σ∂ℓ/∂μ %.3e; μ·1.25: %.3e, μ·0.75: %.3e)\n", to_string(sc), d.loss,
                  d.shift, d.dmu, dp.loss, dm.loss);
      if (sc == RelaxedDualScaling::velocity) {
        // Unit-consistent rows: the loss at the truth is below the lifted one's. Along μ the
        // truth is the better fit for the sliding box only: the resting boxes do not see μ
        // (equal losses), and on the pile island the shift δ = 0.1, which penalizes the
        // sliding speeds γ, makes μ·1.25 fit slightly better (a bias towards sticking;
        // reported, not hidden).
        EXPECT_LE(d.loss, l.loss) << name;
        if (std::string(name) == "box sliding") {
          EXPECT_LT(d.loss, std::min(dp.loss, dm.loss)) << name;
        }
      }
    }
  }
}

TEST(StepLossRelaxedDual, SettingsAndInputAreValidated) {
  RelaxedDualStepLossSettings st;
  EXPECT_TRUE(st.validation_error().empty());
  EXPECT_EQ(st.relaxed.nonconvex, NonconvexPolicy::shift);
  st.relaxed.a1 = 0.0;
  EXPECT_NE(st.validation_error().find("a1"), std::string::npos);
  EXPECT_THROW(RelaxedDualStepLossWorkspace{st}, InputError);
  st = RelaxedDualStepLossSettings();
  st.relaxed.max_dissipation = MaxDissipation::qp;
  EXPECT_NE(st.validation_error().find("max_dissipation"), std::string::npos);
  ContactSystem s = box_stack(1, 0.3);
  EXPECT_THROW(relaxed_dual_step_loss(s, Vector::Zero(4), kDt), InputError);
  EXPECT_THROW(relaxed_dual_step_loss(s, Vector::Zero(3), 0.0), InputError);
  s.minv(2) = -1.0;
  EXPECT_THROW(relaxed_dual_step_loss(s, Vector::Zero(3), kDt), InputError);
}

TEST(StepLossRelaxedDual, FailedSolveIsReported) {
  const ContactSystem s = box_stack(2, 0.3);
  RelaxedDualStepLossSettings st;
  st.qp.max_iter = 1;
  st.qp.polish = false;  // polishing can finish a 1-iteration run (QpSettings::polish)
  const StepLossResult r = relaxed_dual_step_loss(s, noisy_target(s, 7, 0.1), kDt, st);
  EXPECT_EQ(r.status, ContactStatus::failed);
  EXPECT_TRUE(std::isnan(r.loss));
  EXPECT_FALSE(r.message.empty());
}

}  // namespace
}  // namespace lcprelax::learn
